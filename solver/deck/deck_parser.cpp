// parse_deck: the stream of keywords and cards (card_reader.h) into Deck records. Every value a
// keyword gives is checked here, where its columns are known: an unsupported option of a
// supported keyword stops the reading at its field.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <fstream>

#include "solver/core/errors.h"
#include "solver/deck/card_reader.h"
#include "solver/deck/deck.h"
#include "solver/deck/field_checks.h"
#include "solver/deck/interaction_cards.h"
#include "solver/deck/keyword_layouts.h"

namespace crashlink::deck {

namespace {

namespace L = layout;

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
  SpcNode,
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

struct KeywordName {
  const char* name;
  Kw kw;
  bool title_ok;  ///< accepts the _TITLE suffix
  bool id_ok;     ///< accepts the _ID suffix
};

constexpr KeywordName kKeywords[] = {
    {"*TITLE", Kw::Title, false, false},
    {"*NODE", Kw::Node, false, false},
    {"*ELEMENT_SHELL", Kw::ElementShell, false, false},
    {"*ELEMENT_SHELL_THICKNESS", Kw::ElementShell, false, false},
    {"*ELEMENT_SOLID", Kw::ElementSolid, false, false},
    {"*PART", Kw::Part, false, false},
    {"*PART_INERTIA", Kw::Part, false, false},
    {"*SECTION_SHELL", Kw::SectionShell, true, false},
    {"*SECTION_SOLID", Kw::SectionSolid, true, false},
    {"*MAT_ELASTIC", Kw::MatElastic, true, false},
    {"*MAT_001", Kw::MatElastic, true, false},
    {"*MAT_RIGID", Kw::MatRigid, true, false},
    {"*MAT_020", Kw::MatRigid, true, false},
    {"*MAT_PLASTIC_KINEMATIC", Kw::MatPlasticKinematic, true, false},
    {"*MAT_003", Kw::MatPlasticKinematic, true, false},
    {"*MAT_PIECEWISE_LINEAR_PLASTICITY", Kw::MatPiecewiseLinear, true, false},
    {"*MAT_024", Kw::MatPiecewiseLinear, true, false},
    {"*DEFINE_CURVE", Kw::DefineCurve, true, false},
    {"*SET_NODE_LIST", Kw::SetNodeList, true, false},
    {"*SET_NODE_LIST_GENERATE", Kw::SetNodeListGenerate, true, false},
    {"*SET_NODE_GENERAL", Kw::SetNodeGeneral, true, false},
    {"*SET_PART_LIST", Kw::SetPartList, true, false},
    {"*SET_PART_LIST_GENERATE", Kw::SetPartListGenerate, true, false},
    {"*BOUNDARY_SPC_NODE", Kw::SpcNode, false, true},
    {"*BOUNDARY_SPC_SET", Kw::SpcSet, false, true},
    {"*INITIAL_VELOCITY_GENERATION", Kw::VelocityGeneration, false, false},
    {"*INITIAL_VELOCITY_NODE", Kw::VelocityNode, false, false},
    {"*INITIAL_VELOCITY", Kw::VelocityPlain, false, false},
    {"*CONTROL_TERMINATION", Kw::Termination, false, false},
    {"*CONTROL_TIMESTEP", Kw::Timestep, false, false},
    {"*DEFINE_BOX", Kw::DefineBox, true, false},
    {"*DEFINE_COORDINATE_SYSTEM", Kw::CoordinateSystem, true, false},
    {"*CONTACT_AUTOMATIC_SURFACE_TO_SURFACE", Kw::Contact, true, true},
    {"*CONTACT_SURFACE_TO_SURFACE", Kw::Contact, true, true},
    {"*CONTACT_AUTOMATIC_NODES_TO_SURFACE", Kw::Contact, true, true},
    {"*CONTACT_NODES_TO_SURFACE", Kw::Contact, true, true},
    {"*CONTACT_AUTOMATIC_SINGLE_SURFACE", Kw::Contact, true, true},
    {"*CONTACT_SINGLE_SURFACE", Kw::Contact, true, true},
    {"*HOURGLASS", Kw::Hourglass, true, false},
    {"*CONTROL_HOURGLASS", Kw::ControlHourglass, false, false},
    {"*CONTROL_BULK_VISCOSITY", Kw::ControlBulk, false, false},
    {"*CONTROL_CONTACT", Kw::ControlContact, false, false},
    {"*CONTROL_SHELL", Kw::ControlShell, false, false},
    {"*CONTROL_ENERGY", Kw::Database, false, false},
    {"*LOAD_BODY_X", Kw::LoadBody, false, false},
    {"*LOAD_BODY_Y", Kw::LoadBody, false, false},
    {"*LOAD_BODY_Z", Kw::LoadBody, false, false},
    {"*BOUNDARY_PRESCRIBED_MOTION_NODE", Kw::Motion, false, true},
    {"*BOUNDARY_PRESCRIBED_MOTION_SET", Kw::Motion, false, true},
    {"*LOAD_NODE_POINT", Kw::LoadNode, false, false},
    {"*LOAD_NODE_SET", Kw::LoadNode, false, false},
    {"*RIGIDWALL_PLANAR", Kw::RigidWall, false, true},
    {"*RIGIDWALL_PLANAR_MOVING", Kw::RigidWall, false, true},
};

constexpr const char* kReaderKeywords[] = {"*KEYWORD",
                                           "*END",
                                           "*INCLUDE",
                                           "*INCLUDE_PATH",
                                           "*INCLUDE_PATH_RELATIVE",
                                           "*PARAMETER",
                                           "*PARAMETER_EXPRESSION",
                                           "*COMMENT",
                                           "*DATABASE_*"};

bool ends_with(std::string_view s, std::string_view suffix) {
  return s.size() > suffix.size() && s.substr(s.size() - suffix.size()) == suffix;
}

/// The keyword's handler and its suffixes; false if not supported.
bool lookup(std::string_view k, Kw& kw, bool& title, bool& id) {
  title = id = false;
  if (k.rfind("*RIGIDWALL_PLANAR", 0) == 0) {
    // the options in any order: _ID, _MOVING (_ORTHO, _FINITE and _FORCES are not computed)
    std::string_view rest = k.substr(std::string_view("*RIGIDWALL_PLANAR").size());
    bool moving = false;
    while (!rest.empty()) {
      if (!id && rest.rfind("_ID", 0) == 0 && (rest.size() == 3 || rest[3] == '_')) {
        id = true;
        rest.remove_prefix(3);
      } else if (!moving && rest.rfind("_MOVING", 0) == 0) {
        moving = true;
        rest.remove_prefix(7);
      } else {
        id = false;
        return false;
      }
    }
    kw = Kw::RigidWall;
    return true;
  }
  if (k.rfind("*DATABASE_", 0) == 0) {
    // The outputs whose intervals crashlink takes, and the node histories (probes); the rest of
    // *DATABASE_* is accepted without effect.
    static constexpr std::pair<const char*, Kw> kRead[] = {
        {"*DATABASE_GLSTAT", Kw::DatabaseAscii},        {"*DATABASE_NODOUT", Kw::DatabaseAscii},
        {"*DATABASE_RCFORC", Kw::DatabaseAscii},        {"*DATABASE_RWFORC", Kw::DatabaseAscii},
        {"*DATABASE_MATSUM", Kw::DatabaseAscii},        {"*DATABASE_SLEOUT", Kw::DatabaseAscii},
        {"*DATABASE_BINARY_D3PLOT", Kw::D3plot},        {"*DATABASE_HISTORY_NODE", Kw::HistoryNode},
        {"*DATABASE_HISTORY_NODE_SET", Kw::HistoryNode}};
    kw = Kw::Database;
    for (const auto& [name, what] : kRead) {
      if (k == name) kw = what;
      if (k == "*DATABASE_HISTORY_NODE_ID" && what == Kw::HistoryNode) kw = what, id = true;
    }
    return true;
  }
  for (int pass = 0; pass < 3; ++pass) {
    std::string_view base = k;
    if (pass == 1) {
      if (!ends_with(k, "_TITLE")) continue;
      base.remove_suffix(6);
    }
    if (pass == 2) {
      if (!ends_with(k, "_ID")) continue;
      base.remove_suffix(3);
    }
    for (const auto& e : kKeywords)
      if (base == e.name) {
        if ((pass == 1 && !e.title_ok) || (pass == 2 && !e.id_ok)) return false;
        kw = e.kw;
        title = pass == 1;
        id = pass == 2;
        return true;
      }
  }
  return false;
}

std::string supported_list() {
  std::string s;
  for (const auto& k : supported_keywords()) s += (s.empty() ? "" : " ") + k;
  return s;
}

/// The state of the keyword block being read.
struct Block {
  Kw kw = Kw::Skip;
  std::string keyword;
  bool title = false, id = false;
  int card = 0;  ///< index of the next card within the current record
  std::string pending_title;
  std::int64_t pending_eid = 0, pending_pid = 0;  ///< two-card solids
  std::int32_t pending_line = 0;
  CardRef ref;             ///< the keyword's line
  std::size_t before = 0;  ///< records of its kind before the block (records_of)
};

class Parser {
 public:
  Parser(Deck& d, const ParseOptions& o) : d_(d), o_(o) {}

