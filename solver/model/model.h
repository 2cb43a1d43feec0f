#pragma once
// The model: what a scenario describes, as flat arrays (structure of arrays). Pure input data:
// no solution state lives here (see solver/integration/state.h). SI units throughout.
//
// Array layouts (n = node count, ne = element count of a part):
//   Nodes::x0            [3n]  interleaved x,y,z of node i at 3i..3i+2            [m]
//   Part::connectivity   [k*ne] node indices (0-based) of element e at k*e..k*e+k-1,
//                        k = 8 (Hex8, LS-DYNA order: bottom face 0-3, top 4-7, both
//                        counter-clockwise seen from the top) or 4 (Shell4; triangle: n3 == n2)
#include <cstdint>
#include <string>
#include <vector>

#include "core/vec3.h"
#include "solver/materials/material.h"
#include "solver/model/curve.h"

namespace crashlink::model {

enum class ElementKind : std::uint8_t { Hex8, Shell4 };

inline int nodes_per_element(ElementKind k) {
  return k == ElementKind::Hex8 ? 8 : 4;
}

struct Nodes {
  std::vector<std::int64_t> id;  ///< [n] user ids (for messages and output)
  std::vector<double> x0;        ///< [3n] reference coordinates [m]

  std::size_t count() const { return id.size(); }
};

/// A part: elements of one kind, one material, one set of section properties.
struct Part {
  std::string name;
  std::int64_t user_id = 0;  ///< the user's part id (a deck's *PART PID); 0: none
  ElementKind kind = ElementKind::Hex8;
  int material = -1;                       ///< index into Model::materials
  std::vector<std::int32_t> connectivity;  ///< [k*ne], see the header comment
  std::vector<std::int64_t> element_id;    ///< [ne] user ids
  double thickness_m = 0.0;                ///< Shell4 only
  /// Shell4: [ne] or empty: each element's initial thickness [m] (a deck's
  /// *ELEMENT_SHELL_THICKNESS), overriding thickness_m.
  std::vector<double> element_thickness_m;
  int through_thickness_points = 5;    ///< Shell4 only: Gauss points through the thickness (>= 3)
  double hourglass_coefficient = 0.1;  ///< Flanagan–Belytschko / BT stiffness coefficient [-]
  /// Stiffness-proportional (Rayleigh beta) damping, LS-DYNA *DAMPING_PART_STIFFNESS: xi, the
  /// fraction of critical damping at each element's highest frequency, in [0, 0.5]; 0: none.
  /// The kernels add sigma_d = beta_e C : D with beta_e = xi_e dt_e (solver/elements/hex8.h).
  double damping_ratio = 0.0;
  /// [ne] or empty: per-element xi overriding damping_ratio (same range).
  std::vector<double> element_damping_ratio;
  /// Mass scaling (integration/mass_scaling.h, LS-DYNA *CONTROL_TIMESTEP DT2MS): [ne] or empty:
  /// each element's density is its material's times this factor (>= 1) in its mass, its stable
  /// step and its bulk viscosity; empty: 1.
  std::vector<double> element_density_scale;

