#pragma once
// The keyword parser of parse_deck (deck.h): the block state and the card readers, shared by
// deck_parser.cpp (keywords, the mesh, parts, sections, materials, curves, sets, boxes, frames,
// contacts, walls) and condition_cards.cpp (constraints, initial velocities, hourglass and
// other controls, loads, prescribed motions, output). Internal to crashlink::deck.
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "solver/deck/card.h"
#include "solver/deck/deck.h"

namespace crashlink::deck::detail {

enum class Kw : std::uint8_t {
  Title,
  Node,
  ElementShell,
  ElementSolid,
  Part,
  SectionShell,
  SectionSolid,
  MatElastic,
  MatRigid,
  MatPlasticKinematic,
  MatPiecewiseLinear,
  DefineCurve,
  SetNodeList,
  SetNodeListGenerate,
  SetNodeGeneral,
  SetPartList,
  SetPartListGenerate,
  SetShellList,
  SetSegment,
  SpcNode,
  RigidConstraint,
  SpcSet,
  VelocityGeneration,
  VelocityNode,
  VelocityPlain,
  Termination,
  Timestep,
  DefineBox,
  CoordinateSystem,
  Contact,
  Hourglass,
  ControlHourglass,
  ControlBulk,
  LoadBody,
  RigidWall,
  Motion,
  LoadNode,
  ControlContact,
  ControlShell,
  Database,
  DatabaseAscii,
  D3plot,
  HistoryNode,
  Skip
};

/// The state of the keyword block being read.
/// *PART_INERTIA's card 3 (index 0), 4 (1) or 5 (2) into p (also a nodal body's _INERTIA).
void read_inertia_card(const Card& c, int index, PartCard& p);
/// *MAT_RIGID's card 2 (also a nodal body's _SPC card): CMO, CON1, CON2 as model::DofBits.
std::uint8_t read_rigid_dofs(const Card& c);

struct Block {
  Kw kw = Kw::Skip;
  std::string keyword;
  bool title = false, id = false;
  int card = 0;  ///< index of the next card within the current record
  std::string pending_title;
  std::int64_t pending_eid = 0, pending_pid = 0;  ///< two-card solids, welds
  CardRef pending_ref;                            ///< a generalized weld's card 1
  std::int32_t pending_line = 0;
  CardRef ref;             ///< the keyword's line
  std::size_t before = 0;  ///< records of its kind before the block (records_of)
};

class Parser {
 public:
  Parser(Deck& d, const ParseOptions& o) : d_(d), o_(o) {}

  void keyword(std::string_view k, const CardRef& ref);

  void card(const Card& c);

  void finish();

 private:
  const std::vector<std::string>& ignored();

  /// How many records of the kind `kw` makes the deck holds (SIZE_MAX: not counted).
  std::size_t records_of(Kw kw) const;

  void finish_block();

  /// The title card of a _TITLE keyword; true if `c` was it.
  bool title_card(const Card& c);
  int card_index() const { return b_.card - (b_.title ? 1 : 0); }

  void node(const Card& c);

  void shell(const Card& c);

  void solid(const Card& c);

  void part(const Card& c);

  /// *PART_INERTIA's cards 3 (XC YC ZC TM IRCS NODEID), 4 (the inertia tensor about the centre,
  /// global axes) and 5 (VTX VTY VTZ VRX VRY VRZ).
  void part_inertia(const Card& c);

  void section_shell(const Card& c);

  void section_solid(const Card& c);

  void read_elastic_constants(const Card& c, Layout l, MaterialCard& m);

  void material(const Card& c);

  /// Cowper-Symonds C and P (fields ic, ip of `l`): C >= 0 (0 or blank: no rate effect), P > 0
  /// with it.
  void read_rate(const Card& c, Layout l, std::size_t ic, std::size_t ip, const char* c_name,
                 const char* p_name, MaterialCard& m);

  void check_material_end();

  void curve(const Card& c);

  void set(const Card& c);