  void keyword(std::string_view k, const CardRef& ref) {
    finish_block();
    b_ = Block{};
    b_.keyword = std::string(k);
    b_.ref = ref;
    bool title = false, id = false;
    if (std::find(ignored().begin(), ignored().end(), std::string(k.substr(1))) !=
        ignored().end()) {
      b_.kw = Kw::Skip;
      d_.skipped_cards[b_.keyword] += 0;
      return;
    }
    if (!lookup(k, b_.kw, title, id))
      throw InputError(d_.files.name(ref.file), ref.line, std::string(k),
                       fmt::format("not supported; fix: remove it, or pass --ignore {} to skip it "
                                   "(what it does is then missing from the run). Supported: {}",
                                   k.substr(1), supported_list()));
    b_.title = title;
    b_.id = id;
    b_.before = records_of(b_.kw);
    if (b_.kw == Kw::Database) ++d_.without_effect[b_.keyword];
    if (b_.kw == Kw::RigidWall) {
      RigidWallCard w;
      w.keyword = b_.keyword;
      w.moving = b_.keyword.find("_MOVING") != std::string::npos;
      w.ref = ref;
      d_.rigid_walls.push_back(std::move(w));
    }
    if (b_.kw == Kw::Contact) {
      ContactCard c;
      c.keyword = b_.keyword;
      std::string_view base = k;
      if (title) base.remove_suffix(6);
      if (id) base.remove_suffix(3);
      c.automatic = base.find("_AUTOMATIC_") != std::string_view::npos;
      c.kind = ends_with(base, "SINGLE_SURFACE")     ? ContactCard::Kind::SingleSurface
               : ends_with(base, "NODES_TO_SURFACE") ? ContactCard::Kind::NodesToSurface
                                                     : ContactCard::Kind::SurfaceToSurface;
      c.ref = ref;
      d_.contacts.push_back(std::move(c));
    }
    if (b_.kw == Kw::SetNodeList || b_.kw == Kw::SetNodeListGenerate ||
        b_.kw == Kw::SetNodeGeneral || b_.kw == Kw::SetPartList ||
        b_.kw == Kw::SetPartListGenerate) {
      SetCard s;
      s.parts = b_.kw == Kw::SetPartList || b_.kw == Kw::SetPartListGenerate;
      s.keyword = b_.keyword;
      s.ref = ref;
      d_.sets.push_back(std::move(s));
    }
  }

  void card(const Card& c) {
    switch (b_.kw) {
      case Kw::Skip:
        if (b_.keyword.empty())
          throw InputError(c.file(), c.ref().line, "(data card)",
                           "no keyword before it; fix: start the file with *KEYWORD and put "
                           "every card under its keyword");
        ++d_.skipped_cards[b_.keyword];
        return;
      case Kw::Database:
        return;
      case Kw::DatabaseAscii:
      case Kw::D3plot:
        return output_interval(c);
      case Kw::HistoryNode:
        return history_node(c);
      case Kw::Title:
        if (b_.card++ == 0) d_.title = std::string(trim(c.whole()));
        return;
      case Kw::Node:
        return node(c);
      case Kw::ElementShell:
        return shell(c);
      case Kw::ElementSolid:
        return solid(c);
      case Kw::Part:
        return part(c);
      case Kw::SectionShell:
        return section_shell(c);
      case Kw::SectionSolid:
        return section_solid(c);
      case Kw::MatElastic:
      case Kw::MatRigid:
      case Kw::MatPlasticKinematic:
      case Kw::MatPiecewiseLinear:
        return material(c);
      case Kw::DefineCurve:
        return curve(c);
      case Kw::SetNodeList:
      case Kw::SetNodeListGenerate:
      case Kw::SetPartList:
      case Kw::SetPartListGenerate:
        return set(c);
      case Kw::SetNodeGeneral:
        return set_general(c);
      case Kw::SpcNode:
      case Kw::SpcSet:
        return spc(c);
      case Kw::VelocityGeneration:
        return velocity_generation(c);
      case Kw::VelocityNode:
        return velocity_node(c);
      case Kw::VelocityPlain:
        return velocity_plain(c);
      case Kw::Termination:
        return termination(c);
      case Kw::Timestep:
        return timestep(c);
      case Kw::DefineBox:
        return box(c);
      case Kw::CoordinateSystem:
        return coordinate_system(c);
      case Kw::Contact:
        return contact(c);
      case Kw::Hourglass:
        return hourglass(c);
      case Kw::ControlHourglass:
        return control_hourglass(c);
      case Kw::ControlBulk:
        return control_bulk(c);
      case Kw::LoadBody:
        return load_body(c);
      case Kw::RigidWall:
        return rigid_wall(c);
      case Kw::Motion:
      case Kw::LoadNode:
        return curve_dof(c);
      case Kw::ControlContact:
        return control_contact(c);
      case Kw::ControlShell:
        return control_shell(c);
    }
  }

  void finish() {
    finish_block();
    for (const auto& k : o_.ignore) {
      std::string key = upper(k);
      if (key.front() != '*') key.insert(key.begin(), '*');
      if (!d_.skipped_cards.count(key))
        throw InputError(fmt::format(
            "--ignore {}: the deck has no such keyword; fix: remove it from --ignore (keywords "
            "are written without '*', e.g. --ignore ELEMENT_BEAM)",
            k));
    }
  }

 private:
  const std::vector<std::string>& ignored() {
    if (ignored_.empty())
      for (const auto& k : o_.ignore) {
        if (k.empty() || k == "*")  // k.front() of an empty name would be undefined
          throw InputError(d_.files.name(0), 0, "--ignore",
                           "an empty keyword name; fix: list keywords without '*' and without "
                           "empty entries, e.g. --ignore ELEMENT_BEAM,DAMPING_GLOBAL");
        ignored_.push_back(upper(k.front() == '*' ? k.substr(1) : k));
      }
    return ignored_;
  }

  /// How many records of the kind `kw` makes the deck holds (SIZE_MAX: not counted).
  std::size_t records_of(Kw kw) const {
    switch (kw) {
      case Kw::Part:
        return d_.parts.size();
      case Kw::SectionShell:
      case Kw::SectionSolid:
        return d_.sections.size();
      case Kw::MatElastic:
      case Kw::MatRigid:
      case Kw::MatPlasticKinematic:
      case Kw::MatPiecewiseLinear:
        return d_.materials.size();
      case Kw::DefineCurve:
        return d_.curves.size();
      case Kw::SpcNode:
      case Kw::SpcSet:
        return d_.spcs.size();
      case Kw::VelocityGeneration:
      case Kw::VelocityNode:
      case Kw::VelocityPlain:
        return d_.velocities.size();
      case Kw::Motion:
      case Kw::LoadNode:
        return d_.curve_dofs.size();
      case Kw::DefineBox:
        return d_.boxes.size();
      case Kw::CoordinateSystem:
        return d_.coordinate_systems.size();
      case Kw::Hourglass:
        return d_.hourglass.size();
      case Kw::LoadBody:
        return d_.body_loads.size();
      default:
        return SIZE_MAX;
    }
  }

