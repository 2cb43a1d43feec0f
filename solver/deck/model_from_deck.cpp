#include "solver/deck/model_from_deck.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <unordered_map>
#include <unordered_set>

#include "solver/core/errors.h"
#include "solver/deck/keyword_layouts.h"
#include "solver/materials/bilinear_hardening.h"

namespace crashlink::deck {

namespace {

namespace L = layout;
using IdMap = std::unordered_map<std::int64_t, std::int32_t>;

std::string at(const Deck& d, const CardRef& r) {
  return fmt::format("{}:{}", d.files.name(r.file), r.line);
}

/// id -> index of `records` (their `.id`), refusing a duplicate at its ID field.
template <class Records>
IdMap index_ids(const Deck& d, const Records& records, Layout l, const char* what) {
  IdMap m;
  m.reserve(records.size());
  for (std::size_t i = 0; i < records.size(); ++i) {
    const auto& r = records[i];
    const auto [it, inserted] = m.emplace(r.id, static_cast<std::int32_t>(i));
    if (!inserted)
      fail_at(d, r.ref, r.keyword, l, 0,
              fmt::format("{} {} is already defined at {}; fix: give each {} its own id", what,
                          r.id, at(d, records[static_cast<std::size_t>(it->second)].ref), what));
  }
  return m;
}

double wave_speed_m_s(const MaterialCard& m, const UnitSystem& u) {
  return std::sqrt(m.E * u.stress_Pa() / (m.rho * u.density_kg_m3()));
}

class Builder {
 public:
  Builder(const Deck& d, const UnitSystem& u) : d_(d), u_(u) {}

