# crashlink_target_defaults(<target>): warnings (errors in CI) and the release architecture.
function(crashlink_target_defaults target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow -Wconversion
    -Wno-sign-conversion -Wnon-virtual-dtor -Wold-style-cast -Wcast-align -Woverloaded-virtual)
  if(CRASHLINK_WERROR)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
  if(CRASHLINK_NATIVE_ARCH)
    target_compile_options(${target} PRIVATE $<$<CONFIG:Release>:-march=x86-64-v3>)
  endif()
  # std::sqrt without errno (nothing here reads errno after a math call): GCC then vectorises
  # loops with a square root instead of keeping a branch to the library for negative arguments
  # (the J2 shell's lane return, materials/plane_stress_update.h). The results are the same: a
  # square root is correctly rounded either way.
  target_compile_options(${target} PRIVATE -fno-math-errno)
endfunction()

# crashlink_library(<name> [DEPS ...]): one library per folder, alias crashlink::<name>,
# sources = every *.cpp in the calling folder (one concept per file, no list to keep in sync).
function(crashlink_library name)
  cmake_parse_arguments(ARG "" "" "DEPS;PUBLIC_DEPS" ${ARGN})
  file(GLOB srcs CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/*.cpp)
  if(NOT srcs)  # a header-only folder
    add_library(crashlink_${name} INTERFACE)
    add_library(crashlink::${name} ALIAS crashlink_${name})
    target_include_directories(crashlink_${name} INTERFACE ${PROJECT_SOURCE_DIR})
    target_link_libraries(crashlink_${name} INTERFACE ${ARG_PUBLIC_DEPS} ${ARG_DEPS})
    return()
  endif()
  add_library(crashlink_${name} STATIC ${srcs})
  add_library(crashlink::${name} ALIAS crashlink_${name})
  target_include_directories(crashlink_${name} PUBLIC ${PROJECT_SOURCE_DIR})
  target_link_libraries(crashlink_${name} PUBLIC ${ARG_PUBLIC_DEPS} PRIVATE ${ARG_DEPS})
  crashlink_target_defaults(crashlink_${name})
endfunction()
