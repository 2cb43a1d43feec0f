// The `contacts` section (docs/scenario-format.md): penalty contacts (two-pass, one-pass or
// single-surface) with Coulomb friction, one model::Contact per entry.
#include "core/errors.h"
#include "solver/contact/segments.h"
#include "solver/io/scenario_sections.h"

namespace crashlink::io::detail {

void read_contacts(const YamlNode& section, ScenarioBuild& b) {
  auto& m = b.model;
  for (const auto& [name, entry] :
       section.entries("contacts (name: {type, slave, master, penalty_scale, soft, friction})")) {
    entry.expect_keys({"type", "slave", "master", "penalty_scale", "soft", "friction",
                       "slave_thickness", "master_thickness"});
    model::Contact c;
    c.name = name;
    if (auto t = entry.optional("type")) {
      const std::string k = t->text();
      if (k == "surface_to_surface")
        c.kind = model::ContactKind::SurfaceToSurface;
      else if (k == "node_to_surface")
        c.kind = model::ContactKind::NodeToSurface;
      else if (k == "single_surface")
        c.kind = model::ContactKind::SingleSurface;
      else
        t->fail("unknown contact type '" + k +
                "'; use surface_to_surface (two passes, the default), node_to_surface (one "
                "pass: the slave nodes against the master surface) or single_surface (the "
                "master parts against themselves)");
    }
    const bool self = c.kind == model::ContactKind::SingleSurface;
    if (self) {
      if (auto sl = entry.optional("slave"))
        sl->fail("a single_surface contact has no slave: list its parts under master");
    } else {
      c.slave_nodes = read_node_reference(
          entry.required("slave", "a node set name or a selection such as {part: plate}"), b);
    }
    const auto master = entry.required(
        "master", self ? "the parts whose surface folds onto itself, e.g. [tube]"
                       : "the parts whose surface the slave nodes hit, e.g. [plate]");
    if (master.is_sequence()) {
      for (const auto& pn : master.items("part names")) {
        const int p = read_part_reference(pn, b);
        for (int q : c.master_parts)
          if (q == p) pn.fail("part '" + pn.text() + "' is listed twice; list it once");
        c.master_parts.push_back(p);
      }
      if (c.master_parts.empty()) master.fail("lists no part; give at least one part name");
    } else {
      c.master_parts.push_back(read_part_reference(master, b));
    }
    if (auto s = entry.optional("penalty_scale")) c.penalty_scale = s->positive();
    // the sides' shells' contact thickness in place of their own (LS-DYNA SST, MST)
    c.slave_thickness_m = entry.non_negative_or("slave_thickness", 0.0);
    c.master_thickness_m = entry.non_negative_or("master_thickness", 0.0);
    if (self && c.master_thickness_m > 0.0)
      entry.required("master_thickness")
          .fail("a single_surface contact has one side: give its `slave_thickness`");
    if (auto soft = entry.optional("soft")) {
      if (soft->is_scalar()) {
        c.soft = soft->boolean();
      } else {
        soft->expect_keys({"enabled", "scale"});
        c.soft = soft->boolean_or("enabled", true);
        c.soft_scale = soft->positive_or("scale", 0.1);
      }
    }
    if (auto fr = entry.optional("friction")) {
      fr->expect_keys({"static", "dynamic", "decay"});
      c.static_friction = fr->non_negative_or("static", 0.0);
      c.dynamic_friction = fr->non_negative_or("dynamic", c.static_friction);
      c.friction_decay_s_m = fr->non_negative_or("decay", 0.0);
      if (c.dynamic_friction > c.static_friction)
        if (auto d = fr->optional("dynamic"))
          d->fail(
              fmt::format("dynamic coefficient {} exceeds the static one {}; friction decays "
                          "from static to dynamic, so dynamic <= static",
                          c.dynamic_friction, c.static_friction));
    }
    // The master parts must give segments: shells, or hexahedra with exterior faces.
    try {
      (void)contact::build_segments(m, c.master_parts, c.penalty_scale);
    } catch (const ModelError& e) {
      master.fail(e.what());
    }
    m.contacts.push_back(std::move(c));
  }
}

}  // namespace crashlink::io::detail