  void finish_block() {
    // A keyword whose cards are missing would define nothing without a word.
    const std::size_t before = b_.before;
    const bool empty =
        (before != SIZE_MAX && records_of(b_.kw) == before) ||
        ((b_.kw == Kw::Termination || b_.kw == Kw::ControlHourglass || b_.kw == Kw::ControlBulk) &&
         b_.card == 0) ||
        (b_.kw == Kw::Contact && d_.contacts.back().cards == 0) ||
        (b_.kw == Kw::VelocityPlain && b_.card == 1) ||
        (b_.kw == Kw::RigidWall &&
         d_.rigid_walls.back().cards < (d_.rigid_walls.back().moving ? 3 : 2)) ||
        (b_.kw == Kw::DefineCurve && !d_.curves.empty() && records_of(b_.kw) != before &&
         d_.curves.back().a.empty()) ||
        (d_.sets.size() > 0 && b_.kw >= Kw::SetNodeList && b_.kw <= Kw::SetPartListGenerate &&
         d_.sets.back().id == 0);
    if (empty && !b_.keyword.empty())
      throw InputError(d_.files.name(b_.ref.file), b_.ref.line, b_.keyword,
                       b_.kw == Kw::DefineCurve && records_of(b_.kw) != before
                           ? "the curve has no point; fix: add its points (A, O) after LCID"
                           : "its cards are missing (the next keyword or the end of the file "
                             "follows); fix: add them or remove the keyword");
    if (b_.kw == Kw::Part && b_.keyword == "*PART_INERTIA" && b_.card >= 2)
      throw InputError(d_.files.name(d_.parts.back().ref.file), d_.parts.back().ref.line,
                       b_.keyword,
                       fmt::format("card {} of the part's inertia is missing (3: XC YC ZC TM "
                                   "IRCS NODEID, 4: IXX IXY IXZ IYY IYZ IZZ, 5: VTX VTY VTZ VRX "
                                   "VRY VRZ); fix: add it",
                                   b_.card + 1));
    if (b_.kw == Kw::ElementShell && b_.card == 1)
      throw InputError(d_.files.name(last_.file), last_.line, b_.keyword,
                       "an element's thickness card (THIC1-THIC4) is missing after its node "
                       "card; fix: add it");
    if (b_.kw == Kw::ElementSolid && b_.card == 1) {
      // "EID PID" card without its node card: the deck ends inside an element.
      throw InputError(d_.files.name(last_.file), last_.line, b_.keyword,
                       "an element's node card is missing after its EID/PID card; fix: add it");
    }
    if ((b_.kw == Kw::MatPlasticKinematic || b_.kw == Kw::MatPiecewiseLinear) &&
        records_of(b_.kw) != before)
      check_material_end();
    if (b_.kw == Kw::CoordinateSystem && records_of(b_.kw) != before && card_index() == 1)
      throw InputError(d_.files.name(last_.file), last_.line, b_.keyword,
                       "card 2 (XP YP ZP, a point in the local x-y plane) is missing; fix: add "
                       "it");
    if (b_.kw == Kw::SectionShell && card_index() == 1)
      throw InputError(d_.files.name(d_.sections.back().ref.file), d_.sections.back().ref.line,
                       b_.keyword,
                       "card 2 (T1 T2 T3 T4 ...) is missing; fix: add it with the thickness T1");
    if (b_.kw == Kw::Part && b_.card == 1)
      throw InputError(d_.files.name(last_.file), last_.line, b_.keyword,
                       "the card PID SECID MID is missing after the title; fix: add it");
  }

  /// The title card of a _TITLE keyword; true if `c` was it.
  bool title_card(const Card& c) {
    if (b_.title && b_.card == 0) {
      b_.pending_title = std::string(trim(c.whole()));
      b_.card = 1;
      return true;
    }
    return false;
  }
  int card_index() const { return b_.card - (b_.title ? 1 : 0); }

  void node(const Card& c) {
    if (blank(c)) return;
    const auto nid = c.field(L::kNode, 0);
    d_.nodes.id.push_back(positive_id(nid));
    for (std::size_t k = 1; k <= 3; ++k) d_.nodes.x.push_back(c.field(L::kNode, k).real(0.0));
    for (std::size_t k = 4; k <= 5; ++k)
      must_be_default(c.field(L::kNode, k), 0.0,
                      "nodal constraints on *NODE (TC, RC) are not read; fix: leave them blank "
                      "and use *BOUNDARY_SPC_NODE");
    d_.nodes.ref.push_back(c.ref());
  }

  void shell(const Card& c) {
    if (blank(c)) return;
    auto& e = d_.shells;
    const bool with_thickness = b_.keyword == "*ELEMENT_SHELL_THICKNESS";
    if (with_thickness && b_.card == 1) {  // THIC1-THIC4 (0: the section's), BETA
      std::array<double, 4> t{};
      for (std::size_t k = 0; k < 4; ++k) {
        const auto f = c.field(L::kShellThickness, k);
        t[k] = f.real(0.0);
        if (t[k] < 0.0) f.fail("must be >= 0 (0: the section's thickness); fix: write it");
      }
      // BETA, the material angle: without effect on an isotropic material
      e.thickness.resize(e.count());
      e.thickness.back() = t;
      b_.card = 0;
      return;
    }
    e.id.push_back(positive_id(c.field(L::kElement, 0)));
    e.part.push_back(positive_id(c.field(L::kElement, 1)));
    for (std::size_t k = 2; k < 6; ++k) e.nodes.push_back(positive_id(c.field(L::kElement, k)));
    for (std::size_t k = 6; k < 10; ++k)
      must_be_default(c.field(L::kElement, k), 0.0,
                      "8-node shells are not computed; fix: use 4-node shells (N5-N8 blank)");
    e.ref.push_back(c.ref());
    e.id_line.push_back(c.ref().line);
    e.two_card.push_back(0);
    if (with_thickness) {
      b_.card = 1;
      last_ = c.ref();
    }
  }

  void solid(const Card& c) {
    if (blank(c)) return;
    auto& e = d_.solids;
    if (b_.card == 0) {
      const auto eid = c.field(L::kElement, 0);
      const auto pid = c.field(L::kElement, 1);
      bool nodes_here = false;
      for (std::size_t k = 2; k < 10; ++k)
        nodes_here = nodes_here || !c.field(L::kElement, k).blank();
      if (!nodes_here) {  // the two-card layout: "EID PID", then "N1 ... N10"
        b_.pending_eid = positive_id(eid);
        b_.pending_pid = positive_id(pid);
        b_.card = 1;
        last_ = c.ref();
        b_.pending_line = c.ref().line;
        return;
      }
      e.id.push_back(positive_id(eid));
      e.part.push_back(positive_id(pid));
      for (std::size_t k = 2; k < 10; ++k) e.nodes.push_back(positive_id(c.field(L::kElement, k)));
      e.ref.push_back(c.ref());
      e.id_line.push_back(c.ref().line);
      e.two_card.push_back(0);
      return;
    }
    e.id.push_back(b_.pending_eid);
    e.part.push_back(b_.pending_pid);
    for (std::size_t k = 0; k < 8; ++k) e.nodes.push_back(positive_id(c.field(L::kSolidNodes, k)));
    for (std::size_t k = 8; k < 10; ++k)
      must_be_default(c.field(L::kSolidNodes, k), 0.0,
                      "10-node tetrahedra are not computed; fix: use 8-node hexahedra "
                      "(N9, N10 blank or 0)");
    e.ref.push_back(c.ref());
    e.id_line.push_back(b_.pending_line);
    e.two_card.push_back(1);
    b_.card = 0;
  }

  void part(const Card& c) {
    if (b_.card == 0) {
      b_.pending_title = std::string(trim(c.whole()));
      b_.card = 1;
      last_ = c.ref();
      return;
    }
    if (b_.card >= 2) return part_inertia(c);
    PartCard p;
    p.keyword = b_.keyword;
    p.id = positive_id(c.field(L::kPart, 0));
    p.section = positive_id(c.field(L::kPart, 1));
    p.material = positive_id(c.field(L::kPart, 2));
    must_be_default(c.field(L::kPart, 3), 0.0,
                    "equations of state are not computed; fix: leave EOSID blank");
    p.hourglass = c.field(L::kPart, 4).integer(0);
    if (p.hourglass < 0)
      c.field(L::kPart, 4).fail("must be a *HOURGLASS id or blank; fix: write one");
    must_be_default(c.field(L::kPart, 7), 0.0,
                    "thermal materials are not computed; fix: leave TMID blank");
    p.title = std::move(b_.pending_title);
    p.ref = c.ref();
    p.inertia = b_.keyword == "*PART_INERTIA";
    d_.parts.push_back(std::move(p));
    b_.card = d_.parts.back().inertia ? 2 : 0;
  }