  model::Model build() {
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

 private:
  void index_nodes() {
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

  int node(std::int64_t id, const CardRef& ref, const char* keyword, Layout l, std::size_t f) {
    const auto it = nodes_.find(id);
    if (it == nodes_.end())
      fail_at(d_, ref, keyword, l, f,
              fmt::format("node {} is not defined; fix: add it under *NODE or correct the id", id));
    return it->second;
  }

  void materials() {
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

  static std::string join(const std::vector<std::string>& v, const char* sep) {
    std::string s;
    for (const auto& x : v) s += (s.empty() ? "" : sep) + x;
    return s;
  }

  /// *MAT_024's yield curve: LCSS, else the EPS/ES table, else SIGY/ETAN.
  materials::HardeningCurve hardening_024(const MaterialCard& c, double E_Pa) {
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

  void parts() {
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

  /// The part of element `e` of `cards` (its PID checked against the sections).
  int element_part(const ElementCards& cards, std::size_t e, bool shell) {
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

  void elements() {
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
        if (any_thickness[p]) {
          // *ELEMENT_SHELL_THICKNESS: the mean of the corners' thicknesses (the
          // Belytschko-Tsay element's one point), a zero corner taking the section's
          for (std::size_t e = 0; e < shell_thickness[p].size(); ++e) {
            const auto& t = shell_thickness[p][e];
            const bool tri = part.connectivity[4 * e + 3] == part.connectivity[4 * e + 2];
            const int corners = tri ? 3 : 4;
            double sum = 0.0;
            for (int k = 0; k < corners; ++k)
              sum += t[static_cast<std::size_t>(k)] > 0.0 ? t[static_cast<std::size_t>(k)]
                                                          : s.thickness;
            part.element_thickness_m.push_back(sum / corners * u_.length_m);
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
        if (pc.inertia) {
          part_inertia(pc, rb);
          inertia_bodies_.insert(static_cast<int>(m_.rigid_bodies.size()));
        }
        rigid_body_of_part_[pc.id] = static_cast<int>(m_.rigid_bodies.size());
        m_.rigid_bodies.push_back(std::move(rb));
      }
    }
  }

  /// *PART_INERTIA on a rigid part: the body's mass, centre (NODEID's position if given),
  /// inertia tensor about it (global axes) and initial velocities, in SI. (*INITIAL_VELOCITY_
  /// GENERATION on the part, read later, replaces the translational velocity.)
  void part_inertia(const PartCard& pc, model::RigidBody& rb) {
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

  /// QM of the part's *HOURGLASS (HGID), else *CONTROL_HOURGLASS's QH, else 0.1.
  double hourglass_coefficient(const PartCard& p) {
    if (p.hourglass != 0) {
      for (const auto& h : d_.hourglass)
        if (h.id == p.hourglass) return h.qm;
      fail_at(d_, p.ref, "*PART", L::kPart, 4,
              fmt::format("*HOURGLASS {} is not defined; fix: add it or leave HGID blank",
                          p.hourglass));
    }
    return d_.has_control_hourglass ? d_.control_hourglass.qm : 0.1;
  }

  /// A shell's corners distinct except n3 = n4 (a triangle); a hexahedron's all distinct.
  void check_distinct(const std::int32_t* q, int k, bool shell, const CardRef& ref, const char* kw,
                      Layout l, std::size_t first) {
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

  std::string part_name(const PartCard& p) {
    std::string name =
        trim(p.title).empty() ? fmt::format("part_{}", p.id) : std::string(trim(p.title));
    if (used_names_.count(name)) name = fmt::format("{} (PID {})", name, p.id);
    used_names_.emplace(name, 0);
    return name;
  }

  /// Drops the nodes no element uses (they would have no mass), keeping the deck's order.
  void compact_nodes() {
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

  /// The model index of deck node `id` (-1: a node in no element).
  int model_node(std::int64_t id, const CardRef& ref, const char* kw, Layout l, std::size_t f) {
    return node(id, ref, kw, l, f);
  }

  void sets() {
    IdMap node_sets, part_sets;
    for (std::size_t i = 0; i < d_.sets.size(); ++i) {
      const SetCard& s = d_.sets[i];
      auto& map = s.parts ? part_sets : node_sets;
      const auto [it, inserted] = map.emplace(s.id, static_cast<std::int32_t>(i));
      if (!inserted)
        fail_at(d_, s.ref, s.keyword, L::kSetHeader, 0,
                fmt::format("set {} is already defined at {}; fix: give each {} set its own id",
                            s.id, at(d_, d_.sets[static_cast<std::size_t>(it->second)].ref),
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
        if (static_cast<double>(hi) - static_cast<double>(lo) <
            static_cast<double>(defined.size())) {
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

  /// The node ids one *SET_NODE_GENERAL card adds (ALL: every node; NODE: the ids, checked;
  /// PART: the nodes of the parts' elements; BOX: the nodes inside the boxes, bounds included).
  void general_members(const SetCard& s, const GeneralEntry& g, std::vector<std::int64_t>& ids) {
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

  void boxes() { boxes_ = index_ids(d_, d_.boxes, L::kBox, "box"); }

  /// *DEFINE_COORDINATE_SYSTEM: the local axes e1 along O->L, e3 normal to O->L and O->P,
  /// e2 = e3 x e1 (LS-DYNA's construction), as the columns of the rotation local -> global.
  void coordinate_systems() {
    const auto ids =
        index_ids(d_, d_.coordinate_systems, L::kCoordinateSystem1, "coordinate system");
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

  /// The rotation local -> global of ICID (identity for 0), or the error at `field` of `ref`.
  Mat3 frame(std::int64_t icid, const CardRef& ref, const std::string& kw, Layout l,
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

  void fail_member(const SetCard& s, std::size_t k) {
    // The member's field on its card: count the members listed before it on the same card.
    std::size_t field = 0;
    for (std::size_t j = k; j > 0 && s.member_ref[j - 1].line == s.member_ref[k].line; --j) ++field;
    fail_at(d_, s.member_ref[k], s.keyword, L::kSetList, field,
            fmt::format("{} {} is not defined; fix: correct the id or define the {}",
                        s.parts ? "part" : "node", s.members[k], s.parts ? "part" : "node"));
  }

  const std::vector<std::int64_t>& node_set(std::int64_t id, const CardRef& ref,
                                            const std::string& kw, Layout l,
                                            std::size_t field = 0) {
    const auto it = node_set_members_.find(id);
    if (it == node_set_members_.end())
      fail_at(d_, ref, kw, l, field,
              fmt::format("node set {} is not defined; fix: add *SET_NODE_LIST {}", id, id));
    return it->second;
  }

  void constraints() {
    for (const auto& s : d_.spcs) {
      const Layout l = s.set ? Layout(L::kSpcSet) : Layout(L::kSpcNode);
      std::vector<std::int64_t> one{s.target};
      const auto& ids = s.set ? node_set(s.target, s.ref, s.keyword, l) : one;
      for (auto id : ids) {
        const int i = node(id, s.ref, s.keyword.c_str(), l, 0);
        if (i >= 0) m_.fixed[static_cast<std::size_t>(i)] |= s.mask;
      }
    }
  }

  void velocities() {
    for (const auto& v : d_.velocities) {
      const bool generation = v.styp != 0;
      const bool plain = v.styp == 4;  // *INITIAL_VELOCITY
      const Layout l = plain        ? Layout(L::kInitialVelocity1)
                       : generation ? Layout(L::kVelocityGeneration1)
                                    : Layout(L::kVelocityNode);
      const Mat3 r = frame(v.icid, v.ref, v.keyword, l, plain ? 4 : 7);
      const Vec3 vel = mul(r, Vec3{v.v[0] * u_.velocity_m_s(), v.v[1] * u_.velocity_m_s(),
                                   v.v[2] * u_.velocity_m_s()});
      std::vector<std::int64_t> part_ids;
      std::vector<std::int64_t> node_ids;
      if (v.styp == 0) {
        node_ids.push_back(v.target);
      } else if (v.styp == 1) {
        const auto it = part_set_members_.find(v.target);
        if (it == part_set_members_.end())
          fail_at(d_, v.ref, v.keyword, l, 0,
                  fmt::format("part set {} is not defined (STYP 1); fix: add *SET_PART_LIST {}",
                              v.target, v.target));
        part_ids = it->second;
      } else if (v.styp == 2) {
        if (!parts_.count(v.target))
          fail_at(d_, v.ref, v.keyword, l, 0,
                  fmt::format("part {} is not defined (STYP 2); fix: correct the id", v.target));
        part_ids.push_back(v.target);
      } else if (plain && v.target == 0) {
        node_ids = m_.nodes.id;  // NSID 0: every node (a rigid body's follow its body)
      } else {
        node_ids = node_set(v.target, v.ref, v.keyword, l);
      }
      model::InitialVelocity iv;
      iv.velocity_m_s = vel;
      for (auto pid : part_ids) {
        if (const auto rb = rigid_body_of_part_.find(pid); rb != rigid_body_of_part_.end()) {
          // LS-DYNA's IRIGID 0 (default) keeps a *PART_INERTIA body's velocity; 1 overrides it
          if (inertia_bodies_.count(rb->second) == 0 || v.irigid == 1)
            m_.rigid_bodies[static_cast<std::size_t>(rb->second)].velocity_m_s = vel;
          else
            d_notes_.push_back(
                fmt::format("{}: {}: part {} keeps the velocity of its *PART_INERTIA (IRIGID 0; 1 "
                            "overrides it)",
                            at(d_, v.ref), v.keyword, pid));
          continue;
        }
        const auto p = part_index_.find(pid);
        if (p == part_index_.end()) continue;  // a part without elements
        for (auto i : m_.parts[static_cast<std::size_t>(p->second)].connectivity)
          iv.nodes.push_back(i);
      }
      for (auto id : node_ids) {
        const int i = node(id, v.ref, v.keyword.c_str(), l, 0);
        if (i >= 0) iv.nodes.push_back(i);
      }
      std::sort(iv.nodes.begin(), iv.nodes.end());
      iv.nodes.erase(std::unique(iv.nodes.begin(), iv.nodes.end()), iv.nodes.end());
      if (plain) {
        // A rigid body with nodes in the set takes the velocity (LS-DYNA: IRIGID 0 protects
        // only *PART_INERTIA velocities); its nodes follow the body, so they leave the list.
        std::vector<int> body_of(m_.nodes.count(), -1);
        for (std::size_t b = 0; b < m_.rigid_bodies.size(); ++b)
          for (int p : m_.rigid_bodies[b].parts)
            for (auto c : m_.parts[static_cast<std::size_t>(p)].connectivity)
              body_of[static_cast<std::size_t>(c)] = static_cast<int>(b);
        std::vector<char> moved(m_.rigid_bodies.size(), 0);
        for (auto c : iv.nodes) {
          const int b = body_of[static_cast<std::size_t>(c)];
          if (b < 0 || moved[static_cast<std::size_t>(b)]) continue;
          moved[static_cast<std::size_t>(b)] = 1;
          if (inertia_bodies_.count(b) == 0)
            m_.rigid_bodies[static_cast<std::size_t>(b)].velocity_m_s = vel;
          else
            d_notes_.push_back(fmt::format(
                "{}: {}: rigid body '{}' keeps the velocity of its *PART_INERTIA", at(d_, v.ref),
                v.keyword, m_.rigid_bodies[static_cast<std::size_t>(b)].name));
        }
        std::erase_if(iv.nodes,
                      [&](std::int32_t c) { return body_of[static_cast<std::size_t>(c)] >= 0; });
      }
      if (iv.nodes.empty()) continue;
      // Consecutive *INITIAL_VELOCITY_NODE cards with one velocity make one entry.
      if (!generation && !m_.initial_velocities.empty() && last_was_node_ &&
          m_.initial_velocities.back().velocity_m_s == vel) {
        auto& back = m_.initial_velocities.back().nodes;
        back.insert(back.end(), iv.nodes.begin(), iv.nodes.end());
      } else {
        m_.initial_velocities.push_back(std::move(iv));
      }
      last_was_node_ = !generation;
    }
  }

  /// The model parts of a contact surface: SSTYP/MSTYP 2 (part set), 3 (part), 5 (all parts);
  /// id 0 of a single-surface contact: all parts. Parts without elements are left out.
  std::vector<int> surface_parts(const ContactCard& k, bool slave) {
    const std::int64_t id = slave ? k.ssid : k.msid;
    const int typ = slave ? k.sstyp : k.mstyp;
    const std::size_t id_field = slave ? 0 : 1, typ_field = slave ? 2 : 3;
    std::vector<int> out;
    const bool all = typ == 5 || (id == 0 && k.kind == ContactCard::Kind::SingleSurface);
    if (all) {
      for (std::size_t p = 0; p < m_.parts.size(); ++p) out.push_back(static_cast<int>(p));
      return out;
    }
    if (id == 0)
      fail_at(d_, k.ref, k.keyword, L::kContact1, id_field,
              fmt::format("the {} surface is not given; fix: write a part (TYP 3) or part set "
                          "(TYP 2) id",
                          slave ? "slave" : "master"));
    std::vector<std::int64_t> pids;
    if (typ == 3) {
      if (!parts_.count(id))
        fail_at(d_, k.ref, k.keyword, L::kContact1, id_field,
                fmt::format("part {} is not defined; fix: correct the id", id));
      pids.push_back(id);
    } else if (typ == 2) {
      const auto it = part_set_members_.find(id);
      if (it == part_set_members_.end())
        fail_at(d_, k.ref, k.keyword, L::kContact1, id_field,
                fmt::format("part set {} is not defined; fix: add *SET_PART_LIST {}", id, id));
      pids = it->second;
    } else {
      fail_at(d_, k.ref, k.keyword, L::kContact1, typ_field,
              fmt::format("surface type {} is not read: crashlink takes a contact surface as "
                          "parts (3), a part set (2){}{}; fix: name the parts",
                          typ,
                          slave && k.kind != ContactCard::Kind::SingleSurface
                              ? ", a node set (4, slave only)"
                              : "",
                          " or all parts (5)"));
    }
    for (auto pid : pids)
      if (const auto p = part_index_.find(pid); p != part_index_.end()) out.push_back(p->second);
    if (out.empty())
      fail_at(d_, k.ref, k.keyword, L::kContact1, id_field,
              fmt::format("the {} surface holds no element; fix: name parts with elements",
                          slave ? "slave" : "master"));
    return out;
  }

  /// The heading, else contact_<CID> or contact_<n> (n: the deck's order); a name already taken
  /// gets " (CID c)" or " (n)" appended (LS-DYNA allows repeated headings, crashlink's results
  /// need distinct names).
  std::string contact_name(const ContactCard& k, std::size_t i) {
    const std::string tag = k.cid > 0 ? std::to_string(k.cid) : std::to_string(i + 1);
    std::string name = k.heading.empty() ? "contact_" + tag : k.heading;
    if (used_contact_names_.count(name))
      name += k.cid > 0 ? " (CID " + tag + ")" : " (" + tag + ")";
    for (int extra = 2; used_contact_names_.count(name); ++extra)
      name = fmt::format("{} #{}", name, extra);
    used_contact_names_.emplace(name, 0);
    return name;
  }

  /// *CONTACT_* onto model::Contact (docs/decks.md "Contacts"): penalty_scale = 0.1 SFS (SLSFAC's
  /// default 0.1), SOFT 1 adds the mass-and-step stiffness scaled by SOFSCL, Coulomb friction
  /// mu = FD + (FS - FD) exp(-DC |v_rel|) as crashlink's.
  void contacts() {
    for (std::size_t i = 0; i < d_.contacts.size(); ++i) {
      const ContactCard& k = d_.contacts[i];
      model::Contact c;
      c.name = contact_name(k, i);
      c.kind = k.kind == ContactCard::Kind::SingleSurface    ? model::ContactKind::SingleSurface
               : k.kind == ContactCard::Kind::NodesToSurface ? model::ContactKind::NodeToSurface
                                                             : model::ContactKind::SurfaceToSurface;
      if (k.kind == ContactCard::Kind::SingleSurface) {
        c.master_parts = surface_parts(k, true);
      } else {
        if (k.sstyp == 4) {
          for (auto id : node_set(k.ssid, k.ref, k.keyword, L::kContact1)) {
            const int n = node(id, k.ref, k.keyword.c_str(), L::kContact1, 0);
            if (n >= 0) c.slave_nodes.push_back(n);
          }
        } else {
          for (int p : surface_parts(k, true))
            for (auto n : m_.parts[static_cast<std::size_t>(p)].connectivity)
              c.slave_nodes.push_back(n);
        }
        std::sort(c.slave_nodes.begin(), c.slave_nodes.end());
        c.slave_nodes.erase(std::unique(c.slave_nodes.begin(), c.slave_nodes.end()),
                            c.slave_nodes.end());
        if (c.slave_nodes.empty())
          fail_at(d_, k.ref, k.keyword, L::kContact1, 0,
                  "the slave surface holds no node of an element; fix: correct the set");
        c.master_parts = surface_parts(k, false);
      }
      if (k.sfs != k.sfm && k.kind != ContactCard::Kind::SingleSurface)
        fail_at(d_, k.ref3, k.keyword, L::kContact3, 1,
                fmt::format("crashlink has one penalty scale per contact and SFS = {}; fix: "
                            "write SFM = SFS",
                            k.sfs));
      c.penalty_scale = d_.slsfac * k.sfs;  // *CONTROL_CONTACT SLSFAC (default 0.1)
      c.soft = k.soft == 1;
      c.soft_scale = k.sofscl;
      c.static_friction = k.fs;
      c.dynamic_friction = k.fd == 0.0 && k.dc == 0.0 ? k.fs : k.fd;
      c.friction_decay_s_m = k.dc * u_.time_s / u_.length_m;
      if (!k.automatic)
        d_notes_.push_back(fmt::format(
            "{}: {}: computed as its automatic form (crashlink's contact finds either side of "
            "a shell, whatever its normal)",
            at(d_, k.ref), k.keyword));
      m_.contacts.push_back(std::move(c));
    }
  }

  /// *RIGIDWALL_PLANAR onto model::RigidWall: the plane through the tail point, normal along
  /// tail -> head (the side the nodes stay on), the nodes of NSID (0: every node).
  void rigid_walls() {
    std::vector<char> on_body(m_.nodes.count(), 0);
    for (const auto& rb : m_.rigid_bodies)
      for (int p : rb.parts)
        for (auto c : m_.parts[static_cast<std::size_t>(p)].connectivity)
          on_body[static_cast<std::size_t>(c)] = 1;
    for (std::size_t i = 0; i < d_.rigid_walls.size(); ++i) {
      const RigidWallCard& k = d_.rigid_walls[i];
      model::RigidWall w;
      w.name = k.heading.empty() ? fmt::format("rigidwall_{}", i + 1) : k.heading;
      if (!used_wall_names_.insert(w.name).second) {  // a heading met twice: made unique
        const std::string base = w.name;
        w.name = fmt::format("{} ({})", base, i + 1);
        for (int extra = 2; !used_wall_names_.insert(w.name).second; ++extra)
          w.name = fmt::format("{} ({}) #{}", base, i + 1, extra);
      }
      Vec3 n{};
      for (std::size_t c = 0; c < 3; ++c) {
        w.point_m[c] = k.tail[c] * u_.length_m;
        n[c] = k.head[c] - k.tail[c];
      }
      const double len = norm(n);
      if (!(len > 0.0))
        fail_at(d_, k.ref2, k.keyword, L::kRigidWall2, 3,
                "the head point is the tail point: the wall has no normal; fix: put the head on "
                "the side of the nodes the wall stops");
      w.normal = (1.0 / len) * n;
      if (k.moving) {  // *RIGIDWALL_PLANAR_MOVING: MASS, V0 along the normal (toward the nodes)
        w.mass_kg = k.mass * u_.mass_kg;
        w.velocity_m_s = k.v0 * u_.velocity_m_s();
      }
      if (k.nsid == 0) {
        for (std::size_t c = 0; c < m_.nodes.count(); ++c)
          w.nodes.push_back(static_cast<std::int32_t>(c));
      } else {
        for (auto id : node_set(k.nsid, k.ref, k.keyword, L::kRigidWall1)) {
          const int c = node(id, k.ref, k.keyword.c_str(), L::kRigidWall1, 0);
          if (c >= 0) w.nodes.push_back(c);
        }
        std::sort(w.nodes.begin(), w.nodes.end());
        w.nodes.erase(std::unique(w.nodes.begin(), w.nodes.end()), w.nodes.end());
      }
      // A rigid body's nodes follow the body: the wall leaves them out, and says so.
      const auto rigid = std::erase_if(
          w.nodes, [&](std::int32_t c) { return on_body[static_cast<std::size_t>(c)] != 0; });
      if (rigid > 0)
        d_notes_.push_back(fmt::format("{}: {}: {} nodes of rigid bodies left out of the wall",
                                       at(d_, k.ref), k.keyword, rigid));
      if (w.nodes.empty())
        fail_at(d_, k.ref, k.keyword, L::kRigidWall1, 0,
                "the wall stops no node of a deformable element; fix: correct NSID");
      m_.rigid_walls.push_back(std::move(w));
    }
  }

  /// Curve `lcid` against time in SI: abscissa SFA (a + OFFA) [deck time] -> s, ordinate
  /// SF SFO (o + OFFO) x `unit` (LS-DYNA's *DEFINE_CURVE remark: offsets first, then scales).
  model::Curve time_curve(std::int64_t lcid, double sf, double unit, const CardRef& ref,
                          const std::string& keyword, Layout l, std::size_t field) {
    const auto it = curves_.find(lcid);
    if (it == curves_.end())
      fail_at(d_, ref, keyword, l, field,
              fmt::format("curve {} is not defined; fix: add *DEFINE_CURVE {}", lcid, lcid));
    const CurveCard& cv = d_.curves[static_cast<std::size_t>(it->second)];
    model::Curve c;
    for (std::size_t i = 0; i < cv.a.size(); ++i) {
      c.t_s.push_back(cv.sfa * (cv.a[i] + cv.offa) * u_.time_s);
      c.value.push_back(sf * cv.sfo * (cv.o[i] + cv.offo) * unit);
    }
    return c;
  }

  /// *BOUNDARY_PRESCRIBED_MOTION_NODE/_SET (VAD 0: velocity) -> model::PrescribedVelocity,
  /// *LOAD_NODE_POINT/_SET -> model::NodalLoad (force per node), one dof each; a set's nodes in
  /// no element are left out.
  void curve_dofs() {
    int motions = 0, loads = 0;
    for (const CurveDofCard& k : d_.curve_dofs) {
      const Layout l = k.load ? (k.set ? Layout(L::kLoadSet) : Layout(L::kLoadNode))
                              : (k.set ? Layout(L::kMotionSet) : Layout(L::kMotionNode));
      std::vector<std::int64_t> one{k.target};
      const auto& ids = k.set ? node_set(k.target, k.ref, k.keyword, l) : one;
      std::vector<std::int32_t> nodes;
      for (auto id : ids) {
        const int i = node(id, k.ref, k.keyword.c_str(), l, 0);
        if (i < 0 && !k.set)
          fail_at(d_, k.ref, k.keyword, l, 0,
                  fmt::format("node {} belongs to no element (crashlink leaves such nodes out); "
                              "fix: drive a node of an element",
                              id));
        if (i >= 0) nodes.push_back(i);
      }
      if (nodes.empty())
        fail_at(d_, k.ref, k.keyword, l, 0,
                "the set holds no node of an element; fix: correct the set");
      const bool rotation = k.dof >= 5;
      const int dof = rotation ? k.dof - 2 : k.dof - 1;  // model: 0-2 x, y, z; 3-5 rotations
      const std::size_t lcid_field = k.load ? 2 : 3;
      if (k.load) {
        model::NodalLoad ld;
        ld.name = fmt::format("load_{}", ++loads);
        ld.nodes = std::move(nodes);
        ld.dof = dof;
        ld.force = time_curve(k.lcid, k.sf, u_.force_N(), k.ref, k.keyword, l, lcid_field);
        m_.loads.push_back(std::move(ld));
      } else {
        model::PrescribedVelocity pv;
        pv.name = fmt::format("motion_{}", ++motions);
        pv.nodes = std::move(nodes);
        pv.dof = dof;
        pv.velocity = time_curve(k.lcid, k.sf, rotation ? 1.0 / u_.time_s : u_.velocity_m_s(),
                                 k.ref, k.keyword, l, lcid_field);
        m_.prescribed_velocities.push_back(std::move(pv));
      }
    }
  }

  /// *DATABASE_HISTORY_NODE(_ID|_SET): a probe per node, named by its heading or node_<NID>; a
  /// node named twice is probed once.
  void probes() {
    std::unordered_map<std::int64_t, int> seen;
    std::unordered_set<std::string> names;
    for (const HistoryNodeCard& h : d_.history_nodes) {
      const bool with_id = h.keyword.ends_with("_ID");
      const Layout l = with_id ? Layout(L::kIdHeading) : Layout(L::kHistoryIds);
      std::vector<std::int64_t> one{h.id};
      const auto& ids = h.set ? node_set(h.id, h.ref, h.keyword, l, h.field) : one;
      for (const auto id : ids) {
        const int c = node(id, h.ref, h.keyword.c_str(), l, h.field);
        if (c < 0 && h.set) continue;  // a set's node in no element: left out, as everywhere
        if (c < 0)
          fail_at(d_, h.ref, h.keyword, l, h.field,
                  fmt::format("node {} belongs to no element (crashlink leaves such nodes out); "
                              "fix: probe a node of an element",
                              id));
        if (!seen.emplace(id, c).second) continue;
        model::Probe p;
        // The heading names the probe (an HDF5 path element: no '/'); a heading met twice gets
        // the node id appended.
        p.name = h.heading.empty() ? fmt::format("node_{}", id) : h.heading;
        std::replace(p.name.begin(), p.name.end(), '/', '_');
        if (!names.insert(p.name).second) {
          const std::string base = p.name;
          p.name = fmt::format("{}_{}", base, id);
          for (int k = 2; !names.insert(p.name).second; ++k)
            p.name = fmt::format("{}_{}_{}", base, id, k);
        }
        p.kind = model::Probe::Kind::Node;
        p.index = c;
        m_.probes.push_back(std::move(p));
      }
    }
  }

  void controls() {
    if (!d_.has_end_time)
      throw InputError(d_.files.name(0), 0, "*CONTROL_TERMINATION",
                       "missing: the deck sets no end time; fix: add *CONTROL_TERMINATION with "
                       "ENDTIM");
    m_.controls.end_time_s = d_.end_time * u_.time_s;
    m_.controls.dt_scale = d_.tssfac;
    // *DATABASE_GLSTAT ... DT: one history interval for every series (the smallest given);
    // *DATABASE_BINARY_D3PLOT DT: the field states' interval.
    m_.controls.history_interval_s = d_.history_dt * u_.time_s;
    m_.controls.field_interval_s =
        d_.field_count > 0 ? m_.controls.end_time_s / static_cast<double>(d_.field_count)
                           : d_.field_dt * u_.time_s;
    if (d_.has_bulk) {
      m_.controls.bulk_q_quadratic = d_.bulk_q1;
      m_.controls.bulk_q_linear = d_.bulk_q2;
      m_.controls.shell_bulk_viscosity = d_.bulk_shells;
    }
    // *LOAD_BODY_*: a base acceleration a (LS-DYNA): the body load is -rho a, so gravity along
    // -z is *LOAD_BODY_Z with +9.81 m/s^2. Constant curves only.
    for (const auto& l : d_.body_loads) {
      const auto it = curves_.find(l.curve);
      if (it == curves_.end())
        fail_at(
            d_, l.ref, l.keyword, L::kLoadBody, 0,
            fmt::format("curve {} is not defined; fix: add *DEFINE_CURVE {}", l.curve, l.curve));
      const CurveCard& cv = d_.curves[static_cast<std::size_t>(it->second)];
      const double a0 = cv.sfo * (cv.o.front() + cv.offo);
      for (double o : cv.o)
        if (std::abs(cv.sfo * (o + cv.offo) - a0) > 1e-12 * std::abs(a0))
          fail_at(d_, l.ref, l.keyword, L::kLoadBody, 0,
                  fmt::format("curve {} changes in time ({} at {}:{}): crashlink's body "
                              "acceleration is constant; fix: a curve with one value",
                              l.curve, cv.keyword, d_.files.name(cv.ref.file), cv.ref.line));
      const double a_m_s2 = l.sf * a0 * u_.length_m / (u_.time_s * u_.time_s);
      m_.controls.gravity_m_s2[static_cast<std::size_t>(l.axis)] -= a_m_s2;
    }
  }

 public:
  std::size_t free_nodes_ = 0;
  std::vector<std::int64_t> empty_parts_;
  std::vector<std::string> d_notes_;  ///< notes found while building (read_deck prints them)

 private:
  const Deck& d_;
  const UnitSystem& u_;
  model::Model m_;
  IdMap nodes_, curves_, sections_, materials_, parts_;
  std::unordered_map<std::int64_t, int> part_index_, rigid_body_of_part_;
  std::unordered_map<std::string, int> used_names_;
  std::unordered_map<std::int64_t, std::vector<std::int64_t>> node_set_members_, part_set_members_;
  IdMap boxes_;
  std::unordered_map<std::string, int> used_contact_names_;
  std::unordered_set<std::string> used_wall_names_;
  std::unordered_set<int> inertia_bodies_;  ///< bodies whose velocity *PART_INERTIA gave
  std::unordered_map<std::int64_t, Mat3> frames_;
  bool last_was_node_ = false;
};

}  // namespace

std::vector<std::string> plausible_unit_systems(const Deck& deck) {
  std::vector<std::string> out;
  for (const auto& u : unit_systems()) {
    bool ok = true;
    for (const auto& m : deck.materials) {
      if (m.type == MaterialType::Rigid) continue;
      const double c = wave_speed_m_s(m, u);
      ok = ok && c >= kMinWaveSpeed_m_s && c <= kMaxWaveSpeed_m_s;
    }
    if (ok) out.emplace_back(u.name);
  }
  return out;
}

std::vector<std::string> inferable_unit_systems(const Deck& deck) {
  std::vector<std::string> out;
  const bool deformable = std::any_of(deck.materials.begin(), deck.materials.end(),
                                      [](const auto& m) { return m.type != MaterialType::Rigid; });
  if (!deformable) return out;
  for (const auto& u : unit_systems()) {
    bool ok = true;
    for (const auto& m : deck.materials) {
      if (m.type == MaterialType::Rigid) continue;
      const double c = wave_speed_m_s(m, u), rho = m.rho * u.density_kg_m3();
      ok = ok && c >= kMinWaveSpeed_m_s && c <= kMaxWaveSpeed_m_s && rho >= kMinDensity_kg_m3 &&
           rho <= kMaxDensity_kg_m3;
    }
    if (ok) out.emplace_back(u.name);
  }
  return out;
}

model::Model model_from_deck(const Deck& deck, const UnitSystem& units) {
  Builder b(deck, units);
  return b.build();
}

DeckRead read_deck(const std::string& path, const DeckOptions& options) {
  ParseOptions po;
  po.ignore = options.ignore;
  const Deck deck = parse_deck(path, po);
  const UnitSystem* units = find_unit_system(options.units);
  std::string inferred;
  if (!units && options.units.empty()) {
    // No system given: the one system in which the materials are crash materials, if one.
    const auto fits = inferable_unit_systems(deck);
    if (fits.size() == 1) {
      units = find_unit_system(fits[0]);
      inferred = fits[0];
    }
  }
  if (!units) {
    const auto fits = plausible_unit_systems(deck);
    const auto strict = inferable_unit_systems(deck);
    std::string fit_text, strict_text;
    for (const auto& f : fits) fit_text += (fit_text.empty() ? "" : ", ") + f;
    for (const auto& f : strict) strict_text += (strict_text.empty() ? "" : ", ") + f;
    throw InputError(
        path, 0, "--units",
        fmt::format("{}; a deck writes no units down{}; fix: pass --units with one of {} (the "
                    "materials' wave speeds fit: {}; their densities too: {})",
                    options.units.empty()
                        ? std::string("not given")
                        : fmt::format("'{}' is not a known system", options.units),
                    options.units.empty()
                        ? std::string(", and no single system makes every material's wave "
                                      "speed and density those of a crash material")
                        : std::string(),
                    unit_system_names(), fit_text.empty() ? std::string("none") : fit_text,
                    strict_text.empty() ? std::string("none") : strict_text));
  }
  Builder b(deck, *units);
  DeckRead out{b.build(), {}, {}, {}, std::string(units->name)};
  if (!inferred.empty())
    out.messages.push_back(fmt::format(
        "units: --units not given; read in {}, the only system in which every material's wave "
        "speed sqrt(E/RO) and density are those of a crash material ([{:.0f}, {:.0f}] m/s, "
        "[{:.0f}, "
        "{:.0f}] kg/m^3); pass --units to choose",
        inferred, kMinWaveSpeed_m_s, kMaxWaveSpeed_m_s, kMinDensity_kg_m3, kMaxDensity_kg_m3));
  for (std::uint32_t f = 0; f < deck.files.count(); ++f) out.files.push_back(deck.files.name(f));
  for (const PartCard& pc : deck.parts)
    if (std::find(b.empty_parts_.begin(), b.empty_parts_.end(), pc.id) == b.empty_parts_.end())
      out.part_ids.push_back(pc.id);
  // LS-DYNA keeps a shell's thickness unless *CONTROL_SHELL ISTUPD asks; crashlink's shells
  // always take it from the thickness strain (ISTUPD 1).
  const bool shells =
      std::any_of(out.model.parts.begin(), out.model.parts.end(),
                  [](const auto& p) { return p.kind == model::ElementKind::Shell4; });
  if (shells && deck.istupd == 0)
    out.messages.push_back(
        "shells: crashlink updates their thickness from the thickness strain (LS-DYNA's "
        "*CONTROL_SHELL ISTUPD 1); the deck leaves ISTUPD at 0, under which LS-DYNA keeps it: "
        "compare with ISTUPD 1");
  if (!deck.without_effect.empty()) {
    std::string s;
    for (const auto& [k, n] : deck.without_effect) s += (s.empty() ? "" : ", ") + k;
    out.messages.push_back("accepted without effect (crashlink writes its own output): " + s);
  }
  if (deck.history_dt_max > deck.history_dt)
    out.messages.push_back(
        fmt::format("crashlink writes every history at one interval: {:g} s, the smallest DT of {}",
                    out.model.controls.history_interval_s, [&] {
                      std::string s;
                      for (const auto& k : deck.history_dt_keywords)
                        s += (s.empty() ? "" : ", ") + k;
                      return s;
                    }()));
  for (const auto& [k, n] : deck.skipped_cards)
    out.messages.push_back(fmt::format("skipped on request (--ignore): {} ({} cards)", k, n));
  if (b.free_nodes_ > 0)
    out.messages.push_back(
        fmt::format("{} nodes belong to no element and are left out", b.free_nodes_));
  for (auto pid : b.empty_parts_)
    out.messages.push_back(fmt::format("part {} has no element and is left out", pid));
  for (const auto& n : deck.notes) out.messages.push_back(n);
  for (const auto& n : b.d_notes_) out.messages.push_back(n);
  return out;
}

bool is_deck_path(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext == ".k" || ext == ".key" || ext == ".dyn" || ext == ".kw";
}

}  // namespace crashlink::deck
