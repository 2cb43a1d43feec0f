#!/usr/bin/python3
"""Every library's includes and its declared CMake dependencies agree (run by .ci/run).

Each `crashlink_library(NAME PUBLIC_DEPS ... DEPS ...)` builds the sources of its own folder
(cmake/CrashlinkWarnings.cmake). For each library:
  - a project header it includes (`#include "folder/file.h"`) belongs to the library of that
    folder, which must be the library itself, one it declares, or one that a declared library
    brings publicly (what CMake gives it: an include that compiles only because some other
    library happens to link it is refused);
  - a project library it declares must have a header included by it (no dependency kept for
    nothing);
  - an external package it declares (fmt, spdlog, yaml-cpp, Eigen, HDF5, CLI11, ZeroMQ) must be
    included by it, and an external header it includes must come from a package it declares or
    one of its declared libraries brings publicly.
Prints each disagreement as CMakeLists.txt path: library: what; exits 1 if there is one.
Usage: tools/check_cmake_deps.py [REPO_ROOT]
"""
import os
import re
import subprocess
import sys

LIBRARY = re.compile(r"crashlink_library\(\s*(\w+)(.*?)\)", re.S)
INCLUDE = re.compile(r'^[ \t]*#[ \t]*include[ \t]*[<"]([^">]+)[">]', re.M)
# External packages: the names a CMakeLists may link them by -> the include prefixes that show use.
EXTERNAL = [
    (("fmt::fmt",), ("fmt/",)),
    (("spdlog::spdlog",), ("spdlog/",)),
    (("yaml-cpp", "yaml-cpp::yaml-cpp"), ("yaml-cpp/",)),
    (("Eigen3::Eigen",), ("Eigen/",)),
    (("HDF5::HDF5", "hdf5::hdf5"), ("hdf5.h", "H5")),
    (("CLI11::CLI11",), ("CLI/",)),
    (("cppzmq", "cppzmq-static"), ("zmq.hpp", "zmq.h", "zmq_addon.hpp")),
]


def cmake_files(root):
    out = subprocess.run(["git", "ls-files", "*CMakeLists.txt"], cwd=root, check=True,
                         capture_output=True, text=True).stdout.split()
    return [f for f in out if not f.startswith(("tests/", "bench/", "apps/"))]


def parse_libraries(root):
    """name -> {folder, public, private, cmake} for every crashlink_library."""
    libs = {}
    for cm in cmake_files(root):
        text = open(os.path.join(root, cm), encoding="utf-8").read()
        text = re.sub(r"#.*", "", text)
        for m in LIBRARY.finditer(text):
            name, args = m.group(1), m.group(2).split()
            public, private, mode = [], [], None
            for a in args:
                if a in ("PUBLIC_DEPS", "DEPS"):
                    mode = a
                elif mode == "PUBLIC_DEPS":
                    public.append(a)
                elif mode == "DEPS":
                    private.append(a)
            libs[name] = {"folder": os.path.dirname(cm), "public": public, "private": private,
                          "cmake": cm}
    # The generated protocol library (proto/CMakeLists.txt, add_library by hand).
    libs.setdefault("proto", {"folder": "proto", "public": ["protobuf"], "private": [],
                              "cmake": "proto/CMakeLists.txt"})
    return libs


def sources(root, folder, library_folders):
    """The library's files: its folder and the subfolders that are no library of their own."""
    out = []
    for d, subdirs, files in os.walk(os.path.join(root, folder)):
        rel = os.path.relpath(d, root)
        if rel != folder and rel in library_folders:
            subdirs[:] = []
            continue
        out += [os.path.join(d, f) for f in files if f.endswith((".cpp", ".h"))]
    return sorted(out)


def owner(include, folders):
    """The library whose folder holds this project header, or None for an external one."""
    folder = os.path.dirname(include)
    return folders.get(folder)


def brought_publicly(lib, libs):
    """What `lib` gives its users: the project libraries (itself and its public dependencies',
    transitively) and the external packages among their public dependencies."""
    projects, packages, pending = set(), set(), [lib]
    while pending:
        cur = pending.pop()
        if cur in projects or cur not in libs:
            continue
        projects.add(cur)
        for d in libs[cur]["public"]:
            if d.startswith("crashlink::"):
                pending.append(d.split("::", 1)[1])
            else:
                packages.add(d)
    return projects, packages


def check(root):
    libs = parse_libraries(root)
    folders = {v["folder"]: k for k, v in libs.items()}
    problems = []
    for name, lib in sorted(libs.items()):
        if name == "proto":
            continue
        declared = lib["public"] + lib["private"]
        declared_libs = {d.split("::", 1)[1] for d in declared if d.startswith("crashlink::")}
        declared_ext = {d for d in declared if not d.startswith("crashlink::")}
        reachable, brought = set(), set()
        for d in declared_libs:
            projects, packages = brought_publicly(d, libs)
            reachable |= projects
            brought |= packages
        used_libs, used_ext_prefixes = set(), set()
        for path in sources(root, lib["folder"], folders):
            text = open(path, encoding="utf-8").read()
            rel = os.path.relpath(path, root)
            for m in INCLUDE.finditer(text):
                inc = m.group(1)
                line = text.count("\n", 0, m.start()) + 1
                lib_of = owner(inc, folders)
                if lib_of is not None:
                    if lib_of == name:
                        continue
                    used_libs.add(lib_of)
                    if lib_of not in reachable:
                        problems.append(f"{rel}:{line}: library {name} includes {inc} of "
                                        f"crashlink::{lib_of}, which {lib['cmake']} does not "
                                        f"declare; add it to DEPS (or PUBLIC_DEPS if a header "
                                        f"of {name} needs it)")
                elif "/" in inc or inc.endswith((".h", ".hpp")):
                    used_ext_prefixes.add(inc)
        for d in sorted(declared_libs - used_libs):
            problems.append(f"{lib['cmake']}: library {name} declares crashlink::{d} but "
                            f"includes none of its headers; drop it")
        for names, prefixes in EXTERNAL:
            used = any(i.startswith(prefixes) for i in used_ext_prefixes)
            have = set(names) & declared_ext
            for ext in sorted(have):
                if not used:
                    problems.append(f"{lib['cmake']}: library {name} declares {ext} but includes "
                                    f"none of its headers ({', '.join(prefixes)}); drop it")
            if used and not have and not set(names) & brought:
                problems.append(f"{lib['cmake']}: library {name} includes {prefixes[0]}... "
                                f"but declares no {names[0]}; add it to DEPS")
    return problems


def main():
    root = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "..")
    root = os.path.abspath(root)
    problems = check(root)
    for p in problems:
        print(p)
    if problems:
        print(f"check_cmake_deps: {len(problems)} disagreement(s) between includes and CMake "
              f"dependencies")
        return 1
    print(f"check_cmake_deps: {len(parse_libraries(root))} libraries, includes and declared "
          f"dependencies agree")
    return 0


if __name__ == "__main__":
    sys.exit(main())