  /// *PART_INERTIA's cards 3 (XC YC ZC TM IRCS NODEID), 4 (the inertia tensor about the centre,
  /// global axes) and 5 (VTX VTY VTZ VRX VRY VRZ).
  void part_inertia(const Card& c) {
    PartCard& p = d_.parts.back();
    if (b_.card == 2) {
      for (std::size_t k = 0; k < 3; ++k) p.centre[k] = c.field(L::kPartInertia3, k).real(0.0);
      const auto tm = c.field(L::kPartInertia3, 3);
      p.mass = tm.real(0.0);
      if (!(p.mass > 0.0)) tm.fail("the part's mass must be > 0; fix: write it (deck mass unit)");
      must_be_default(c.field(L::kPartInertia3, 4), 0.0,
                      "an inertia tensor in the principal or a local system (IRCS 1) is not "
                      "read; fix: write IRCS 0 and the tensor in global axes");
      p.centre_node = c.field(L::kPartInertia3, 5).integer(0);
      if (p.centre_node < 0)
        c.field(L::kPartInertia3, 5).fail("must be a node id or 0; fix: write one");
      p.inertia_ref = c.ref();
    } else if (b_.card == 3) {
      for (std::size_t k = 0; k < 6; ++k) p.tensor[k] = c.field(L::kPartInertia4, k).real(0.0);
    } else {
      for (std::size_t k = 0; k < 3; ++k) {
        p.velocity[k] = c.field(L::kPartInertia5, k).real(0.0);
        p.angular_velocity[k] = c.field(L::kPartInertia5, 3 + k).real(0.0);
      }
      b_.card = 0;  // the next part's title
      return;
    }
    ++b_.card;
  }

  void section_shell(const Card& c) {
    if (title_card(c)) return;
    if (card_index() == 0) {
      SectionCard s;
      s.shell = true;
      s.keyword = b_.keyword;
      s.id = positive_id(c.field(L::kSectionShell1, 0));
      const auto elform = c.field(L::kSectionShell1, 1);
      if (elform.integer(2) != 2)
        elform.fail(
            "crashlink computes the Belytschko-Tsay shell (ELFORM 2) only; fix: write "
            "ELFORM 2 (or blank)");
      const auto shrf = c.field(L::kSectionShell1, 2);
      s.shrf_blank = shrf.blank();
      if (!shrf.blank() && std::abs(shrf.real(0.0) - 5.0 / 6.0) > 1e-3)
        shrf.fail(
            "crashlink's shells use Reissner's shear factor 5/6; fix: write SHRF 0.8333 "
            "(or leave it blank)");
      const auto nip = c.field(L::kSectionShell1, 3);
      s.nip = static_cast<int>(nip.integer(2));
      if (s.nip == 0) s.nip = 2;
      if (s.nip < 3 || s.nip > 9)
        nip.fail(fmt::format(
            "{} Gauss points through the thickness{}: crashlink integrates with 3 to 9; fix: "
            "write NIP 3 (elastic) or 5 (plasticity)",
            s.nip,
            nip.blank() || nip.integer(0) == 0 ? " (LS-DYNA's default for a blank NIP)" : ""));
      must_be_default(c.field(L::kSectionShell1, 4), 0.0, "PROPT is not read; fix: leave it blank");
      must_be_default(c.field(L::kSectionShell1, 6), 0.0,
                      "composite layers (ICOMP 1) are not computed; fix: write ICOMP 0");
      s.ref = c.ref();
      d_.sections.push_back(std::move(s));
      b_.card = b_.title ? 2 : 1;
      return;
    }
    SectionCard& s = d_.sections.back();
    const auto t1 = c.field(L::kSectionShell2, 0);
    s.thickness = positive(t1, "1.0 (mm) for a 1 mm sheet");
    for (std::size_t k = 1; k < 4; ++k) {
      const auto tk = c.field(L::kSectionShell2, k);
      if (!tk.blank() && tk.real(0.0) != 0.0 && tk.real(0.0) != s.thickness)
        tk.fail(
            fmt::format("crashlink's shells have one thickness per part; fix: write T2-T4 "
                        "equal to T1 = {} or blank",
                        s.thickness));
    }
    if (s.shrf_blank)
      d_.notes.push_back(
          fmt::format("{}:{}: {} {}: SHRF blank (LS-DYNA reads 1.0): crashlink's shells use 5/6",
                      d_.files.name(s.ref.file), s.ref.line, s.keyword, s.id));
    b_.card = 0;
  }

  void section_solid(const Card& c) {
    if (title_card(c)) return;
    SectionCard s;
    s.shell = false;
    s.keyword = b_.keyword;
    s.id = positive_id(c.field(L::kSectionSolid, 0));
    const auto elform = c.field(L::kSectionSolid, 1);
    if (elform.integer(1) != 1)
      elform.fail(
          "crashlink computes the one-point hexahedron (ELFORM 1) only; fix: write "
          "ELFORM 1 (or blank)");
    s.ref = c.ref();
    d_.sections.push_back(std::move(s));
    b_.card = 0;
  }

  void read_elastic_constants(const Card& c, Layout l, MaterialCard& m) {
    m.id = positive_id(c.field(l, 0));
    m.rho = positive(c.field(l, 1), "7.85e-9 (t/mm^3) for steel in mm-t-s");
    m.E = positive(c.field(l, 2), "2.1e5 (MPa) for steel in mm-t-s");
    const auto pr = c.field(l, 3);
    m.nu = pr.real(0.0);
    if (!(m.nu > -1.0 && m.nu < 0.5)) pr.fail("must lie in (-1, 0.5); fix: steel is 0.3");
  }

  void material(const Card& c) {
    if (title_card(c)) return;
    const int k = card_index();
    if (k == 0) {
      MaterialCard m;
      m.keyword = b_.keyword;
      m.title = std::move(b_.pending_title);
      m.ref = c.ref();
      switch (b_.kw) {
        case Kw::MatElastic: {
          m.type = MaterialType::Elastic;
          read_elastic_constants(c, L::kMatElastic, m);
          for (std::size_t i = 4; i < 6; ++i)
            must_be_default(c.field(L::kMatElastic, i), 0.0,
                            "beam damping (DA, DB) is not computed; fix: leave it blank");
          must_be_default(c.field(L::kMatElastic, 6), 0.0,
                          "the fluid option (K) is not computed; fix: leave K blank");
          break;
        }
        case Kw::MatRigid:
          m.type = MaterialType::Rigid;
          read_elastic_constants(c, L::kMatRigid1, m);
          break;
        case Kw::MatPlasticKinematic: {
          m.type = MaterialType::PlasticKinematic;
          read_elastic_constants(c, L::kMat003a, m);
          m.sigy = positive(c.field(L::kMat003a, 4), "250 (MPa) in mm-t-s");
          const auto etan = c.field(L::kMat003a, 5);
          m.etan = etan.real(0.0);
          if (m.etan < 0.0 || m.etan >= m.E)
            etan.fail(fmt::format("must lie in [0, E = {}); fix: write the tangent modulus", m.E));
          const auto beta = c.field(L::kMat003a, 6);
          if (beta.real(0.0) != 1.0)
            beta.fail(
                "crashlink computes isotropic hardening (BETA = 1) only, kinematic "
                "hardening (BETA < 1; blank is 0) is not computed; fix: write BETA 1.0");
          break;
        }
        case Kw::MatPiecewiseLinear: {
          m.type = MaterialType::PiecewiseLinear;
          read_elastic_constants(c, L::kMat024a, m);
          m.sigy = c.field(L::kMat024a, 4).real(0.0);
          const auto etan = c.field(L::kMat024a, 5);
          m.etan = etan.real(0.0);
          if (m.etan < 0.0 || m.etan >= m.E)
            etan.fail(fmt::format("must lie in [0, E = {}); fix: write the tangent modulus", m.E));
          const auto fail = c.field(L::kMat024a, 6);
          if (!fail.blank() && fail.real(0.0) != 0.0 && fail.real(0.0) < 1e20)
            fail.fail("element failure (erosion) is not computed; fix: leave FAIL blank");
          break;
        }
        default:
          break;
      }
      d_.materials.push_back(std::move(m));
      b_.card = (b_.title ? 1 : 0) + 1;
      return;
    }
    MaterialCard& m = d_.materials.back();
    ++b_.card;
    if (b_.kw == Kw::MatRigid) {
      if (k == 1) {
        const auto cmo = c.field(L::kMatRigid2, 0);
        if (cmo.real(0.0) != 0.0)
          cmo.fail(
              "rigid-body constraints (CMO, CON1, CON2) are not read yet; fix: write CMO 0 "
              "and fix the body's nodes with *BOUNDARY_SPC_*");
      }
      return;  // card 3 (LCO/alignment) has no effect without constraints
    }
    if (b_.kw == Kw::MatPlasticKinematic) {
      if (k == 1) {
        read_rate(c, L::kMat003b, 0, 1, "SRC", "SRP", m);
        must_be_default(c.field(L::kMat003b, 2), 0.0,
                        "element failure (FS) is not computed; fix: leave FS blank");
        if (m.rate_c > 0.0)
          must_be_default(c.field(L::kMat003b, 3), 0.0,
                          "the viscoplastic rate formulation (VP 1) is not computed; fix: write "
                          "VP 0 (the yield stress scaled by the Cowper-Symonds factor)");
      }
      return;
    }
    if (b_.kw == Kw::MatPiecewiseLinear) {
      if (k == 1) {
        read_rate(c, L::kMat024b, 0, 1, "C", "P", m);
        must_be_default(c.field(L::kMat024b, 3), 0.0,
                        "a table of yield-stress scale factors over strain rate (LCSR) is not "
                        "read; fix: write LCSR 0 and give C and P (Cowper-Symonds)");
        const auto vp = c.field(L::kMat024b, 4);
        const auto vpv = vp.real(0.0);
        if (m.rate_c > 0.0 && vpv != 0.0 && vpv != -1.0)
          vp.fail(
              "the viscoplastic rate formulation (VP 1) and the tables of VP 3 are not "
              "computed; fix: write VP 0 or -1 (the yield stress scaled by the "
              "Cowper-Symonds factor)");
        const auto lcss = c.field(L::kMat024b, 2);
        m.lcss = lcss.integer(0);
        if (m.lcss < 0) lcss.fail("must be a curve id > 0 or blank; fix: write the curve's LCID");
      } else if (k == 2 || k == 3) {
        auto& v = k == 2 ? m.eps : m.es;
        for (std::size_t i = 0; i < 8; ++i)
          v.push_back(c.field(k == 2 ? Layout(L::kMat024Eps) : Layout(L::kMat024Es), i).real(0.0));
      }
    }
  }

