#pragma once
// The composer of export_deck (deck_writer.h), shared by its files: deck_writer.cpp (the deck's
// head, controls and the scenario beside it), composer_model.cpp (nodes, parts, sections,
// materials, elements, rigid bodies) and composer_conditions.cpp (constraints, velocities,
// loads, contacts, walls, probes). Internal to crashlink::deck_writer.
#include <cstdint>
#include <sstream>
#include <string>
#include <vector>

#include "solver/deck/keyword_layouts.h"
#include "solver/deck/units.h"
#include "solver/deck_writer/deck_writer.h"
#include "solver/deck_writer/keyword_block.h"
#include "solver/integration/rigid_body.h"
#include "solver/model/model.h"

namespace crashlink::deck_writer::detail {

namespace L = deck::layout;

class Composer {
 public:
  Composer(const model::Model& m, const deck::UnitSystem& u) : m_(m), u_(u) {}

  ExportText compose(const std::string& deck_name, const std::string& source);

 private:
  // deck_writer.cpp
  void head(const std::string& source);
  void controls();
  std::string scenario(const std::string& deck_name) const;

  // composer_model.cpp
  void check_exportable() const;
  void nodes();
  void materials();
  void parts();
  void elements();

  // composer_conditions.cpp
  /// Rigid bodies beyond one part: *CONSTRAINED_RIGID_BODIES, *CONSTRAINED_EXTRA_NODES_SET,
  /// *CONSTRAINED_NODAL_RIGID_BODY_TITLE (and its velocity as *INITIAL_VELOCITY on its nodes).
  void rigid_constraints();
  /// The velocities of bodies of nodes, as *INITIAL_VELOCITY on their nodes after every other.
  void rigid_body_velocities();
  /// *INITIAL_VELOCITY of node set `sid` at `v_m_s` (SI, converted).
  void initial_velocity(std::int64_t sid, const Vec3& v_m_s);
  void constraints();
  void initial_velocities();
  void curve_dofs();
  void contacts();
  void rigid_walls();
  void probes();

  /// Writes a *SET_NODE_LIST_TITLE of `nodes` (model indices) and returns its id.
  std::int64_t node_set(const std::vector<std::int32_t>& nodes, const std::string& title);
  /// Writes a *SET_PART_LIST_TITLE of `parts` (model indices, in order) and returns its id.
  std::int64_t part_set(const std::vector<int>& parts, const std::string& title);
  /// Writes a *DEFINE_CURVE_TITLE of `c` (time [s] -> value x `unit_SI`, converted to the
  /// deck's units) and returns its id; a one-point curve is written constant over [0, end].
  std::int64_t curve(const model::Curve& c, double value_unit_SI, const std::string& title);
  std::int64_t curve(const std::vector<double>& a, const std::vector<double>& o,
                     const std::string& title);

  void emit(const KeywordBlock& b) { b.write(out_, rounding_); }
  void comment(const std::string& text) { out_ << "$ " << text << '\n'; }

  /// SI -> deck units.
  double length(double v_m) const { return v_m / u_.length_m; }
  double mass(double v_kg) const { return v_kg / u_.mass_kg; }
  double time(double v_s) const { return v_s / u_.time_s; }
  double velocity(double v_m_s) const { return v_m_s / u_.velocity_m_s(); }
  double stress(double v_Pa) const { return v_Pa / u_.stress_Pa(); }
  double density(double v_kg_m3) const { return v_kg_m3 / u_.density_kg_m3(); }
  double force(double v_N) const { return v_N / u_.force_N(); }

  std::int64_t node_id(std::int32_t i) const { return m_.nodes.id[static_cast<std::size_t>(i)]; }

  const model::Model& m_;
  const deck::UnitSystem& u_;
  std::ostringstream out_;
  Rounding rounding_;
  std::vector<std::string> notes_;
  std::vector<std::int64_t> part_id_;  ///< the *PART PID of each model part
  /// The rigid bodies as the solver builds them (centre, mass, inertia), model order; set by
  /// parts() for *PART_INERTIA and a nodal body's _INERTIA.
  std::vector<integration::RigidBodyState> body_states_;
  /// A body of nodes only with a given mass, inertia, centre or angular velocity: written as
  /// *CONSTRAINED_NODAL_RIGID_BODY_INERTIA.
  static bool nodal_inertia_given(const model::RigidBody& rb) {
    return rb.parts.empty() &&
           (rb.mass_kg > 0.0 || rb.inertia_given || rb.centre_given ||
            rb.angular_velocity_rad_s[0] != 0.0 || rb.angular_velocity_rad_s[1] != 0.0 ||
            rb.angular_velocity_rad_s[2] != 0.0);
  }
  /// *MAT_RIGID's (and a nodal body's _SPC) CON1/CON2 code of three held axes (bits x, y, z).
  static long long con_code(int bits) {
    static constexpr long long kCode[8] = {0, 1, 2, 4, 3, 6, 5, 7};
    return kCode[bits & 7];
  }
  std::int64_t next_node_set_ = 1, next_part_set_ = 1, next_segment_set_ = 1, next_curve_ = 1;
};

/// Ids 8 ids to a card, as *SET_*_LIST and *DATABASE_HISTORY_NODE write them.
void list_cards(KeywordBlock& b, const std::vector<std::int64_t>& ids);

}  // namespace crashlink::deck_writer::detail
