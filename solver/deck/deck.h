#pragma once
// A keyword deck as read: the supported keywords' cards in the deck's own units, each record
// with the card it came from (file, line, format) so that the model building that follows can
// point at the field of any mistake. parse_deck fills it in one pass; references (node, part,
// section, material, curve, set ids) are resolved afterwards by model_from_deck.
#include <array>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "solver/deck/card.h"
#include "solver/deck/parameters.h"

namespace crashlink::deck {

struct NodeCards {
  std::vector<std::int64_t> id;
  std::vector<double> x;  ///< [3n] deck length units
  std::vector<CardRef> ref;
};

/// *ELEMENT_SHELL (k = 4) or *ELEMENT_SOLID (k = 8) records.
struct ElementCards {
  std::vector<std::int64_t> id, part;
  std::vector<std::int64_t> nodes;     ///< [k per element] node ids
  std::vector<CardRef> ref;            ///< the card holding the node ids
  std::vector<std::int32_t> id_line;   ///< the line holding EID and PID (two-card solids: above)
  std::vector<std::uint8_t> two_card;  ///< solids: 1 if written as "EID PID" + "N1..N10"
  /// shells of *ELEMENT_SHELL_THICKNESS: THIC1-THIC4 (deck length; 0: the section's); else
  /// empty
  std::vector<std::array<double, 4>> thickness;
  std::size_t count() const { return id.size(); }
};

struct PartCard {
  std::int64_t id = 0, section = 0, material = 0, hourglass = 0;
  std::string title;
  std::string keyword = "*PART";
  CardRef ref;  ///< the card with PID, SECID, MID
  /// *PART_INERTIA (deck units): centre (or NODEID's position), mass, inertia tensor IXX IXY IXZ
  /// IYY IYZ IZZ about the centre, initial velocity and angular velocity.
  bool inertia = false;
  std::array<double, 3> centre{};
  double mass = 0.0;
  std::int64_t centre_node = 0;
  std::array<double, 6> tensor{};
  std::array<double, 3> velocity{}, angular_velocity{};
  CardRef inertia_ref;  ///< card 3 (TM)
};

struct SectionCard {
  std::int64_t id = 0;
  bool shell = true;
  int nip = 0;
  double thickness = 0.0;  ///< T1, deck length units
  /// T1-T4 (blank or 0: T1), deck length units; unequal: each shell takes their mean
  std::array<double, 4> corner{};
  bool shrf_blank = true;
  std::string keyword;
  CardRef ref;
};

enum class MaterialType : std::uint8_t { Elastic, PlasticKinematic, PiecewiseLinear, Rigid };

struct MaterialCard {
  std::int64_t id = 0;
  MaterialType type = MaterialType::Elastic;
  std::string keyword;  ///< as written, e.g. *MAT_024
  std::string title;
  double rho = 0.0, E = 0.0, nu = 0.0, sigy = 0.0, etan = 0.0;  ///< deck units
  std::int64_t lcss = 0;                                        ///< *MAT_024 LCSS
  std::vector<double> eps, es;                                  ///< *MAT_024 8-point table
  double rate_c = 0.0, rate_p = 0.0;  ///< Cowper-Symonds SRC/SRP (003), C/P (024), deck units
  std::uint8_t rigid_fixed = 0;  ///< *MAT_RIGID CMO 1: held dofs (model::DofBits) from CON1/CON2
  CardRef ref;                   ///< the card with MID
};

struct CurveCard {
  std::int64_t id = 0;
  double sfa = 1.0, sfo = 1.0, offa = 0.0, offo = 0.0;
  std::vector<double> a, o;  ///< points as written (scaled later)
  std::string keyword;
  CardRef ref;
};

/// One data card of *SET_NODE_GENERAL: ALL, NODE (ids), PART (ids), BOX (box ids).
struct GeneralEntry {
  enum class Option : std::uint8_t { All, Node, Part, Box } option = Option::All;
  std::vector<std::int64_t> ids;
  std::vector<std::uint8_t> field;  ///< each id's field on the card (1-7: E1-E7)
  CardRef ref;
};

struct SetCard {
  std::int64_t id = 0;
  bool parts = false;                 ///< *SET_PART_*; else *SET_NODE_* (or shells)
  bool shells = false;                ///< *SET_SHELL_LIST: shell element ids
  std::vector<GeneralEntry> general;  ///< *SET_NODE_GENERAL
  std::vector<std::int64_t> members;
  std::vector<CardRef> member_ref;                  ///< one per member (the card listing it)
  std::vector<std::array<std::int64_t, 2>> ranges;  ///< _GENERATE
  std::vector<CardRef> range_ref;
  std::string keyword;
  CardRef ref;
};

/// *SET_SEGMENT: faces given by their corners (a triangle repeats N3 as N4).
struct SegmentSetCard {
  std::int64_t id = 0;
  std::vector<std::int64_t> nodes;   ///< [4 per segment] node ids
  std::vector<CardRef> segment_ref;  ///< the card of each segment
  std::string keyword;
  CardRef ref;
};

/// *CONSTRAINED_NODAL_RIGID_BODY (a body of the nodes of NSID), *CONSTRAINED_EXTRA_NODES_NODE /
/// _SET (nodes added to rigid part PID's body), *CONSTRAINED_RIGID_BODIES (part PIDC's body
/// merged into part PID's) or *CONSTRAINED_SPOTWELD (a breakable body of nodes N1, N2).
struct RigidConstraintCard {
  enum class Kind : std::uint8_t {
    NodalBody,
    ExtraNodes,
    MergeBodies,
    SpotWeld  ///< *CONSTRAINED_SPOTWELD: pid the WID (0: none), target N1, n2 N2
  } kind = Kind::NodalBody;
  std::int64_t n2 = 0;
  double sn = 0.0, ss = 0.0, exp_n = 0.0, exp_m = 0.0, tf = 0.0;  ///< SpotWeld, deck units
  std::int64_t pid = 0;     ///< the body's PID (NodalBody), the rigid part (ExtraNodes), PIDL
  std::int64_t target = 0;  ///< NSID (NodalBody), NID or NSID (ExtraNodes), PIDC (MergeBodies)
  bool set = false;   ///< ExtraNodes: target is a node set; SpotWeld: target is NSID (GENERALIZED)
  std::string title;  ///< NodalBody _TITLE: the body's name
  /// NodalBody _INERTIA: the body's centre, mass, inertia and velocities (as *PART_INERTIA's
  /// cards 3-5: inertia.centre ... inertia.angular_velocity, inertia.inertia_ref)
  bool has_inertia = false;
  PartCard inertia;
  /// NodalBody _SPC: held dofs (model::DofBits) from CMO 1, CON1, CON2
  std::uint8_t fixed = 0;
  std::string keyword;
  CardRef ref;
};

struct SpcCard {
  std::int64_t target = 0;  ///< node id or node set id
  bool set = false;
  std::uint8_t mask = 0;  ///< model::DofBits
  std::string keyword;
  CardRef ref;
};

/// *BOUNDARY_PRESCRIBED_MOTION_NODE/_SET (velocity) or *LOAD_NODE_POINT/_SET: one dof of a node
/// or node set driven by a curve.
struct CurveDofCard {
  std::int64_t target = 0;  ///< node id or node set id
  bool set = false;
  bool load = false;   ///< *LOAD_NODE_*: a force; else a prescribed velocity
  int dof = 0;         ///< the deck's DOF: 1-3 translations, 5-7 rotations (motion only)
  bool rigid = false;  ///< *BOUNDARY_PRESCRIBED_MOTION_RIGID: target is a rigid part's id
  int vad = 0;         ///< motion: 0 the curve is a velocity, 2 a displacement
  std::int64_t lcid = 0;
  double sf = 1.0;
  std::string keyword;
  CardRef ref;
};

struct VelocityCard {
  std::int64_t target = 0;  ///< node, part, part set or node set id
  int styp = 0;  ///< *INITIAL_VELOCITY_GENERATION: 1 part set, 2 part, 3 node set; 0 node;
                 ///< 4: *INITIAL_VELOCITY (node set NSID, 0: every node)
  std::array<double, 3> v{};  ///< deck velocity units, in the system ICID
  std::int64_t icid = 0;      ///< *DEFINE_COORDINATE_SYSTEM id; 0: global axes
  /// *INITIAL_VELOCITY_GENERATION card 2 IRIGID: 1 overrides a *PART_INERTIA body's velocity
  /// (0, the default, keeps it).
  int irigid = 0;
  /// *INITIAL_VELOCITY_GENERATION OMEGA (rad per deck time unit) about the axis through card 2's
  /// XC YC ZC along NX NY NZ (global axes, deck length units)
  double omega = 0.0;
  std::array<double, 3> centre{}, axis{};
  CardRef ref2;  ///< card 2
  std::string keyword;
  CardRef ref;
};

/// *DEFINE_BOX: an axis-aligned box, deck length units.
struct BoxCard {
  std::int64_t id = 0;
  std::array<double, 3> lo{}, hi{};
  std::string keyword;
  CardRef ref;
};

/// *DEFINE_COORDINATE_SYSTEM: origin O, a point L on the local x axis, a point P in the local
/// x-y plane (deck length units).
struct CoordinateSystemCard {
  std::int64_t id = 0;
  std::array<double, 3> o{}, l{}, p{};
  std::string keyword;
  CardRef ref;
};

/// *CONTACT_..._(AUTOMATIC_)SURFACE_TO_SURFACE / NODES_TO_SURFACE / SINGLE_SURFACE.
struct ContactCard {
  enum class Kind : std::uint8_t { SurfaceToSurface, NodesToSurface, SingleSurface };
  Kind kind = Kind::SurfaceToSurface;
  bool automatic = true;
  std::string keyword, heading;
  std::int64_t cid = 0;  ///< the ID card's CID (_ID, _TITLE), 0 without
  std::int64_t ssid = 0, msid = 0;
  int sstyp = 0, mstyp = 0;
  double fs = 0.0, fd = 0.0, dc = 0.0;  ///< friction; DC in deck time / length
  double sfs = 1.0, sfm = 1.0;          ///< penalty scale factors
  double sst = 0.0, mst = 0.0;          ///< contact thicknesses (0: the shells'), deck length
  int soft = 0;
  double sofscl = 0.1;
  int cards = 0;  ///< data cards read (the ID card not counted)
  CardRef ref;    ///< card 1 (SSID ...)
  CardRef ref3;   ///< card 3 (SFS ...), if written
};

/// *HOURGLASS (per part through HGID) or *CONTROL_HOURGLASS (id 0: every part without HGID).
struct HourglassCard {
  std::int64_t id = 0;
  int ihq = 0;      ///< 0: blank (LS-DYNA's default, 1)
  double qm = 0.1;  ///< coefficient
  std::string keyword;
  CardRef ref;
};

/// *LOAD_BODY_X / _Y / _Z: a base acceleration along one axis, curve LCID scaled by SF.
struct BodyLoadCard {
  int axis = 0;
  std::int64_t curve = 0;
  double sf = 1.0;
  std::string keyword;
  CardRef ref;
};

/// *RIGIDWALL_PLANAR(_FINITE)(_MOVING) and *RIGIDWALL_GEOMETRIC_FLAT / _CYLINDER: a plane
/// through the tail point, normal from tail to head (the nodes' side), or a cylinder about the
/// axis from tail to head, stopping the nodes of NSID (0: all).
struct RigidWallCard {
  enum class Kind : std::uint8_t { Planar, Flat, Cylinder } kind = Kind::Planar;
  std::string keyword, heading;
  std::int64_t nsid = 0;
  std::array<double, 3> tail{}, head{};
  bool finite = false;                ///< _FINITE (GEOMETRIC_FLAT: always): XHEV.. LENL LENM
  std::array<double, 3> edge_head{};  ///< XHEV, YHEV, ZHEV: the head of the edge l from the tail
  double len_l = 0.0, len_m = 0.0;    ///< LENL, LENM (deck units)
  double radius = 0.0, length = 0.0;  ///< Cylinder: RADCYL, LENCYL (deck units)
  bool moving = false;                ///< _MOVING: MASS, V0
  double mass = 0.0, v0 = 0.0;        ///< deck units
  int cards = 0;
  CardRef ref;        ///< card 1
  CardRef ref2;       ///< card 2
  CardRef ref_shape;  ///< the FINITE / FLAT / CYLINDER card
  CardRef ref3;       ///< the _MOVING card
  int needed() const { return 2 + (finite || kind == Kind::Cylinder ? 1 : 0) + (moving ? 1 : 0); }
};

/// One node (or node set) of *DATABASE_HISTORY_NODE(_ID|_SET): a probe.
struct HistoryNodeCard {
  std::string keyword, heading;  ///< heading: _ID's HEADING
  std::int64_t id = 0;           ///< NID, or the set's SID
  bool set = false;
  std::size_t field = 0;  ///< the id's field on its card
  CardRef ref;
};

struct Deck {
  DeckFiles files;
  Parameters params;
  std::string title;
  NodeCards nodes;
  ElementCards shells, solids;
  std::vector<PartCard> parts;
  std::vector<SectionCard> sections;
  std::vector<MaterialCard> materials;
  std::vector<CurveCard> curves;
  std::vector<SetCard> sets;
  std::vector<SegmentSetCard> segment_sets;
  std::vector<SpcCard> spcs;
  std::vector<RigidConstraintCard> rigid_constraints;  ///< in deck order
  std::vector<VelocityCard> velocities;
  std::vector<BoxCard> boxes;
  std::vector<CoordinateSystemCard> coordinate_systems;
  std::vector<ContactCard> contacts;
  std::vector<HourglassCard> hourglass;  ///< *HOURGLASS
  bool has_control_hourglass = false;
  HourglassCard control_hourglass;       ///< *CONTROL_HOURGLASS
  bool has_bulk = false;                 ///< *CONTROL_BULK_VISCOSITY
  double bulk_q1 = 1.5, bulk_q2 = 0.06;  ///< quadratic, linear (LS-DYNA's names)
  bool bulk_shells = false;              ///< TYPE -2
  std::vector<BodyLoadCard> body_loads;
  std::vector<RigidWallCard> rigid_walls;
  std::vector<CurveDofCard> curve_dofs;  ///< prescribed motions and nodal loads, in deck order
  bool has_end_time = false;
  double end_time = 0.0;  ///< ENDTIM, deck time units
  double tssfac = 0.9;
  double dt2ms = 0.0;   ///< *CONTROL_TIMESTEP DT2MS (deck time; < 0: mass scaling), 0: none
  double slsfac = 0.1;  ///< *CONTROL_CONTACT SLSFAC: the penalty scale per unit SFS
  bool has_control_shell = false;
  int istupd = 0;  ///< *CONTROL_SHELL ISTUPD (LS-DYNA's default 0: no thinning)
  /// The smallest DT of the ASCII histories (*DATABASE_GLSTAT, ...), deck time units; 0: none.
  double history_dt = 0.0;
  double history_dt_max = 0.0;  ///< the largest of those DTs (a note when it differs)
  std::vector<std::string> history_dt_keywords;  ///< the keywords that set one (DT > 0)
  double field_dt = 0.0;         ///< *DATABASE_BINARY_D3PLOT DT, deck time units; 0: none
  std::int64_t field_count = 0;  ///< its NPLTC: ENDTIM / NPLTC in place of DT when > 0
  std::vector<HistoryNodeCard> history_nodes;
  /// *DATABASE_RBDOUT given: every rigid body's motion is a probe (named after the body).
  bool rigid_body_output = false;
  /// Keywords accepted but without effect in crashlink (*DATABASE_*), and how many times.
  std::map<std::string, int> without_effect;
  /// Keywords skipped on request (--ignore), with their cards counted.
  std::map<std::string, int> skipped_cards;
  std::vector<std::string> notes;  ///< readings the user should know about (LS-DYNA defaults)
};

struct ParseOptions {
  /// Keywords to skip (upper case, with or without '*'); each must be met at least once.
  std::vector<std::string> ignore;
};

/// Reads the deck at `path` and every file it includes. Throws InputError at the first mistake
/// ("file:line: *KEYWORD field NAME (columns a-b) = value: what; fix").
Deck parse_deck(const std::string& path, const ParseOptions& options = {});

/// The keywords parse_deck understands (for messages and docs).
const std::vector<std::string>& supported_keywords();

/// Throws the InputError of field `i` of `layout` on the card at `ref` (read again from its
/// file: the mapping of a deck points at columns without keeping every card's text).
[[noreturn]] void fail_at(const Deck& deck, const CardRef& ref, std::string_view keyword,
                          Layout layout, std::size_t i, std::string_view what);

}  // namespace crashlink::deck