  /// Cowper-Symonds C and P (fields ic, ip of `l`): C >= 0 (0 or blank: no rate effect), P > 0
  /// with it.
  void read_rate(const Card& c, Layout l, std::size_t ic, std::size_t ip, const char* c_name,
                 const char* p_name, MaterialCard& m) {
    const auto cf = c.field(l, ic), pf = c.field(l, ip);
    m.rate_c = cf.real(0.0);
    m.rate_p = pf.real(0.0);
    if (m.rate_c < 0.0)
      cf.fail(
          fmt::format("must be >= 0 (0: no strain-rate effect); fix: write {} in 1/time of "
                      "the deck's units (mild steel: 40.4 1/s)",
                      c_name));
    if (m.rate_c > 0.0 && !(m.rate_p > 0.0))
      pf.fail(fmt::format("must be > 0 when {} is given; fix: write {} (mild steel: 5)", c_name,
                          p_name));
  }

  void check_material_end() {
    MaterialCard& m = d_.materials.back();
    if (m.type != MaterialType::PiecewiseLinear) return;
    // The 8-point table: the used pairs are those up to the last non-zero ES.
    std::size_t n = 0;
    for (std::size_t i = 0; i < m.es.size(); ++i)
      if (m.es[i] != 0.0) n = i + 1;
    m.es.resize(n);
    m.eps.resize(std::min(m.eps.size(), n));
    if (m.lcss == 0 && n == 0 && !(m.sigy > 0.0))
      throw InputError(d_.files.name(m.ref.file), m.ref.line, m.keyword,
                       fmt::format("MID {}: no yield stress: SIGY is blank, no LCSS curve and no "
                                   "EPS/ES table; fix: give SIGY (and ETAN) or LCSS",
                                   m.id));
  }

  void curve(const Card& c) {
    if (title_card(c)) return;
    if (card_index() == 0) {
      CurveCard cv;
      cv.keyword = b_.keyword;
      cv.id = positive_id(c.field(L::kCurve, 0));
      must_be_default(c.field(L::kCurve, 1), 0.0,
                      "dynamic relaxation curves (SIDR 1, 2) are not computed; fix: write SIDR 0");
      const auto sfa = c.field(L::kCurve, 2);
      const auto sfo = c.field(L::kCurve, 3);
      cv.sfa = sfa.real(1.0);
      cv.sfo = sfo.real(1.0);
      if (cv.sfa == 0.0) cv.sfa = 1.0;  // LS-DYNA: 0 reads as the default 1
      if (cv.sfo == 0.0) cv.sfo = 1.0;
      cv.offa = c.field(L::kCurve, 4).real(0.0);
      cv.offo = c.field(L::kCurve, 5).real(0.0);
      cv.ref = c.ref();
      d_.curves.push_back(std::move(cv));
      b_.card = b_.title ? 2 : 1;
      return;
    }
    if (blank(c)) return;
    CurveCard& cv = d_.curves.back();
    const auto a = c.field(L::kCurvePoint, 0);
    const double x = a.real(0.0);
    if (!cv.a.empty() && !(x > cv.a.back()))
      a.fail(fmt::format("abscissae must increase: {} follows {}; fix: order the points", x,
                         cv.a.back()));
    cv.a.push_back(x);
    cv.o.push_back(c.field(L::kCurvePoint, 1).real(0.0));
  }

  void set(const Card& c) {
    if (title_card(c)) return;
    SetCard& s = d_.sets.back();
    if (card_index() == 0) {
      s.id = positive_id(c.field(L::kSetHeader, 0));
      s.ref = c.ref();
      b_.card = b_.title ? 2 : 1;
      return;
    }
    if (blank(c)) return;
    const bool generate = b_.kw == Kw::SetNodeListGenerate || b_.kw == Kw::SetPartListGenerate;
    if (generate) {
      for (std::size_t k = 0; k + 1 < 8; k += 2) {
        const auto b = c.field(L::kSetGenerate, k);
        const auto e = c.field(L::kSetGenerate, k + 1);
        if (b.blank() && e.blank()) continue;
        const std::int64_t lo = positive_id(b), hi = positive_id(e);
        if (hi < lo)
          e.fail(fmt::format("the range ends before it begins ({}); fix: swap them", lo));
        s.ranges.push_back({lo, hi});
        s.range_ref.push_back(c.ref());
      }
      return;
    }
    for (std::size_t k = 0; k < 8; ++k) {
      const auto f = c.field(L::kSetList, k);
      if (f.blank() || f.integer(0) == 0) continue;
      s.members.push_back(positive_id(f));
      s.member_ref.push_back(c.ref());
    }
  }

  void spc(const Card& c) {
    if (b_.id && b_.card == 0) {  // the ID/HEADING card
      b_.card = 1;
      return;
    }
    if (blank(c)) return;
    const Layout l = b_.kw == Kw::SpcNode ? Layout(L::kSpcNode) : Layout(L::kSpcSet);
    SpcCard s;
    s.keyword = b_.keyword;
    s.set = b_.kw == Kw::SpcSet;
    s.target = positive_id(c.field(l, 0));
    must_be_default(c.field(l, 1), 0.0,
                    "constraints in a local coordinate system are not computed; fix: write CID "
                    "0 (global axes)");
    for (std::size_t k = 2; k < 8; ++k) {
      const auto f = c.field(l, k);
      const auto v = f.integer(0);
      if (v != 0 && v != 1) f.fail("must be 0 (free) or 1 (fixed); fix: write 0 or 1");
      if (v == 1) s.mask = static_cast<std::uint8_t>(s.mask | (1u << (k - 2)));
    }
    s.ref = c.ref();
    d_.spcs.push_back(std::move(s));
  }

