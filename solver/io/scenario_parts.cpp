// The `parts` section and its mesh generators (docs/scenario-format.md).
#include <array>

#include "core/errors.h"
#include "solver/io/scenario_sections.h"
#include "solver/model/mesh_generators.h"
#include "solver/model/node_merging.h"

namespace crashlink::io::detail {

namespace {

using model::ElementKind;

std::array<int, 3> read_divisions3(const YamlNode& d) {
  const auto all = d.items("3 integers [nx, ny, nz]");
  if (all.size() != 3) d.fail(fmt::format("expected 3 integers [nx, ny, nz], got {}", all.size()));
  return {all[0].positive_int(), all[1].positive_int(), all[2].positive_int()};
}

template <std::size_t N>
std::array<double, N> read_sizes(const YamlNode& s, const char* form) {
  const auto all = s.items(form);
  if (all.size() != N)
    s.fail(fmt::format("expected {} lengths {} in m, got {}", N, form, all.size()));
  std::array<double, N> out{};
  for (std::size_t i = 0; i < N; ++i) out[i] = all[i].positive();
  return out;
}

/// Most elements a scenario may generate in all: ten times the largest benchmark (1e6 elements at
/// ~70 ns per element per cycle is 0.07 s per cycle on one core, hours for a crash run), low
/// enough that a typo in `divisions` fails at its line instead of exhausting memory (found by the
/// scenario fuzz target, docs/fuzzing.md).
constexpr double kMaxElements = 1.0e6;

/// Fails at `divisions` when `elements` more would take the model past kMaxElements.
void check_element_count(const model::Model& m, const YamlNode& divisions, double elements) {
  const double total = static_cast<double>(m.element_count()) + elements;
  if (total > kMaxElements)
    divisions.fail(
        fmt::format("{:.4g} elements (model total {:.4g}), more than the {:.0f} a "
                    "scenario may hold; use fewer divisions",
                    elements, total, kMaxElements));
}

int read_axis(const YamlNode& a) {
  const std::string s = a.choice({"x", "y", "z"});
  return s == "x" ? 0 : s == "y" ? 1 : 2;
}

int mesh_box(model::Model& m, model::Part part, const YamlNode& mesh) {
  mesh.expect_keys({"generator", "origin", "size", "divisions"});
  model::BoxMesh box;
  box.origin_m = mesh.vec3_or("origin", {0.0, 0.0, 0.0});
  const auto size = read_sizes<3>(mesh.required("size", "[lx, ly, lz] in m"), "[lx, ly, lz]");
  box.size_m = {size[0], size[1], size[2]};
  const auto d = mesh.required("divisions", "[nx, ny, nz] elements per edge");
  box.divisions = read_divisions3(d);
  check_element_count(m, d,
                      static_cast<double>(box.divisions[0]) * box.divisions[1] * box.divisions[2]);
  return model::generate_box(m, std::move(part), box);
}

int mesh_bar(model::Model& m, model::Part part, const YamlNode& mesh) {
  mesh.expect_keys(
      {"generator", "origin", "axis", "length", "cross_section", "divisions", "cross_divisions"});
  model::BarMesh bar;
  bar.origin_m = mesh.vec3_or("origin", {0.0, 0.0, 0.0});
  if (auto a = mesh.optional("axis")) bar.axis = read_axis(*a);
  bar.length_m = mesh.required("length", "bar length in m").positive();
  bar.cross_section_m =
      read_sizes<2>(mesh.required("cross_section", "[a, b] side lengths in m"), "[a, b]");
  const auto d = mesh.required("divisions", "number of hexahedra along the bar");
  bar.elements = d.positive_int();
  if (auto cd = mesh.optional("cross_divisions")) {
    const auto all = cd->items("2 integers [na, nb]");
    if (all.size() != 2) cd->fail(fmt::format("expected 2 integers [na, nb], got {}", all.size()));
    bar.cross_divisions = {all[0].positive_int(), all[1].positive_int()};
  }
  check_element_count(
      m, d, static_cast<double>(bar.elements) * bar.cross_divisions[0] * bar.cross_divisions[1]);
  return model::generate_bar(m, std::move(part), bar);
}

int mesh_plate(model::Model& m, model::Part part, const YamlNode& mesh) {
  mesh.expect_keys({"generator", "origin", "size", "normal", "edges", "divisions", "distort"});
  model::PlateMesh plate;
  plate.origin_m = mesh.vec3_or("origin", {0.0, 0.0, 0.0});
  if (auto edges = mesh.optional("edges")) {
    for (const char* k : {"size", "normal"})
      if (auto v = mesh.optional(k))
        v->fail("give either 'edges' [[e1], [e2]] or 'size' [l1, l2] with 'normal', not both");
    const auto e = edges->items("two edge vectors [[x, y, z], [x, y, z]]");
    if (e.size() != 2) edges->fail(fmt::format("expected 2 edge vectors, got {}", e.size()));
    plate.edge1_m = e[0].vec3();
    plate.edge2_m = e[1].vec3();
    if (!(norm(cross(plate.edge1_m, plate.edge2_m)) > 1e-12 * dot(plate.edge1_m, plate.edge1_m)))
      edges->fail("the two edges are zero or parallel; give two independent vectors");
  } else {
    const auto size = read_sizes<2>(mesh.required("size", "[l1, l2] in m"), "[l1, l2]");
    const int normal = mesh.has("normal") ? read_axis(mesh.required("normal")) : 2;
    // In-plane axes (normal+1, normal+2) cyclic, so that e1 x e2 = +normal.
    plate.edge1_m[static_cast<std::size_t>((normal + 1) % 3)] = size[0];
    plate.edge2_m[static_cast<std::size_t>((normal + 2) % 3)] = size[1];
  }
  const auto d = mesh.required("divisions", "[n1, n2] elements per edge");
  const auto all = d.items("2 integers [n1, n2]");
  if (all.size() != 2) d.fail(fmt::format("expected 2 integers [n1, n2], got {}", all.size()));
  plate.divisions = {all[0].positive_int(), all[1].positive_int()};
  check_element_count(m, d, static_cast<double>(plate.divisions[0]) * plate.divisions[1]);
  if (auto dist = mesh.optional("distort")) {
    plate.distort = dist->non_negative();
    if (plate.distort > 0.4)
      dist->fail(fmt::format("{} is above 0.4 element sizes: quads would fold; use 0.1-0.3",
                             plate.distort));
  }
  return model::generate_plate(m, std::move(part), plate);
}

int mesh_sphere(model::Model& m, model::Part part, const YamlNode& mesh) {
  mesh.expect_keys({"generator", "centre", "radius", "divisions"});
  model::SphereMesh s;
  s.centre_m = mesh.required("centre", "[x, y, z] in m").vec3();
  s.radius_m = mesh.required("radius", "m").positive();
  const auto d = mesh.required("divisions", "elements per cube edge, 6 n^2 quads");
  s.divisions = d.positive_int();
  check_element_count(m, d, 6.0 * s.divisions * static_cast<double>(s.divisions));
  return model::generate_sphere(m, std::move(part), s);
}

}  // namespace

void read_parts(const YamlNode& section, ScenarioBuild& b) {
  const auto all = section.entries("parts (name: {material, mesh, ...})");
  if (all.empty()) section.fail("no part defined; add e.g. 'plate: {material: steel, mesh: ...}'");
  for (const auto& [name, p] : all) {
    p.expect_keys({"material", "element", "thickness", "integration_points", "hourglass",
                   "damping_ratio", "mesh", "merge_nodes", "merge_tolerance"});
    model::Part part;
    part.name = name;
    const auto mat = p.required("material", "a name from 'materials'");
    const auto it = b.material_index.find(mat.text());
    if (it == b.material_index.end())
      mat.fail("unknown material '" + mat.text() + "';" +
               did_you_mean(mat.text(), b.material_names()) +
               " define it under 'materials' (defined: " + quoted_list(b.material_names()) + ")");
    part.material = it->second;

    const auto mesh = p.required("mesh", "{generator: box|plate|bar|sphere, ...}");
    const std::string gen = mesh.required("generator", "box, plate, bar or sphere")
                                .choice({"box", "plate", "bar", "sphere"});
    const ElementKind natural =
        (gen == "box" || gen == "bar") ? ElementKind::Hex8 : ElementKind::Shell4;
    part.kind = natural;
    if (auto e = p.optional("element")) {
      part.kind = e->choice({"hex8", "shell4"}) == "hex8" ? ElementKind::Hex8 : ElementKind::Shell4;
      if (part.kind != natural)
        e->fail(fmt::format(
            "the '{}' generator builds {} elements; use element: {}{}", gen,
            natural == ElementKind::Hex8 ? "hex8" : "shell4",
            natural == ElementKind::Hex8 ? "hex8" : "shell4",
            gen == "sphere"
                ? " (the sphere generator meshes the surface only: a rigid headform needs no "
                  "volume mesh)"
                : ""));
    }
    const bool shell = part.kind == ElementKind::Shell4;
    if (shell) {
      part.thickness_m = p.required("thickness", "shell thickness in m, e.g. 0.001").positive();
      if (auto ip = p.optional("integration_points")) {
        part.through_thickness_points = ip->positive_int();
        if (part.through_thickness_points < 3 || part.through_thickness_points > 9)
          ip->fail(fmt::format("{} points through the thickness; use 3 to 9 (5 for plasticity)",
                               part.through_thickness_points));
      }
    } else {
      for (const char* k : {"thickness", "integration_points"})
        if (auto v = p.optional(k)) v->fail("applies to shell4 parts only; remove it");
    }
    if (auto hg = p.optional("hourglass")) {
      part.hourglass_coefficient = hg->non_negative();
      if (part.hourglass_coefficient > 0.3)
        hg->fail(fmt::format("{} is above 0.3; use 0.05-0.15 (default 0.1)",
                             part.hourglass_coefficient));
    }
    if (auto xi = p.optional("damping_ratio")) {
      part.damping_ratio = xi->non_negative();
      if (part.damping_ratio > 0.5)
        xi->fail(fmt::format(
            "{} is above 0.5; give the fraction of critical damping at the element's highest "
            "frequency, e.g. 0.05 (0: none)",
            part.damping_ratio));
      if (part.damping_ratio > 0.0 &&
          b.model.materials[static_cast<std::size_t>(part.material)].kind ==
              materials::MaterialKind::Rigid)
        xi->fail(
            fmt::format("has no effect on a part of rigid material '{}'; remove it", mat.text()));
    }
    const bool merge = p.boolean_or("merge_nodes", false);
    double tolerance_m = 1e-6;
    if (auto t = p.optional("merge_tolerance")) {
      if (!merge) t->fail("has no effect without 'merge_nodes: true'; add it or remove this key");
      tolerance_m = t->positive();
    }

    const std::size_t first_new = b.model.nodes.count();
    try {
      if (gen == "box")
        mesh_box(b.model, std::move(part), mesh);
      else if (gen == "bar")
        mesh_bar(b.model, std::move(part), mesh);
      else if (gen == "plate")
        mesh_plate(b.model, std::move(part), mesh);
      else
        mesh_sphere(b.model, std::move(part), mesh);
      if (merge) {
        if (model::merge_coincident_nodes(b.model, first_new, tolerance_m) == 0)
          p.required("merge_nodes")
              .fail(fmt::format("no node of this part lies within {} m of an earlier part's node; "
                                "check the positions or raise merge_tolerance",
                                tolerance_m));
      }
    } catch (const ModelError& e) {
      mesh.fail(e.what());
    }
    b.part_line[name] = p.line();
  }
}

}  // namespace crashlink::io::detail
