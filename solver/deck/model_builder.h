#pragma once
// The builder of a model from a parsed deck (model_from_deck.h), shared by its three files:
// model_builder.cpp (nodes, materials, parts, elements, sets, frames), model_conditions.cpp (the
// run's conditions: constraints, velocities, contacts, walls, motions and loads, probes, controls)
// and model_from_deck.cpp (the units and read_deck). Internal to crashlink::deck.
#include <fmt/format.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <set>
#include <string>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "solver/deck/deck.h"
#include "solver/deck/keyword_layouts.h"
#include "solver/deck/model_from_deck.h"
#include "solver/deck/units.h"
#include "solver/model/model.h"

namespace crashlink::deck::detail {

namespace L = layout;
using IdMap = std::unordered_map<std::int64_t, std::int32_t>;

inline std::string at(const Deck& d, const CardRef& r) {
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

inline double wave_speed_m_s(const MaterialCard& m, const UnitSystem& u) {
  return std::sqrt(m.E * u.stress_Pa() / (m.rho * u.density_kg_m3()));
}

class Builder {
 public:
  Builder(const Deck& d, const UnitSystem& u) : d_(d), u_(u) {}

  model::Model build();

 private:
  void index_nodes();

  int node(std::int64_t id, const CardRef& ref, const char* keyword, Layout l, std::size_t f);

  void materials();

  static std::string join(const std::vector<std::string>& v, const char* sep);

  /// *MAT_024's yield curve: LCSS, else the EPS/ES table, else SIGY/ETAN.
  materials::HardeningCurve hardening_024(const MaterialCard& c, double E_Pa);

  void parts();

  /// The part of element `e` of `cards` (its PID checked against the sections).
  int element_part(const ElementCards& cards, std::size_t e, bool shell);

  void elements();

  /// *PART_INERTIA on a rigid part: the body's mass, centre (NODEID's position if given),
  /// inertia tensor about it (global axes) and initial velocities, in SI. (*INITIAL_VELOCITY_
  /// GENERATION on the part, read later, replaces the translational velocity.)
  void part_inertia(const PartCard& pc, model::RigidBody& rb);

  /// QM of the part's *HOURGLASS (HGID), else *CONTROL_HOURGLASS's QH, else 0.1.
  double hourglass_coefficient(const PartCard& p);

  /// A shell's corners distinct except n3 = n4 (a triangle); a hexahedron's all distinct.
  void check_distinct(const std::int32_t* q, int k, bool shell, const CardRef& ref, const char* kw,
                      Layout l, std::size_t first);

  std::string part_name(const PartCard& p);

  /// Drops the nodes no element uses (they would have no mass), keeping the deck's order.
  void compact_nodes();

  /// The model index of deck node `id` (-1: a node in no element).
  int model_node(std::int64_t id, const CardRef& ref, const char* kw, Layout l, std::size_t f);

  void sets();

  /// The node ids one *SET_NODE_GENERAL card adds (ALL: every node; NODE: the ids, checked;
  /// PART: the nodes of the parts' elements; BOX: the nodes inside the boxes, bounds included).
  void general_members(const SetCard& s, const GeneralEntry& g, std::vector<std::int64_t>& ids);

  void boxes() { boxes_ = index_ids(d_, d_.boxes, L::kBox, "box"); }

  /// *DEFINE_COORDINATE_SYSTEM: the local axes e1 along O->L, e3 normal to O->L and O->P,
  /// e2 = e3 x e1 (LS-DYNA's construction), as the columns of the rotation local -> global.
  void coordinate_systems();

  /// The rotation local -> global of ICID (identity for 0), or the error at `field` of `ref`.
  Mat3 frame(std::int64_t icid, const CardRef& ref, const std::string& kw, Layout l,
             std::size_t field);

  void fail_member(const SetCard& s, std::size_t k);

  const std::vector<std::int64_t>& node_set(std::int64_t id, const CardRef& ref,
                                            const std::string& kw, Layout l, std::size_t field = 0);

  /// *CONSTRAINED_NODAL_RIGID_BODY (a body of nodes), *CONSTRAINED_EXTRA_NODES (nodes added to
  /// a rigid part's body), *CONSTRAINED_RIGID_BODIES (a rigid part's body merged into the lead
  /// part's), in deck order.
  void rigid_constraints();

  void constraints();

  void velocities();

  /// The model parts of a contact surface: SSTYP/MSTYP 2 (part set), 3 (part), 5 (all parts);
  /// id 0 of a single-surface contact: all parts. Parts without elements are left out.
  std::vector<int> surface_parts(const ContactCard& k, bool slave);

  /// The heading, else contact_<CID> or contact_<n> (n: the deck's order); a name already taken
  /// gets " (CID c)" or " (n)" appended (LS-DYNA allows repeated headings, crashlink's results
  /// need distinct names).
  std::string contact_name(const ContactCard& k, std::size_t i);

  /// The slave faces of SSTYP 0 (*SET_SEGMENT SSID): 4 model node indices each, in the set's
  /// order; each must be a face of an element.
  std::vector<std::int32_t> segment_faces(const ContactCard& k);
  static std::array<std::int32_t, 4> face_key(std::int32_t a, std::int32_t b, std::int32_t c,
                                              std::int32_t d);

  /// *CONTACT_* onto model::Contact (docs/decks.md "Contacts"): penalty_scale = 0.1 SFS (SLSFAC's
  /// default 0.1), SOFT 1 adds the mass-and-step stiffness scaled by SOFSCL, Coulomb friction
  /// mu = FD + (FS - FD) exp(-DC |v_rel|) as crashlink's.
  void contacts();

  /// *RIGIDWALL_PLANAR onto model::RigidWall: the plane through the tail point, normal along
  /// tail -> head (the side the nodes stay on), the nodes of NSID (0: every node).
  void rigid_walls();

  /// Curve `lcid` against time in SI: abscissa SFA (a + OFFA) [deck time] -> s, ordinate
  /// SF SFO (o + OFFO) x `unit` (LS-DYNA's *DEFINE_CURVE remark: offsets first, then scales).
  model::Curve time_curve(std::int64_t lcid, double sf, double unit, const CardRef& ref,
                          const std::string& keyword, Layout l, std::size_t field);

  /// *BOUNDARY_PRESCRIBED_MOTION_NODE/_SET (VAD 0: velocity) -> model::PrescribedVelocity,
  /// *LOAD_NODE_POINT/_SET -> model::NodalLoad (force per node), one dof each; a set's nodes in
  /// no element are left out.
  model::Curve displacement_to_velocity(const model::Curve& d, const CurveDofCard& k);
  void curve_dofs();

  /// *DATABASE_HISTORY_NODE(_ID|_SET): a probe per node, named by its heading or node_<NID>; a
  /// node named twice is probed once.
  void probes();

  void controls();

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
  std::int64_t max_weld_id_ = 0;               ///< the largest WID of the deck's spot welds
  std::unordered_set<std::int64_t> weld_ids_;  ///< the WIDs met so far
  std::unordered_map<std::int64_t, std::vector<std::int64_t>> node_set_members_, part_set_members_,
      shell_set_members_;
  /// shell element id -> (part index, element index), for *SET_SHELL_LIST
  std::unordered_map<std::int64_t, std::array<int, 2>> shell_at_;
  IdMap boxes_;
  std::unordered_map<std::string, int> used_contact_names_;
  std::unordered_set<std::string> used_wall_names_;
  std::unordered_set<int> inertia_bodies_;  ///< bodies whose velocity *PART_INERTIA gave
  std::unordered_map<std::int64_t, Mat3> frames_;
  bool last_was_node_ = false;
  int spot_welds_ = 0;  ///< welds named by their order (without _ID)
  std::set<std::array<std::int32_t, 4>> element_faces_;  ///< segment_faces' lookup
};

}  // namespace crashlink::deck::detail