  void velocity_generation(const Card& c) {
    if (b_.card == 0) {
      VelocityCard v;
      v.keyword = b_.keyword;
      v.target = positive_id(c.field(L::kVelocityGeneration1, 0));
      const auto styp = c.field(L::kVelocityGeneration1, 1);
      v.styp = static_cast<int>(styp.integer(0));
      if (v.styp < 1 || v.styp > 3)
        styp.fail("must be 1 (part set), 2 (part) or 3 (node set); fix: write one of them");
      must_be_default(c.field(L::kVelocityGeneration1, 2), 0.0,
                      "rotational initial velocity (OMEGA) is not read yet; fix: write OMEGA 0 "
                      "(translation only)");
      for (std::size_t k = 0; k < 3; ++k)
        v.v[k] = c.field(L::kVelocityGeneration1, 3 + k).real(0.0);
      must_be_default(c.field(L::kVelocityGeneration1, 6), 0.0,
                      "IVATN 1 is not computed; fix: write IVATN 0");
      v.icid = c.field(L::kVelocityGeneration1, 7).integer(0);
      if (v.icid < 0)
        c.field(L::kVelocityGeneration1, 7)
            .fail("must be a *DEFINE_COORDINATE_SYSTEM id or 0 (global axes); fix: write one");
      v.ref = c.ref();
      d_.velocities.push_back(std::move(v));
      b_.card = 1;
      return;
    }
    // card 2: the rotation's centre and axis, without effect at OMEGA = 0; IRIGID
    const auto irigid = c.field(L::kVelocityGeneration2, 7);
    d_.velocities.back().irigid = static_cast<int>(irigid.integer(0));
    if (d_.velocities.back().irigid < 0 || d_.velocities.back().irigid > 1)
      irigid.fail(
          "must be 0 (keep a *PART_INERTIA body's velocity) or 1 (override it); fix: "
          "write one");
    b_.card = 0;
  }

  /// *INITIAL_VELOCITY: card 1 NSID (0: every node), NSIDEX, BOXID, IRIGID, ICID; card 2 VX VY
  /// VZ (and VXR-VZR, which must be 0).
  void velocity_plain(const Card& c) {
    if (b_.card == 0) {
      if (blank(c)) return;  // a blank line between records (write NSID 0 for every node)
      VelocityCard v;
      v.keyword = b_.keyword;
      v.styp = 4;
      v.target = c.field(L::kInitialVelocity1, 0).integer(0);
      if (v.target < 0)
        c.field(L::kInitialVelocity1, 0).fail("must be a node set id or 0 (every node); fix");
      must_be_default(c.field(L::kInitialVelocity1, 1), 0.0,
                      "exempted nodes (NSIDEX) are not computed; fix: write 0 and leave them "
                      "out of NSID");
      must_be_default(c.field(L::kInitialVelocity1, 2), 0.0,
                      "a box (BOXID) is not computed here; fix: write 0 and give the nodes in "
                      "NSID (e.g. *SET_NODE_GENERAL BOX)");
      must_be_default(c.field(L::kInitialVelocity1, 3), 0.0,
                      "IRIGID is not computed; fix: write 0 and give a rigid part's velocity with "
                      "*INITIAL_VELOCITY_GENERATION on the part");
      v.icid = c.field(L::kInitialVelocity1, 4).integer(0);
      if (v.icid < 0)
        c.field(L::kInitialVelocity1, 4)
            .fail("must be a *DEFINE_COORDINATE_SYSTEM id or 0 (global axes); fix: write one");
      v.ref = c.ref();
      d_.velocities.push_back(std::move(v));
      b_.card = 1;
      return;
    }
    VelocityCard& v = d_.velocities.back();
    for (std::size_t k = 0; k < 3; ++k) v.v[k] = c.field(L::kInitialVelocity2, k).real(0.0);
    for (std::size_t k = 3; k < 6; ++k)
      must_be_default(c.field(L::kInitialVelocity2, k), 0.0,
                      "angular velocities (VXR, VYR, VZR) are not read; fix: leave them blank");
    b_.card = 0;
  }

  void velocity_node(const Card& c) {
    if (blank(c)) return;
    VelocityCard v;
    v.keyword = b_.keyword;
    v.target = positive_id(c.field(L::kVelocityNode, 0));
    for (std::size_t k = 0; k < 3; ++k) v.v[k] = c.field(L::kVelocityNode, 1 + k).real(0.0);
    for (std::size_t k = 4; k < 7; ++k)
      must_be_default(c.field(L::kVelocityNode, k), 0.0,
                      "nodal angular velocities are not read yet; fix: leave VXR, VYR, VZR blank");
    v.icid = c.field(L::kVelocityNode, 7).integer(0);
    if (v.icid < 0)
      c.field(L::kVelocityNode, 7)
          .fail("must be a *DEFINE_COORDINATE_SYSTEM id or 0 (global axes); fix: write one");
    v.ref = c.ref();
    d_.velocities.push_back(std::move(v));
  }

  void set_general(const Card& c) {
    if (title_card(c)) return;
    SetCard& s = d_.sets.back();
    if (card_index() == 0) {
      s.id = positive_id(c.field(L::kSetHeader, 0));
      s.ref = c.ref();
      b_.card = b_.title ? 2 : 1;
      return;
    }
    if (blank(c)) return;
    GeneralEntry g;
    const auto opt = c.field(L::kSetGeneral, 0);
    const std::string o = upper(opt.text());
    if (o == "ALL")
      g.option = GeneralEntry::Option::All;
    else if (o == "NODE")
      g.option = GeneralEntry::Option::Node;
    else if (o == "PART")
      g.option = GeneralEntry::Option::Part;
    else if (o == "BOX")
      g.option = GeneralEntry::Option::Box;
    else
      opt.fail(
          "crashlink reads the options ALL, NODE (node ids), PART (part ids) and BOX (box ids) "
          "of *SET_NODE_GENERAL; fix: write one of them, or list the nodes under "
          "*SET_NODE_LIST");
    for (std::size_t k = 1; k < 8; ++k) {
      const auto f = c.field(L::kSetGeneral, k);
      if (f.blank() || f.integer(0) == 0) continue;
      if (g.option == GeneralEntry::Option::All)
        f.fail("the option ALL takes no id; fix: leave E1-E7 blank");
      g.ids.push_back(positive_id(f));
      g.field.push_back(static_cast<std::uint8_t>(k));
    }
    if (g.option != GeneralEntry::Option::All && g.ids.empty())
      c.field(L::kSetGeneral, 1)
          .fail(fmt::format("the option {} lists no id; fix: write at least one in E1", o));
    g.ref = c.ref();
    s.general.push_back(std::move(g));
  }

  void box(const Card& c) {
    if (title_card(c)) return;
    BoxCard bx;
    bx.keyword = b_.keyword;
    bx.id = positive_id(c.field(L::kBox, 0));
    for (std::size_t k = 0; k < 3; ++k) {
      bx.lo[k] = c.field(L::kBox, 1 + 2 * k).real(0.0);
      const auto hi = c.field(L::kBox, 2 + 2 * k);
      bx.hi[k] = hi.real(0.0);
      if (bx.hi[k] < bx.lo[k])
        hi.fail(fmt::format("the box ends before it begins ({}); fix: swap the bounds", bx.lo[k]));
    }
    bx.ref = c.ref();
    d_.boxes.push_back(std::move(bx));
    b_.card = 0;
  }

  void coordinate_system(const Card& c) {
    if (title_card(c)) return;
    if (card_index() == 0) {
      CoordinateSystemCard cs;
      cs.keyword = b_.keyword;
      cs.id = positive_id(c.field(L::kCoordinateSystem1, 0));
      for (std::size_t k = 0; k < 3; ++k) {
        cs.o[k] = c.field(L::kCoordinateSystem1, 1 + k).real(0.0);
        cs.l[k] = c.field(L::kCoordinateSystem1, 4 + k).real(0.0);
      }
      must_be_default(c.field(L::kCoordinateSystem1, 7), 0.0,
                      "a system defined in another local system (CIDL) is not read; fix: give "
                      "O, L and P in global coordinates and CIDL 0");
      cs.ref = c.ref();
      d_.coordinate_systems.push_back(std::move(cs));
      b_.card = b_.title ? 2 : 1;
      last_ = c.ref();
      return;
    }
    CoordinateSystemCard& cs = d_.coordinate_systems.back();
    for (std::size_t k = 0; k < 3; ++k) cs.p[k] = c.field(L::kCoordinateSystem2, k).real(0.0);
    b_.card = 0;
  }

  /// *CONTACT_...: the ID card (with _ID or _TITLE), cards 1-3, optional cards A, B and later
  /// ones (which must keep their defaults).
  void contact(const Card& c) {
    ContactCard& k = d_.contacts.back();
    if ((b_.id || b_.title) && b_.card == 0) {
      k.heading = std::string(trim(c.field(L::kIdHeading, 1).raw()));
      k.cid = c.field(L::kIdHeading, 0).integer(0);
      b_.card = 1;
      return;
    }
    read_contact_card(c, k.cards++, k, d_.notes);
  }