  /// *SET_SEGMENT: SID, then N1-N4 per card (A1-A4 without effect).
  void segment_set(const Card& c);

  void spc(const Card& c);

  /// *CONSTRAINED_NODAL_RIGID_BODY (PID CID NSID PNODE IPRT DRFLAG RRFLAG; _TITLE: its name),
  /// *CONSTRAINED_EXTRA_NODES_NODE/_SET (PID NID/NSID IFLAG), *CONSTRAINED_RIGID_BODIES (PIDL
  /// PIDC IFLAG): one record per card.
  /// In a *CONSTRAINED_GENERALIZED_WELD_SPOT or a nodal body's _INERTIA / _SPC record, after
  /// its first card (a blank card there is a card of defaults; the block must not end there).
  bool mid_record() const;
  void rigid_constraint(const Card& c);

  void velocity_generation(const Card& c);

  /// *INITIAL_VELOCITY: card 1 NSID (0: every node), NSIDEX, BOXID, IRIGID, ICID; card 2 VX VY
  /// VZ (and VXR-VZR, which must be 0).
  void velocity_plain(const Card& c);

  void velocity_node(const Card& c);

  void set_general(const Card& c);

  void box(const Card& c);

  void coordinate_system(const Card& c);

  /// *CONTACT_...: the ID card (with _ID or _TITLE), cards 1-3, optional cards A, B and later
  /// ones (which must keep their defaults).
  void contact(const Card& c);

  /// IHQ and QM of *HOURGLASS / *CONTROL_HOURGLASS: crashlink computes the Flanagan-Belytschko
  /// stiffness form (IHQ 4, 5; for shells the Belytschko-Tsay one); LS-DYNA's default viscous
  /// form (blank, 0 or 1) is read as it with a note; the other forms are refused.
  void hourglass_type(const Field& ihq_f, HourglassCard& h);

  /// QM / QH: blank or 0 reads as LS-DYNA's default 0.1; (0, 0.3] accepted.
  static double hourglass_coefficient(const Field& f);

  void hourglass(const Card& c);

  void control_hourglass(const Card& c);

  void control_bulk(const Card& c);

  void load_body(const Card& c);

  /// *RIGIDWALL_PLANAR(_ID): card 1 NSID ..., card 2 the tail and head points, FRIC, WVEL.
  void rigid_wall(const Card& c);

  /// *DATABASE_GLSTAT (and the other ASCII histories) and *DATABASE_BINARY_D3PLOT: DT, the
  /// interval of crashlink's history rows (the smallest DT of them: one interval for all) and of
  /// its field states.
  void output_interval(const Card& c);

  /// *DATABASE_HISTORY_NODE(_SET): eight NIDs (SIDs) per card; _ID: one NID and its heading.
  void history_node(const Card& c);

  /// *BOUNDARY_PRESCRIBED_MOTION_NODE/_SET (_ID: a heading card first): NID/NSID, DOF, VAD,
  /// LCID, SF, VID, DEATH, BIRTH; *LOAD_NODE_POINT/_SET: NID/NSID, DOF, LCID, SF, CID, M1-M3.
  void curve_dof(const Card& c);

  /// *CONTROL_CONTACT: SLSFAC (blank or 0: 0.1), the scale of every contact's penalty with its
  /// SFS; the other fields of card 1 and the later cards change nothing crashlink computes the
  /// same way, and are noted when given.
  void control_contact(const Card& c);

  /// *CONTROL_SHELL: THEORY (blank, 0 or 2: Belytschko-Tsay), ISTUPD (crashlink's shells always
  /// take their thickness from the thickness strain, LS-DYNA's ISTUPD 1; 0, the default, keeps
  /// it: noted); the rest noted when given.
  void control_shell(const Card& c);

  void termination(const Card& c);

  void timestep(const Card& c);

  Deck& d_;
  const ParseOptions& o_;
  std::vector<std::string> ignored_;
  Block b_;
  CardRef last_;
};

}  // namespace crashlink::deck::detail