  std::size_t element_count() const {
    return connectivity.size() / static_cast<std::size_t>(nodes_per_element(kind));
  }
  /// Initial thickness of shell element e [m] (element_thickness_m if given, else thickness_m).
  double thickness_of(std::size_t e) const {
    return element_thickness_m.empty() ? thickness_m : element_thickness_m[e];
  }
  /// Density factor of element e (mass scaling; 1 if none).
  double density_scale_of(std::size_t e) const {
    return element_density_scale.empty() ? 1.0 : element_density_scale[e];
  }
  /// xi of element e (element_damping_ratio if given, else damping_ratio).
  double damping_ratio_of(std::size_t e) const {
    return element_damping_ratio.empty() ? damping_ratio : element_damping_ratio[e];
  }
  /// True if some element has a positive damping ratio (the kernels then take the damped path).
  bool damped() const {
    if (element_damping_ratio.empty()) return damping_ratio > 0.0;
    for (double xi : element_damping_ratio)
      if (xi > 0.0) return true;
    return false;
  }
};

/// Degrees of freedom bit mask: bits 0-2 translations x,y,z; bits 3-5 rotations x,y,z.
enum DofBits : std::uint8_t { kUx = 1, kUy = 2, kUz = 4, kRx = 8, kRy = 16, kRz = 32 };

/// Velocity imposed on one dof of a node set, as a function of time.
struct PrescribedVelocity {
  std::string name;
  std::vector<std::int32_t> nodes;
  int dof = 0;     ///< 0..2 translation x,y,z [m/s]; 3..5 rotation [rad/s]
  Curve velocity;  ///< [m/s] or [rad/s] against time [s]
  /// >= 0: the motion is the rigid body's (index into Model::rigid_bodies; nodes empty): its
  /// centre's velocity (dof 0..2) or its angular velocity about a global axis (3..5), LS-DYNA
  /// *BOUNDARY_PRESCRIBED_MOTION_RIGID.
  int rigid_body = -1;
};

/// Force on one translational dof of each node of a set, as a function of time.
struct NodalLoad {
  std::string name;
  std::vector<std::int32_t> nodes;
  int dof = 0;  ///< 0..2
  Curve force;  ///< [N] per node against time [s]
};

/// v_i = velocity + omega x (x_i - centre) at each node (LS-DYNA *INITIAL_VELOCITY_GENERATION
/// with OMEGA: a spin about the axis through centre); the nodes with rotations also turn at
/// omega.
struct InitialVelocity {
  std::vector<std::int32_t> nodes;
  Vec3 velocity_m_s{};
  Vec3 angular_velocity_rad_s{};  ///< omega (0: a translation)
  Vec3 centre_m{};                ///< a point of the spin's axis
  /// The velocity of node position x.
  Vec3 at(const Vec3& x) const {
    return velocity_m_s + cross(angular_velocity_rad_s, x - centre_m);
  }
};

/// A rigid body made of the elements of rigid parts and of extra nodes; its nodes follow its
/// motion. Mass and inertia come from the nodes' lumped masses unless given (then they
/// override). A body of nodes only is LS-DYNA's nodal rigid body (*CONSTRAINED_NODAL_RIGID_BODY);
/// nodes added to a rigid part's body, *CONSTRAINED_EXTRA_NODES. An extra node of deformable
/// shells also turns with the body (its rotational inertia in the body's, its moments in the
/// body's torque).
struct RigidBody {
  std::string name;
  std::vector<int> parts;           ///< indices of rigid parts forming the body (may be empty)
  std::vector<std::int32_t> nodes;  ///< extra node indices that follow the body (may be empty)
  Vec3 velocity_m_s{};              ///< initial velocity of the centre of mass (or see below)
  Vec3 angular_velocity_rad_s{};    ///< initial angular velocity (spatial)
  /// velocity_m_s is that of the body's point at velocity_point_m (a spin about an axis through
  /// it: LS-DYNA *INITIAL_VELOCITY_GENERATION OMEGA); the centre's is velocity + omega x (c - p).
  bool velocity_at_point = false;
  Vec3 velocity_point_m{};
  double mass_kg = 0.0;  ///< > 0: overrides the elements' mass
  bool inertia_given = false;
  Mat3 inertia_kg_m2{};  ///< about the centre of mass, spatial frame at t = 0
  bool centre_given = false;
  Vec3 centre_m{};  ///< centre of mass if given
  /// DofBits of the body held at zero velocity: its centre's translations (bits 0-2) and its
  /// rotations about the global axes (3-5) (LS-DYNA *MAT_RIGID CMO 1, CON1/CON2).
  std::uint8_t fixed = 0;
  /// A spot weld (LS-DYNA *CONSTRAINED_SPOTWELD): a body of two nodes (no parts) that lets go
  /// of them when (max(f_n, 0) / S_n)^n + (|f_s| / S_s)^m >= 1, f_n the force it carries along
  /// node 1 -> node 2 and f_s across, or at time_s. A strength of 0 leaves its term out.
  struct Failure {
    double normal_N = 0.0;  ///< S_n [N] (0: no normal term)
    double shear_N = 0.0;   ///< S_s [N] (0: no shear term)
    double exp_n = 2.0, exp_m = 2.0;
    double time_s = 0.0;  ///< > 0: fails then whatever the forces [s]
    bool any() const { return normal_N > 0.0 || shear_N > 0.0 || time_s > 0.0; }
  } failure;
};

/// A fixed, infinite, frictionless plane that its nodes cannot cross (LS-DYNA
/// *RIGIDWALL_PLANAR): a node that would cross it in a step is stopped on it (its normal velocity
/// set so that x^{n+1} lies on the plane; a perfectly plastic impact of the node), and it leaves
/// freely. The wall's reaction does work (booked as external work, integration/solver.cpp).
struct RigidWall {
  std::string name;
  Vec3 point_m{};                   ///< a point of the plane (Cylinder: of the axis, its tail)
  Vec3 normal{};                    ///< unit normal pointing to the side the nodes stay on
  std::vector<std::int32_t> nodes;  ///< node indices the wall stops
  /// A moving wall (LS-DYNA *RIGIDWALL_PLANAR_MOVING): its mass [kg] (0: fixed) and initial
  /// velocity along `normal` [m/s] (> 0: toward the nodes); it moves along its normal only.
  double mass_kg = 0.0;
  double velocity_m_s = 0.0;
  /// Plane: an infinite plane, or with length_m > 0 the rectangle point + a edge + b (normal x
  /// edge), 0 <= a <= length_m, 0 <= b <= width_m (LS-DYNA _FINITE, *RIGIDWALL_GEOMETRIC_FLAT).
  /// Cylinder (*RIGIDWALL_GEOMETRIC_CYLINDER): the nodes stay outside the cylinder of radius
  /// radius_m about the axis point + s normal (normal: the unit axis), 0 <= s <= length_m if
  /// length_m > 0, else of infinite length. A finite wall or a cylinder acts on the nodes over
  /// it (within its extent, on its side or on it): a node that went round its edge is free.
  enum class Shape : std::uint8_t { Plane, Cylinder } shape = Shape::Plane;
  Vec3 edge{};            ///< Plane, finite: unit vector in the plane along the length
  double length_m = 0.0;  ///< > 0: finite (Plane: along edge; Cylinder: along the axis) [m]
  double width_m = 0.0;   ///< Plane, finite: along normal x edge [m]
  double radius_m = 0.0;  ///< Cylinder [m]
  bool moving() const { return mass_kg > 0.0; }
  bool finite() const { return length_m > 0.0; }
};

/// How a contact pairs its surfaces (solver/contact/contact_interface.cpp).
enum class ContactKind : std::uint8_t {
  /// one pass: the slave nodes against the master segments (LS-DYNA NODES_TO_SURFACE)
  NodeToSurface,
  /// two passes: also the master surface's nodes against the slave surface's segments, the
  /// faces made of slave nodes (LS-DYNA SURFACE_TO_SURFACE, the crash codes' default)
  SurfaceToSurface,
  /// one surface against itself: the master parts' nodes against their own segments, the
  /// segments around each node excluded (LS-DYNA SINGLE_SURFACE / AUTOMATIC_SINGLE_SURFACE)
  SingleSurface,
};

/// Penalty contact, [1] and §2.1 of Bourel 2005: slave nodes against the segments of master
/// parts (shell quads/triangles with thickness offsets on both sides, exterior faces of
/// hexahedra), and for two-pass contact the master nodes against the slave faces. Friction:
/// Coulomb with exponential decay from static to dynamic, mu = mu_d + (mu_s - mu_d)
/// exp(-decay |v_rel|).
struct Contact {
  std::string name;
  ContactKind kind = ContactKind::SurfaceToSurface;
  std::vector<std::int32_t> slave_nodes;  ///< node indices (SingleSurface: unused)
  std::vector<int> master_parts;          ///< part indices whose elements give the segments
  /// SurfaceToSurface: the slave faces, 4 node indices each (a triangle repeats its third);
  /// empty: derived from the model (contact::slave_faces), as the partition does on the whole
  /// model before cutting it, so that a sub-model's cut faces never count as surface.
  std::vector<std::int32_t> slave_faces;
  double penalty_scale = 0.1;  ///< scale factor on the segment stiffness [-]
  bool soft = true;            ///< also a stiffness from nodal mass and step
  double soft_scale = 0.1;     ///< scale on k_soft = m / dt^2 [-]
  /// Contact thickness of the slave side's shells and of the master side's (LS-DYNA SST, MST),
  /// in place of their own: the thickness offsets of their nodes and faces are half of it [m];
  /// 0: the shells' own. Solid faces keep offset 0. Single surface: slave_thickness_m for all.
  double slave_thickness_m = 0.0, master_thickness_m = 0.0;
  double static_friction = 0.0;     ///< mu_s [-]
  double dynamic_friction = 0.0;    ///< mu_d [-]
  double friction_decay_s_m = 0.0;  ///< decay coefficient [s/m]
};

/// A point whose history is written to /history/probes/<name>.
struct Probe {
  std::string name;
  enum class Kind : std::uint8_t { Node, RigidBody } kind = Kind::Node;
  int index = -1;  ///< node index or rigid body index
};

/// Run controls.
struct Controls {
  double end_time_s = 0.0;
  double dt_scale = 0.9;              ///< safety factor on the stable step [-]
  double dt_max_s = 0.0;              ///< > 0: upper bound on the step
  double history_interval_s = 0.0;    ///< glstat/probe sampling; 0: every cycle
  double field_interval_s = 0.0;      ///< field states; 0: first and last only
  bool bulk_viscosity = true;         ///< linear + quadratic artificial bulk viscosity
  double bulk_q_linear = 0.06;        ///< Q1 [-] (crash-code default)
  double bulk_q_quadratic = 1.5;      ///< Q2 [-] (crash-code default)
  bool shell_bulk_viscosity = false;  ///< apply it to shells too (membrane)
  /// Q1 term in expansion too (Abaqus/Explicit's linear bulk viscosity; Q2 stays compression
  /// only). Off by default: LS-DYNA's convention, no viscous pressure in expansion.
  bool bulk_linear_in_expansion = false;
  double energy_tolerance = 0.05;  ///< guard: (|balance| + contact-created) / reference energy
  /// The whole model's energy scale [J] (integration/energy_scale.h), under the guard's reference
  /// energy as a floor: set by the decomposition in every domain's sub-model so that a domain at
  /// rest is judged at the model's scale; 0 (a scenario, a single domain): the solver's own.
  double model_energy_scale_J = 0.0;
  Vec3 gravity_m_s2{};  ///< body acceleration
  /// Conventional mass scaling (LS-DYNA DT2MS < 0, applied at t = 0 by
  /// integration::apply_mass_scaling): every deformable element whose stable step (no safety
  /// factor) is below this gets the density that brings it there [s]; 0: none.
  double mass_scaling_dt_s = 0.0;
  /// The stable step from the assembled mesh's highest frequency (integration::GlobalStep,
  /// docs/elements.md "Global stable step") instead of each element's own estimate alone.
  bool global_stable_step = false;
};

/// A subdomain of the decomposition (docs/decomposition.md, docs/design.md §2.7): the parts it
/// holds (indices into Model::parts; every part in exactly one domain).
struct Domain {
  std::string name;
  std::vector<int> parts;
};

/// Damping confined to the element layers around every `layer` interface (docs/design.md §2.7: the
/// coupling study's stabiliser for 2-D/3-D; docs/multirate.md "Long-run stability"). The layer
/// decomposition (solver/partition) sets element_damping_ratio = max(own, ratio) on every element
/// within `layers` element layers of an interface's far nodes J, on both sides (the moved layer is
/// the fine side's first). Stiffness-proportional, like Part::damping_ratio. ratio 0: off; the
/// `paper` scheme and single-domain runs ignore it.
struct InterfaceDamping {
  double ratio = 0.0;  ///< xi at each element's highest frequency, in [0, 0.5]
  int layers = 3;      ///< element layers on each side of J (>= 1)
};

/// Options of the coupling between domains (scenario key `coupling`, docs/scenario-format.md).
struct Coupling {
  InterfaceDamping interface_damping;
};

struct Model {
  std::string name;
  Nodes nodes;
  std::vector<materials::Material> materials;
  std::vector<Part> parts;
  std::vector<std::uint8_t> fixed;  ///< [n] DofBits mask per node
  std::vector<PrescribedVelocity> prescribed_velocities;
  std::vector<NodalLoad> loads;
  std::vector<InitialVelocity> initial_velocities;
  std::vector<RigidBody> rigid_bodies;
  std::vector<Contact> contacts;
  std::vector<RigidWall> rigid_walls;
  std::vector<Probe> probes;
  Controls controls;
  std::vector<Domain> domains;  ///< scenario order; empty: a single-domain run
  Coupling coupling;            ///< used by the decomposition only

  /// Index of the node with user id `id`, or -1.
  int node_index(std::int64_t id) const;
  int part_index(const std::string& name) const;
  std::size_t element_count() const;
};

/// True if part p's material is rigid (its elements carry geometry and mass only).
inline bool is_rigid(const Model& m, const Part& p) {
  return m.materials[static_cast<std::size_t>(p.material)].kind == materials::MaterialKind::Rigid;
}

/// Structural checks (sizes, index ranges, materials, thickness); throws ModelError with the fix.
void validate(const Model& m);

}  // namespace crashlink::model