  /// IHQ and QM of *HOURGLASS / *CONTROL_HOURGLASS: crashlink computes the Flanagan-Belytschko
  /// stiffness form (IHQ 4, 5; for shells the Belytschko-Tsay one); LS-DYNA's default viscous
  /// form (blank, 0 or 1) is read as it with a note; the other forms are refused.
  void hourglass_type(const Field& ihq_f, HourglassCard& h) {
    h.ihq = static_cast<int>(ihq_f.integer(0));
    if (h.ihq == 0 || h.ihq == 1) {
      d_.notes.push_back(fmt::format(
          "{}:{}: {} IHQ {}: LS-DYNA's viscous hourglass control; crashlink computes the "
          "stiffness form (IHQ 4) with the coefficient QM",
          d_.files.name(h.ref.file), h.ref.line, h.keyword,
          ihq_f.blank() ? std::string("blank") : std::to_string(h.ihq)));
      return;
    }
    if (h.ihq != 4 && h.ihq != 5)
      ihq_f.fail(
          "crashlink computes the stiffness hourglass control (IHQ 4 and 5: Flanagan-Belytschko "
          "for hexahedra, Belytschko-Tsay for shells); the viscous forms 2 and 3 and the "
          "assumed-strain ones (6 and up) are not computed; fix: write IHQ 4");
  }

  /// QM / QH: blank or 0 reads as LS-DYNA's default 0.1; (0, 0.3] accepted.
  static double hourglass_coefficient(const Field& f) {
    double q = f.real(0.1);
    if (q == 0.0) q = 0.1;
    if (!(q > 0.0 && q <= 0.3))
      f.fail("must lie in (0, 0.3]; fix: write 0.05-0.1 (stiffness form)");
    return q;
  }

  void hourglass(const Card& c) {
    if (title_card(c)) return;
    HourglassCard h;
    h.keyword = b_.keyword;
    h.ref = c.ref();
    h.id = positive_id(c.field(L::kHourglass, 0));
    hourglass_type(c.field(L::kHourglass, 1), h);
    h.qm = hourglass_coefficient(c.field(L::kHourglass, 2));
    must_be_default(c.field(L::kHourglass, 3), 0.0, "IBQ is not read; fix: leave it blank");
    for (std::size_t k : {std::size_t{4}, std::size_t{5}})
      must_be_default(c.field(L::kHourglass, k), 0.0,
                      "a bulk viscosity per part (Q1, Q2) is not computed; fix: leave them blank "
                      "and set the model's in *CONTROL_BULK_VISCOSITY");
    d_.hourglass.push_back(std::move(h));
    b_.card = 0;
  }

  void control_hourglass(const Card& c) {
    if (b_.card++ != 0) return;
    HourglassCard& h = d_.control_hourglass;
    h.keyword = b_.keyword;
    h.ref = c.ref();
    hourglass_type(c.field(L::kControlHourglass, 0), h);
    h.qm = hourglass_coefficient(c.field(L::kControlHourglass, 1));
    d_.has_control_hourglass = true;
  }

  void control_bulk(const Card& c) {
    if (b_.card++ != 0) return;
    const auto q1 = c.field(L::kControlBulk, 0), q2 = c.field(L::kControlBulk, 1);
    d_.bulk_q1 = q1.real(1.5);
    d_.bulk_q2 = q2.real(0.06);
    if (d_.bulk_q1 == 0.0 && q1.blank()) d_.bulk_q1 = 1.5;
    if (d_.bulk_q2 == 0.0 && q2.blank()) d_.bulk_q2 = 0.06;
    if (d_.bulk_q1 < 0.0) q1.fail("must be >= 0; fix: write 1.5 (the default)");
    if (d_.bulk_q2 < 0.0) q2.fail("must be >= 0; fix: write 0.06 (the default)");
    const auto type = c.field(L::kControlBulk, 2);
    const auto t = type.integer(1);
    if (t != 1 && t != -2 && t != 0)
      type.fail(
          "crashlink computes the standard bulk viscosity of solids (TYPE 1) and, with TYPE -2, "
          "of shells too; fix: write 1 or -2");
    d_.bulk_shells = t == -2;
    d_.has_bulk = true;
  }

  void load_body(const Card& c) {
    if (blank(c)) return;
    BodyLoadCard l;
    l.keyword = b_.keyword;
    l.axis = b_.keyword.back() - 'X';
    l.ref = c.ref();
    l.curve = positive_id(c.field(L::kLoadBody, 0));
    l.sf = c.field(L::kLoadBody, 1).real(1.0);
    must_be_default(c.field(L::kLoadBody, 2), 0.0,
                    "dynamic relaxation (LCIDDR) is not computed; fix: write 0");
    must_be_default(c.field(L::kLoadBody, 6), 0.0,
                    "a body load in a local system (CID) is not computed; fix: write 0 (global "
                    "axes)");
    d_.body_loads.push_back(std::move(l));
  }

  /// *RIGIDWALL_PLANAR(_ID): card 1 NSID ..., card 2 the tail and head points, FRIC, WVEL.
  void rigid_wall(const Card& c) {
    RigidWallCard& w = d_.rigid_walls.back();
    if (b_.id && b_.card == 0) {
      w.heading = std::string(trim(c.field(L::kIdHeading, 1).raw()));
      b_.card = 1;
      return;
    }
    read_rigid_wall_card(c, w.cards++, w);
  }

  /// *DATABASE_GLSTAT (and the other ASCII histories) and *DATABASE_BINARY_D3PLOT: DT, the
  /// interval of crashlink's history rows (the smallest DT of them: one interval for all) and of
  /// its field states.
  void output_interval(const Card& c) {
    if (b_.card++ != 0) return;
    const bool d3plot = b_.kw == Kw::D3plot;
    const Layout l = d3plot ? Layout(L::kD3plot) : Layout(L::kDatabaseAscii);
    const auto dt_field = c.field(l, 0);
    const double dt = dt_field.real(0.0);
    if (dt < 0.0)
      dt_field.fail("an output interval must be >= 0; fix: write the interval (0: no output)");
    must_be_default(c.field(l, d3plot ? 1 : 2), 0.0,
                    "an output interval from a curve is not read; fix: leave it blank and give "
                    "DT");
    if (d3plot) {
      // NPLTC > 0: ENDTIM / NPLTC, in place of DT (LS-DYNA), set once the end time is known
      const auto npltc = c.field(l, 3);
      d_.field_count = npltc.integer(0);
      if (d_.field_count < 0)
        npltc.fail("must be >= 0 (the number of states over the run); fix: write it or DT");
      d_.field_dt = dt;
      return;
    }
    if (dt == 0.0) return;
    d_.history_dt = d_.history_dt > 0.0 ? std::min(d_.history_dt, dt) : dt;
    d_.history_dt_max = std::max(d_.history_dt_max, dt);
    d_.history_dt_keywords.push_back(b_.keyword);
  }

  /// *DATABASE_HISTORY_NODE(_SET): eight NIDs (SIDs) per card; _ID: one NID and its heading.
  void history_node(const Card& c) {
    const bool set = b_.keyword.find("_SET") != std::string::npos;
    if (b_.id) {
      if (blank(c)) return;
      HistoryNodeCard h{b_.keyword,
                        std::string(trim(c.field(L::kIdHeading, 1).raw())),
                        positive_id(c.field(L::kIdHeading, 0)),
                        false,
                        0,
                        c.ref()};
      d_.history_nodes.push_back(std::move(h));
      return;
    }
    for (std::size_t k = 0; k < 8; ++k) {
      const auto f = c.field(L::kHistoryIds, k);
      if (f.blank() || f.integer(0) == 0) continue;
      d_.history_nodes.push_back({b_.keyword, {}, positive_id(f), set, k, c.ref()});
    }
  }

