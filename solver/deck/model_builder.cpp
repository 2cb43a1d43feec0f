// The model's mesh from a parsed deck: nodes, materials, parts, elements, sets, boxes, frames.
#include "solver/deck/model_builder.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "core/errors.h"
#include "solver/materials/bilinear_hardening.h"

namespace crashlink::deck::detail {

model::Model Builder::build() {
  m_.name = d_.title.empty() ? std::filesystem::path(d_.files.name(0)).stem().string() : d_.title;
  index_nodes();
  curves_ = index_ids(d_, d_.curves, L::kCurve, "curve");
  sections_ = index_ids(d_, d_.sections, L::kSectionShell1, "section");
  materials();
  parts();
  elements();
  compact_nodes();
  boxes();
  coordinate_systems();
  sets();
  rigid_constraints();
  constraints();
  velocities();
  contacts();
  rigid_walls();
  curve_dofs();
  probes();
  controls();
  try {
    model::validate(m_);
  } catch (const ModelError& e) {
    throw InputError(d_.files.name(0), 0, "(model)", e.what());
  }
  return std::move(m_);
}

void Builder::index_nodes() {
  const auto& n = d_.nodes;
  nodes_.reserve(n.id.size());
  for (std::size_t i = 0; i < n.id.size(); ++i) {
    const auto [it, inserted] = nodes_.emplace(n.id[i], static_cast<std::int32_t>(i));
    if (!inserted)
      fail_at(d_, n.ref[i], "*NODE", L::kNode, 0,
              fmt::format("node {} is already defined at {}; fix: give each node its own id",
                          n.id[i], at(d_, n.ref[static_cast<std::size_t>(it->second)])));
  }
}

int Builder::node(std::int64_t id, const CardRef& ref, const char* keyword, Layout l,
                  std::size_t f) {
  const auto it = nodes_.find(id);
  if (it == nodes_.end())
    fail_at(d_, ref, keyword, l, f,
            fmt::format("node {} is not defined; fix: add it under *NODE or correct the id", id));
  return it->second;
}

void Builder::materials() {
  materials_ = index_ids(d_, d_.materials, L::kMatElastic, "material");
  for (const auto& c : d_.materials) {
    materials::Material mat;
    mat.name = c.title.empty() ? fmt::format("mat_{}", c.id) : c.title;
    mat.density_kg_m3 = c.rho * u_.density_kg_m3();
    mat.youngs_modulus_Pa = c.E * u_.stress_Pa();
    mat.poisson_ratio = c.nu;
    if (c.type != MaterialType::Rigid) {
      const double speed = wave_speed_m_s(c, u_);
      if (speed < kMinWaveSpeed_m_s || speed > kMaxWaveSpeed_m_s) {
        const auto fits = plausible_unit_systems(d_);
        fail_at(d_, c.ref, c.keyword, L::kMatElastic, 2,
                fmt::format("with RO = {} and --units {}, the wave speed sqrt(E/RO) is {:.4g} "
                            "m/s, outside the [{:.0f}, {:.0f}] m/s of crash materials (steel "
                            "5200); fix: check E and RO, or the units: {}",
                            c.rho, u_.name, speed, kMinWaveSpeed_m_s, kMaxWaveSpeed_m_s,
                            fits.empty() ? std::string("no unit system fits every material")
                                         : "the deck fits --units " + join(fits, " or ")));
      }
    }
    switch (c.type) {
      case MaterialType::Elastic:
        mat.kind = materials::MaterialKind::Elastic;
        break;
      case MaterialType::Rigid:
        mat.kind = materials::MaterialKind::Rigid;
        break;
      case MaterialType::PlasticKinematic:
        mat.kind = materials::MaterialKind::J2Plastic;
        mat.hardening = materials::bilinear_hardening(
            c.sigy * u_.stress_Pa(), mat.youngs_modulus_Pa, c.etan * u_.stress_Pa());
        break;
      case MaterialType::PiecewiseLinear:
        mat.kind = materials::MaterialKind::J2Plastic;
        mat.hardening = hardening_024(c, mat.youngs_modulus_Pa);
        break;
    }
    if (mat.kind == materials::MaterialKind::J2Plastic && c.rate_c > 0.0) {
      mat.rate_c_per_s = c.rate_c / u_.time_s;  // 1/time
      mat.rate_p = c.rate_p;
    }
    try {
      materials::validate(mat);
    } catch (const ModelError& e) {
      throw InputError(d_.files.name(c.ref.file), c.ref.line,
                       fmt::format("{} MID {}", c.keyword, c.id), e.what());
    }
    m_.materials.push_back(std::move(mat));
  }
}

std::string Builder::join(const std::vector<std::string>& v, const char* sep) {
  std::string s;
  for (const auto& x : v) s += (s.empty() ? "" : sep) + x;
  return s;
}

materials::HardeningCurve Builder::hardening_024(const MaterialCard& c, double E_Pa) {
  const double s = u_.stress_Pa();
  materials::HardeningCurve h;
  if (c.lcss > 0) {
    const auto it = curves_.find(c.lcss);
    if (it == curves_.end())
      fail_at(d_, CardRef{c.ref.file, c.ref.line + 1, c.ref.format}, c.keyword, L::kMat024b, 2,
              fmt::format("curve {} is not defined; fix: add *DEFINE_CURVE {} (effective "
                          "plastic strain, yield stress)",
                          c.lcss, c.lcss));
    const CurveCard& cv = d_.curves[static_cast<std::size_t>(it->second)];
    for (std::size_t i = 0; i < cv.a.size(); ++i) {
      h.eps_p.push_back(cv.sfa * (cv.a[i] + cv.offa));
      h.sigma_y_Pa.push_back(cv.sfo * (cv.o[i] + cv.offo) * s);
    }
    if (h.eps_p.empty() || h.eps_p[0] != 0.0)
      throw InputError(d_.files.name(cv.ref.file), cv.ref.line,
                       fmt::format("{} {}", cv.keyword, cv.id),
                       fmt::format("the yield curve of {} MID {} must start at plastic strain "
                                   "0 (it starts at {}); fix: add the point (0, initial yield)",
                                   c.keyword, c.id, h.eps_p.empty() ? 0.0 : h.eps_p[0]));
    return h;
  }
  if (!c.es.empty()) {
    for (std::size_t i = 0; i < c.es.size(); ++i) {
      h.eps_p.push_back(i < c.eps.size() ? c.eps[i] : 0.0);
      h.sigma_y_Pa.push_back(c.es[i] * s);
    }
    if (h.eps_p[0] != 0.0)
      throw InputError(d_.files.name(c.ref.file), c.ref.line,
                       fmt::format("{} MID {}", c.keyword, c.id),
                       "the EPS/ES table must start at EPS1 = 0; fix: write EPS1 0");
    return h;
  }
  return materials::bilinear_hardening(c.sigy * s, E_Pa, c.etan * s);
}

void Builder::parts() {
  parts_ = index_ids(d_, d_.parts, L::kPart, "part");
  for (const auto& p : d_.parts) {
    const auto s = sections_.find(p.section);
    if (s == sections_.end())
      fail_at(d_, p.ref, "*PART", L::kPart, 1,
              fmt::format("section {} is not defined; fix: add *SECTION_SHELL or "
                          "*SECTION_SOLID {}",
                          p.section, p.section));
    if (materials_.find(p.material) == materials_.end())
      fail_at(d_, p.ref, "*PART", L::kPart, 2,
              fmt::format("material {} is not defined; fix: add a *MAT_... card with MID {}",
                          p.material, p.material));
  }
}

int Builder::element_part(const ElementCards& cards, std::size_t e, bool shell) {
  const char* kw = shell ? "*ELEMENT_SHELL" : "*ELEMENT_SOLID";
  // The PID's card (in the two-card layout, the one before the node card).
  const CardRef pid_ref{cards.ref[e].file, cards.id_line[e], cards.ref[e].format};
  const auto it = parts_.find(cards.part[e]);
  if (it == parts_.end())
    fail_at(d_, pid_ref, kw, L::kElement, 1,
            fmt::format("part {} is not defined; fix: add a *PART with PID {}", cards.part[e],
                        cards.part[e]));
  const PartCard& p = d_.parts[static_cast<std::size_t>(it->second)];
  const SectionCard& s = d_.sections[static_cast<std::size_t>(sections_.at(p.section))];
  if (s.shell != shell)
    fail_at(d_, pid_ref, kw, L::kElement, 1,
            fmt::format("part {} has {} {} ({}); fix: give the part a {}", p.id, s.keyword, s.id,
                        at(d_, s.ref), shell ? "*SECTION_SHELL" : "*SECTION_SOLID"));
  return it->second;
}

void Builder::elements() {
  const std::size_t np = d_.parts.size();
  std::vector<model::Part> parts(np);
  std::vector<std::size_t> counts(np, 0);
  std::vector<std::vector<std::array<double, 4>>> shell_thickness(np);
  std::vector<char> any_thickness(np, 0);
  for (int pass = 0; pass < 2; ++pass) {
    const bool shell = pass == 0;
    // LS-DYNA numbers each element type on its own: a shell and a solid may share an id.
    IdMap ids;
    ids.reserve(shell ? d_.shells.count() : d_.solids.count());
    const ElementCards& c = shell ? d_.shells : d_.solids;
    const int k = shell ? 4 : 8;
    const char* kw = shell ? "*ELEMENT_SHELL" : "*ELEMENT_SOLID";
    for (std::size_t e = 0; e < c.count(); ++e) {
      const bool two = c.two_card[e] != 0;
      const Layout l = two ? Layout(L::kSolidNodes) : Layout(L::kElement);
      const std::size_t first_node_field = two ? 0 : 2;
      const CardRef id_ref{c.ref[e].file, c.id_line[e], c.ref[e].format};
      const auto [it, inserted] = ids.emplace(c.id[e], 0);
      if (!inserted)
        fail_at(d_, id_ref, kw, L::kElement, 0,
                fmt::format("{} {} is already defined; fix: give each {} its own id", kw, c.id[e],
                            shell ? "shell" : "solid"));
      const int p = element_part(c, e, shell);
      model::Part& part = parts[static_cast<std::size_t>(p)];
      const std::int64_t* n = c.nodes.data() + static_cast<std::size_t>(k) * e;
      for (int j = 0; j < k; ++j)
        part.connectivity.push_back(
            node(n[j], c.ref[e], kw, l, first_node_field + static_cast<std::size_t>(j)));
      const std::int32_t* q = part.connectivity.data() + part.connectivity.size() - k;
      check_distinct(q, k, shell, c.ref[e], kw, l, first_node_field);
      part.element_id.push_back(c.id[e]);
      if (shell) {  // *ELEMENT_SHELL_THICKNESS: kept in deck units until the section is known
        const bool given = e < c.thickness.size();
        shell_thickness[static_cast<std::size_t>(p)].push_back(given ? c.thickness[e]
                                                                     : std::array<double, 4>{});
        any_thickness[static_cast<std::size_t>(p)] =
            any_thickness[static_cast<std::size_t>(p)] ||
            (given && (c.thickness[e][0] != 0.0 || c.thickness[e][1] != 0.0 ||
                       c.thickness[e][2] != 0.0 || c.thickness[e][3] != 0.0));
      }
      ++counts[static_cast<std::size_t>(p)];
    }
  }
  for (std::size_t p = 0; p < np; ++p) {
    const PartCard& pc = d_.parts[p];
    if (counts[p] == 0) {
      empty_parts_.push_back(pc.id);
      continue;
    }
    const SectionCard& s = d_.sections[static_cast<std::size_t>(sections_.at(pc.section))];
    model::Part& part = parts[p];
    part.name = part_name(pc);
    part.user_id = pc.id;
    part.kind = s.shell ? model::ElementKind::Shell4 : model::ElementKind::Hex8;
    part.material = materials_.at(pc.material);
    part.hourglass_coefficient = hourglass_coefficient(pc);
    if (s.shell) {
      part.thickness_m = s.thickness * u_.length_m;
      part.through_thickness_points = s.nip;
      // unequal T1-T4: as *ELEMENT_SHELL_THICKNESS with the section's corners (their mean)
      const bool unequal =
          s.corner[1] != s.thickness || s.corner[2] != s.thickness || s.corner[3] != s.thickness;
      if (unequal || any_thickness[p]) {
        // *ELEMENT_SHELL_THICKNESS: the mean of the corners' thicknesses (the
        // Belytschko-Tsay element's one point), a zero corner taking the section's
        for (std::size_t e = 0; e < shell_thickness[p].size(); ++e) {
          const auto& t = shell_thickness[p][e];
          const bool tri = part.connectivity[4 * e + 3] == part.connectivity[4 * e + 2];
          const int corners = tri ? 3 : 4;
          double sum = 0.0;
          bool equal = true;  // equal corners: that value, bit for bit (no rounding of a mean)
          const auto corner = [&](int k) {
            return t[static_cast<std::size_t>(k)] > 0.0 ? t[static_cast<std::size_t>(k)]
                                                        : s.corner[static_cast<std::size_t>(k)];
          };
          for (int k = 0; k < corners; ++k) {
            sum += corner(k);
            equal = equal && corner(k) == corner(0);
          }
          part.element_thickness_m.push_back((equal ? corner(0) : sum / corners) * u_.length_m);
        }
      }
    }
    part_index_[pc.id] = static_cast<int>(m_.parts.size());
    if (pc.inertia && m_.materials[static_cast<std::size_t>(part.material)].kind !=
                          materials::MaterialKind::Rigid)
      fail_at(d_, pc.inertia_ref, pc.keyword, L::kPartInertia3, 3,
              "crashlink reads *PART_INERTIA on rigid parts (*MAT_RIGID) only: a deformable "
              "part's mass comes from its elements; fix: write *PART, or give the part a "
              "*MAT_RIGID material");
    m_.parts.push_back(std::move(part));
    if (m_.materials[static_cast<std::size_t>(m_.parts.back().material)].kind ==
        materials::MaterialKind::Rigid) {
      model::RigidBody rb;
      rb.name = m_.parts.back().name;
      rb.parts.push_back(static_cast<int>(m_.parts.size() - 1));
      rb.fixed = d_.materials[static_cast<std::size_t>(materials_.at(pc.material))].rigid_fixed;
      if (pc.inertia) {
        part_inertia(pc, rb);
        inertia_bodies_.insert(static_cast<int>(m_.rigid_bodies.size()));
      }
      rigid_body_of_part_[pc.id] = static_cast<int>(m_.rigid_bodies.size());
      m_.rigid_bodies.push_back(std::move(rb));
    }
  }
}

void Builder::part_inertia(const PartCard& pc, model::RigidBody& rb) {
  const double L = u_.length_m, M = u_.mass_kg, T = u_.time_s;
  rb.mass_kg = pc.mass * M;
  rb.centre_given = true;
  if (pc.centre_node != 0) {
    const auto it = nodes_.find(pc.centre_node);
    if (it == nodes_.end())
      fail_at(d_, pc.inertia_ref, pc.keyword, L::kPartInertia3, 5,
              fmt::format("node {} is not defined; fix: add it under *NODE or write 0 and the "
                          "centre XC, YC, ZC",
                          pc.centre_node));
    const auto i = static_cast<std::size_t>(it->second);  // index into the deck's nodes
    for (std::size_t k = 0; k < 3; ++k) rb.centre_m[k] = d_.nodes.x[3 * i + k] * L;
  } else {
    for (std::size_t k = 0; k < 3; ++k) rb.centre_m[k] = pc.centre[k] * L;
  }
  const auto& I = pc.tensor;  // IXX IXY IXZ IYY IYZ IZZ
  const double s = M * L * L;
  rb.inertia_given = true;
  rb.inertia_kg_m2 = {{{I[0] * s, I[1] * s, I[2] * s},
                       {I[1] * s, I[3] * s, I[4] * s},
                       {I[2] * s, I[4] * s, I[5] * s}}};
  for (std::size_t k = 0; k < 3; ++k) {
    rb.velocity_m_s[k] = pc.velocity[k] * L / T;
    rb.angular_velocity_rad_s[k] = pc.angular_velocity[k] / T;
  }
}

double Builder::hourglass_coefficient(const PartCard& p) {
  if (p.hourglass != 0) {
    for (const auto& h : d_.hourglass)
      if (h.id == p.hourglass) return h.qm;
    fail_at(
        d_, p.ref, "*PART", L::kPart, 4,
        fmt::format("*HOURGLASS {} is not defined; fix: add it or leave HGID blank", p.hourglass));
  }
  return d_.has_control_hourglass ? d_.control_hourglass.qm : 0.1;
}

void Builder::check_distinct(const std::int32_t* q, int k, bool shell, const CardRef& ref,
                             const char* kw, Layout l, std::size_t first) {
  for (int a = 0; a < k; ++a)
    for (int b = a + 1; b < k; ++b) {
      if (q[a] != q[b]) continue;
      if (shell && a == 2 && b == 3) continue;  // the triangle n3 = n4
      fail_at(d_, ref, kw, l, first + static_cast<std::size_t>(b),
              shell ? "repeats a corner; crashlink reads a triangle as n3 = n4 only; fix: "
                      "write the triangle's nodes as n1 n2 n3 n3"
                    : "repeats a corner: degenerate hexahedra (prisms, tetrahedra) are not "
                      "computed yet; fix: mesh the part with 8 distinct corners per element");
    }
}

std::string Builder::part_name(const PartCard& p) {
  std::string name =
      trim(p.title).empty() ? fmt::format("part_{}", p.id) : std::string(trim(p.title));
  if (used_names_.count(name)) name = fmt::format("{} (PID {})", name, p.id);
  used_names_.emplace(name, 0);
  return name;
}

void Builder::compact_nodes() {
  const auto& n = d_.nodes;
  std::vector<std::int32_t> used(n.id.size(), -1);
  for (const auto& p : m_.parts)
    for (auto i : p.connectivity) used[static_cast<std::size_t>(i)] = 0;
  std::int32_t next = 0;
  for (auto& u : used)
    if (u == 0) u = next++;
  m_.nodes.id.reserve(static_cast<std::size_t>(next));
  m_.nodes.x0.reserve(3 * static_cast<std::size_t>(next));
  for (std::size_t i = 0; i < n.id.size(); ++i) {
    if (used[i] < 0) continue;
    m_.nodes.id.push_back(n.id[i]);
    for (int k = 0; k < 3; ++k)
      m_.nodes.x0.push_back(n.x[3 * i + static_cast<std::size_t>(k)] * u_.length_m);
  }
  for (auto& p : m_.parts)
    for (auto& i : p.connectivity) i = used[static_cast<std::size_t>(i)];
  free_nodes_ = n.id.size() - static_cast<std::size_t>(next);
  for (auto& [id, idx] : nodes_) idx = used[static_cast<std::size_t>(idx)];
  m_.fixed.assign(m_.nodes.count(), 0);
}

int Builder::model_node(std::int64_t id, const CardRef& ref, const char* kw, Layout l,
                        std::size_t f) {
  return node(id, ref, kw, l, f);
}

void Builder::sets() {
  IdMap node_sets, part_sets, shell_sets;
  const IdMap segment_sets = index_ids(d_, d_.segment_sets, L::kSetHeader, "segment set");
  (void)segment_sets;  // looked up by the contacts that name one (segment_faces)
  for (std::size_t i = 0; i < d_.sets.size(); ++i) {
    const SetCard& s = d_.sets[i];
    if (s.shells) {  // *SET_SHELL_LIST: each id a shell of the model, as (part, element)
      if (shell_at_.empty())
        for (std::size_t p = 0; p < m_.parts.size(); ++p)
          if (m_.parts[p].kind == model::ElementKind::Shell4)
            for (std::size_t e = 0; e < m_.parts[p].element_id.size(); ++e)
              shell_at_[m_.parts[p].element_id[e]] = {static_cast<int>(p), static_cast<int>(e)};
      if (!shell_sets.emplace(s.id, static_cast<std::int32_t>(i)).second)
        fail_at(d_, s.ref, s.keyword, L::kSetHeader, 0,
                fmt::format("shell set {} is already defined; fix: give each its own id", s.id));
      for (std::size_t k = 0; k < s.members.size(); ++k)
        if (!shell_at_.count(s.members[k])) fail_member(s, k);
      shell_set_members_[s.id] = s.members;
      continue;
    }
    auto& map = s.parts ? part_sets : node_sets;
    const auto [it, inserted] = map.emplace(s.id, static_cast<std::int32_t>(i));
    if (!inserted)
      fail_at(d_, s.ref, s.keyword, L::kSetHeader, 0,
              fmt::format("set {} is already defined at {}; fix: give each {} set its own id", s.id,
                          at(d_, d_.sets[static_cast<std::size_t>(it->second)].ref),
                          s.parts ? "part" : "node"));
    std::vector<std::int64_t> ids;
    for (const GeneralEntry& g : s.general) general_members(s, g, ids);
    for (std::size_t k = 0; k < s.members.size(); ++k) {
      const bool ok = s.parts ? parts_.count(s.members[k]) > 0 : nodes_.count(s.members[k]) > 0;
      if (!ok) fail_member(s, k);
      ids.push_back(s.members[k]);
    }
    for (std::size_t r = 0; r < s.ranges.size(); ++r) {
      const auto [lo, hi] = s.ranges[r];
      std::size_t found = 0;
      const IdMap& defined = s.parts ? parts_ : nodes_;
      if (static_cast<double>(hi) - static_cast<double>(lo) < static_cast<double>(defined.size())) {
        for (std::int64_t id = lo; id <= hi; ++id)
          if (defined.count(id) > 0) {
            ids.push_back(id);
            ++found;
          }
      } else {  // a range wider than the ids there are: the ids in it, ascending
        std::vector<std::int64_t> in;
        for (const auto& [id, index] : defined)
          if (id >= lo && id <= hi) in.push_back(id);
        std::sort(in.begin(), in.end());
        found = in.size();
        ids.insert(ids.end(), in.begin(), in.end());
      }
      if (found == 0)
        fail_at(d_, s.range_ref[r], s.keyword, L::kSetGenerate, 2 * (r % 4),
                fmt::format("the range {}-{} holds no defined {}; fix: correct the range", lo, hi,
                            s.parts ? "part" : "node"));
    }
    (s.parts ? part_set_members_ : node_set_members_)[s.id] = std::move(ids);
  }
}

void Builder::general_members(const SetCard& s, const GeneralEntry& g,
                              std::vector<std::int64_t>& ids) {
  using Opt = GeneralEntry::Option;
  const auto& n = d_.nodes;
  for (std::size_t k = 0; k < g.ids.size(); ++k) {
    const std::int64_t id = g.ids[k];
    const bool ok = g.option == Opt::Node   ? nodes_.count(id) > 0
                    : g.option == Opt::Part ? parts_.count(id) > 0
                                            : boxes_.count(id) > 0;
    if (!ok)
      fail_at(d_, g.ref, s.keyword, L::kSetGeneral, g.field[k],
              fmt::format("{} {} is not defined; fix: correct the id or define it",
                          g.option == Opt::Node   ? "node"
                          : g.option == Opt::Part ? "part"
                                                  : "*DEFINE_BOX",
                          id));
  }
  const std::size_t before = ids.size();
  switch (g.option) {
    case Opt::All:
      ids.insert(ids.end(), n.id.begin(), n.id.end());
      break;
    case Opt::Node:
      ids.insert(ids.end(), g.ids.begin(), g.ids.end());
      break;
    case Opt::Part:
      for (auto pid : g.ids)
        if (const auto p = part_index_.find(pid); p != part_index_.end())
          for (auto i : m_.parts[static_cast<std::size_t>(p->second)].connectivity)
            ids.push_back(m_.nodes.id[static_cast<std::size_t>(i)]);
      break;
    case Opt::Box:
      for (auto bid : g.ids) {
        const BoxCard& b = d_.boxes[static_cast<std::size_t>(boxes_.at(bid))];
        for (std::size_t i = 0; i < n.id.size(); ++i) {
          bool in = true;
          for (std::size_t c = 0; c < 3; ++c) {
            const double x = n.x[3 * i + c];
            in = in && x >= b.lo[c] && x <= b.hi[c];
          }
          if (in) ids.push_back(n.id[i]);
        }
      }
      break;
  }
  if (ids.size() == before)
    d_notes_.push_back(
        fmt::format("{}: {} {}: this card selects no node", at(d_, g.ref), s.keyword, s.id));
}

void Builder::coordinate_systems() {
  const auto ids = index_ids(d_, d_.coordinate_systems, L::kCoordinateSystem1, "coordinate system");
  for (const auto& cs : d_.coordinate_systems) {
    const Vec3 o{cs.o[0], cs.o[1], cs.o[2]};
    const Vec3 ol = Vec3{cs.l[0], cs.l[1], cs.l[2]} - o;
    const Vec3 op = Vec3{cs.p[0], cs.p[1], cs.p[2]} - o;
    const Vec3 n = cross(ol, op);
    const double lol = norm(ol), ln = norm(n);
    if (!(lol > 0.0) || !(ln > 1e-9 * lol * norm(op)))
      fail_at(d_, cs.ref, cs.keyword, L::kCoordinateSystem1, 4,
              "O, L and P must not lie on one line (O->L is the local x axis, P a point of "
              "the local x-y plane off that axis); fix: correct XL, YL, ZL or XP, YP, ZP");
    const Vec3 e1 = (1.0 / lol) * ol, e3 = (1.0 / ln) * n, e2 = cross(e3, e1);
    Mat3 r{};
    for (int i = 0; i < 3; ++i) {
      r[static_cast<std::size_t>(i)][0] = e1[static_cast<std::size_t>(i)];
      r[static_cast<std::size_t>(i)][1] = e2[static_cast<std::size_t>(i)];
      r[static_cast<std::size_t>(i)][2] = e3[static_cast<std::size_t>(i)];
    }
    frames_[cs.id] = r;
  }
  (void)ids;
}

Mat3 Builder::frame(std::int64_t icid, const CardRef& ref, const std::string& kw, Layout l,
                    std::size_t field) {
  if (icid == 0) return identity3();
  const auto it = frames_.find(icid);
  if (it == frames_.end())
    fail_at(d_, ref, kw, l, field,
            fmt::format("coordinate system {} is not defined; fix: add "
                        "*DEFINE_COORDINATE_SYSTEM {} or write 0 (global axes)",
                        icid, icid));
  return it->second;
}

void Builder::fail_member(const SetCard& s, std::size_t k) {
  // The member's field on its card: count the members listed before it on the same card.
  std::size_t field = 0;
  for (std::size_t j = k; j > 0 && s.member_ref[j - 1].line == s.member_ref[k].line; --j) ++field;
  fail_at(d_, s.member_ref[k], s.keyword, L::kSetList, field,
          fmt::format("{} {} is not defined; fix: correct the id or define the {}",
                      s.parts    ? "part"
                      : s.shells ? "shell"
                                 : "node",
                      s.members[k],
                      s.parts    ? "part"
                      : s.shells ? "shell (*ELEMENT_SHELL)"
                                 : "node"));
}

const std::vector<std::int64_t>& Builder::node_set(std::int64_t id, const CardRef& ref,
                                                   const std::string& kw, Layout l,
                                                   std::size_t field) {
  const auto it = node_set_members_.find(id);
  if (it == node_set_members_.end())
    fail_at(d_, ref, kw, l, field,
            fmt::format("node set {} is not defined; fix: add *SET_NODE_LIST {}", id, id));
  return it->second;
}

}  // namespace crashlink::deck::detail