  /// *BOUNDARY_PRESCRIBED_MOTION_NODE/_SET (_ID: a heading card first): NID/NSID, DOF, VAD,
  /// LCID, SF, VID, DEATH, BIRTH; *LOAD_NODE_POINT/_SET: NID/NSID, DOF, LCID, SF, CID, M1-M3.
  void curve_dof(const Card& c) {
    if (b_.id && b_.card == 0) {
      b_.card = 1;
      return;
    }
    if (blank(c)) return;
    const bool load = b_.kw == Kw::LoadNode;
    const bool set = b_.keyword.find("_SET") != std::string::npos;
    const Layout l = load ? (set ? Layout(L::kLoadSet) : Layout(L::kLoadNode))
                          : (set ? Layout(L::kMotionSet) : Layout(L::kMotionNode));
    CurveDofCard k;
    k.keyword = b_.keyword;
    k.set = set;
    k.load = load;
    k.target = positive_id(c.field(l, 0));
    const auto dof = c.field(l, 1);
    k.dof = static_cast<int>(dof.integer(0));
    const bool rotation = k.dof >= 5 && k.dof <= 7;
    if (!(k.dof >= 1 && k.dof <= 3) && !(rotation && !load))
      dof.fail(load ? "crashlink loads a node along x, y or z (DOF 1, 2, 3); moments, follower "
                      "forces and loads along a vector are not computed; fix: write 1, 2 or 3"
                    : "crashlink prescribes x, y, z (DOF 1, 2, 3) or rotations about them (5, 6, "
                      "7); motion along a vector (4, 8), in a local system (negative) or of all "
                      "translations (9-12) is not computed; fix: one card per global dof");
    if (load) {
      k.lcid = positive_id(c.field(l, 2));
      k.sf = c.field(l, 3).real(1.0);
      if (k.sf == 0.0 && c.field(l, 3).blank()) k.sf = 1.0;
      must_be_default(c.field(l, 4), 0.0,
                      "a load in a local system (CID) is not computed; fix: write 0 (global axes)");
      for (std::size_t f = 5; f < 8; ++f)
        must_be_default(c.field(l, f), 0.0,
                        "a follower force (M1-M3) is not computed; fix: leave M1-M3 blank");
    } else {
      const auto vad = c.field(l, 2);
      if (vad.integer(0) != 0)
        vad.fail(
            "crashlink prescribes a velocity (VAD 0); an acceleration (1) or displacement "
            "(2) curve is not converted; fix: give the velocity curve (VAD 0), the "
            "displacement's slope on each segment");
      k.lcid = positive_id(c.field(l, 3));
      k.sf = c.field(l, 4).real(1.0);
      if (k.sf == 0.0 && c.field(l, 4).blank()) k.sf = 1.0;
      must_be_default(c.field(l, 5), 0.0,
                      "a motion along a vector (VID) is not computed; fix: write 0 and a global "
                      "DOF");
      const auto death = c.field(l, 6);
      if (!death.blank() && death.real(0.0) != 0.0 && death.real(0.0) < 1e20)
        death.fail(
            "a death time (DEATH) is not computed: the motion holds to the end; fix: "
            "write 0, or end the curve's velocity yourself");
      must_be_default(c.field(l, 7), 0.0,
                      "a birth time (BIRTH) is not computed; fix: write 0 and start the curve "
                      "at 0");
    }
    k.ref = c.ref();
    d_.curve_dofs.push_back(std::move(k));
  }

  /// *CONTROL_CONTACT: SLSFAC (blank or 0: 0.1), the scale of every contact's penalty with its
  /// SFS; the other fields of card 1 and the later cards change nothing crashlink computes the
  /// same way, and are noted when given.
  void control_contact(const Card& c) {
    if (b_.card++ != 0) {
      if (!blank(c))
        d_.notes.push_back(fmt::format("{}:{}: *CONTROL_CONTACT card {} not read", c.file(),
                                       c.ref().line, b_.card));
      return;
    }
    const auto f = c.field(L::kControlContact, 0);
    d_.slsfac = f.real(0.1);
    if (d_.slsfac == 0.0) d_.slsfac = 0.1;
    if (!(d_.slsfac > 0.0)) f.fail("must be > 0; fix: write 0.1 (the default)");
    for (std::size_t k = 1; k < 8; ++k)
      if (!c.field(L::kControlContact, k).blank() &&
          c.field(L::kControlContact, k).real(0.0) != 0.0)
        d_.notes.push_back(fmt::format("{}:{}: *CONTROL_CONTACT {} not read", c.file(),
                                       c.ref().line, L::kControlContact[k].name));
  }

  /// *CONTROL_SHELL: THEORY (blank, 0 or 2: Belytschko-Tsay), ISTUPD (crashlink's shells always
  /// take their thickness from the thickness strain, LS-DYNA's ISTUPD 1; 0, the default, keeps
  /// it: noted); the rest noted when given.
  void control_shell(const Card& c) {
    if (b_.card++ != 0) {
      if (!blank(c))
        d_.notes.push_back(
            fmt::format("{}:{}: *CONTROL_SHELL card {} not read", c.file(), c.ref().line, b_.card));
      return;
    }
    d_.has_control_shell = true;
    const auto theory = c.field(L::kControlShell, 4);
    const auto th = theory.integer(0);
    if (th != 0 && th != 2)
      theory.fail("crashlink computes the Belytschko-Tsay shell (THEORY 2) only; fix: write 2");
    const auto istupd = c.field(L::kControlShell, 3);
    d_.istupd = static_cast<int>(istupd.integer(0));
    if (d_.istupd < 0 || d_.istupd > 4)
      istupd.fail(
          "must be 0 to 4; fix: write 1 (the thickness follows the membrane strain, as "
          "crashlink computes it)");
    for (std::size_t k : {0u, 1u, 2u, 5u, 6u, 7u})
      if (!c.field(L::kControlShell, k).blank() && c.field(L::kControlShell, k).real(0.0) != 0.0)
        d_.notes.push_back(fmt::format("{}:{}: *CONTROL_SHELL {} not read", c.file(), c.ref().line,
                                       L::kControlShell[k].name));
  }

  void termination(const Card& c) {
    if (b_.card++ != 0) return;
    const auto endtim = c.field(L::kTermination, 0);
    d_.end_time = positive(endtim, "0.01 (s) or 10 (ms)");
    d_.has_end_time = true;
    must_be_default(c.field(L::kTermination, 1), 0.0,
                    "ending on a cycle count is not computed; fix: leave ENDCYC blank");
    for (std::size_t k = 3; k < 5; ++k)
      must_be_default(c.field(L::kTermination, k), 0.0,
                      "ending on energy or mass change is not computed; fix: leave ENDENG and "
                      "ENDMAS blank");
    if (!c.field(L::kTermination, 2).blank())
      d_.notes.push_back(
          fmt::format("{}:{}: *CONTROL_TERMINATION DTMIN not read (crashlink's "
                      "guard stops a collapsing step)",
                      c.file(), c.ref().line));
  }

  void timestep(const Card& c) {
    if (b_.card++ != 0) return;
    const auto tssfac = c.field(L::kTimestep, 1);
    d_.tssfac = tssfac.real(0.9);
    if (d_.tssfac == 0.0) d_.tssfac = 0.9;  // LS-DYNA: 0 reads as the default
    if (!(d_.tssfac > 0.0 && d_.tssfac <= 1.0))
      tssfac.fail("must lie in (0, 1]; fix: write 0.9 (the default)");
    must_be_default(c.field(L::kTimestep, 4), 0.0,
                    "mass scaling (DT2MS) is not computed yet; fix: leave DT2MS blank");
    must_be_default(c.field(L::kTimestep, 5), 0.0,
                    "a step limit curve (LCTM) is not computed; fix: leave LCTM blank");
  }

  Deck& d_;
  const ParseOptions& o_;
  std::vector<std::string> ignored_;
  Block b_;
  CardRef last_;
};

}  // namespace

const std::vector<std::string>& supported_keywords() {
  static const std::vector<std::string> all = [] {
    std::vector<std::string> v;
    for (const auto& k : kKeywords) {
      std::string n = k.name;
      if (k.title_ok) n += "(_TITLE)";
      if (k.id_ok) n += "(_ID)";
      v.push_back(n);
    }
    for (const char* k : kReaderKeywords) v.push_back(k);
    return v;
  }();
  return all;
}

Deck parse_deck(const std::string& path, const ParseOptions& options) {
  Deck d;
  Parser p(d, options);
  CardReader r(path, d.files, d.params);
  for (;;) {
    const auto ev = r.next();
    if (ev == CardReader::Event::End) break;
    if (ev == CardReader::Event::Keyword)
      p.keyword(r.keyword(), r.keyword_ref());
    else
      p.card(r.card());
  }
  p.finish();
  return d;
}

void fail_at(const Deck& deck, const CardRef& ref, std::string_view keyword, Layout layout,
             std::size_t i, std::string_view what) {
  std::ifstream in(deck.files.name(ref.file), std::ios::binary);
  std::string line;
  for (int n = 0; n < ref.line && std::getline(in, line); ++n) {
  }
  if (!line.empty() && line.back() == '\r') line.pop_back();
  const Card c(line, ref, keyword, deck.files, deck.params);
  c.field(layout, i).fail(what);
}

}  // namespace crashlink::deck
