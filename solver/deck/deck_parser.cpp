// parse_deck: the stream of keywords and cards (card_reader.h) into Deck records. Every value a
// keyword gives is checked here, where its columns are known: an unsupported option of a
// supported keyword stops the reading at its field.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <fstream>

#include "core/errors.h"
#include "solver/deck/card_reader.h"
#include "solver/deck/deck.h"
#include "solver/deck/field_checks.h"
#include "solver/deck/interaction_cards.h"
#include "solver/deck/keyword_layouts.h"
#include "solver/deck/keyword_parser.h"

namespace crashlink::deck {

namespace {

namespace L = layout;
using detail::Block;
using detail::Kw;

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
    {"*SET_SEGMENT", Kw::SetSegment, true, false},
    {"*SET_SHELL_LIST", Kw::SetShellList, true, false},
    {"*CONSTRAINED_NODAL_RIGID_BODY", Kw::RigidConstraint, true, false},
    {"*CONSTRAINED_NODAL_RIGID_BODY_INERTIA", Kw::RigidConstraint, true, false},
    {"*CONSTRAINED_NODAL_RIGID_BODY_SPC", Kw::RigidConstraint, true, false},
    {"*CONSTRAINED_EXTRA_NODES_NODE", Kw::RigidConstraint, false, false},
    {"*CONSTRAINED_EXTRA_NODES_SET", Kw::RigidConstraint, false, false},
    {"*CONSTRAINED_RIGID_BODIES", Kw::RigidConstraint, false, false},
    {"*CONSTRAINED_SPOTWELD", Kw::RigidConstraint, false, true},
    {"*CONSTRAINED_GENERALIZED_WELD_SPOT", Kw::RigidConstraint, false, true},
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
    {"*CONTROL_OUTPUT", Kw::Database, false, false},
    {"*CONTROL_PARALLEL", Kw::Database, false, false},
    {"*LOAD_BODY_X", Kw::LoadBody, false, false},
    {"*LOAD_BODY_Y", Kw::LoadBody, false, false},
    {"*LOAD_BODY_Z", Kw::LoadBody, false, false},
    {"*BOUNDARY_PRESCRIBED_MOTION_NODE", Kw::Motion, false, true},
    {"*BOUNDARY_PRESCRIBED_MOTION_SET", Kw::Motion, false, true},
    {"*BOUNDARY_PRESCRIBED_MOTION_RIGID", Kw::Motion, false, true},
    {"*LOAD_NODE_POINT", Kw::LoadNode, false, false},
    {"*LOAD_NODE_SET", Kw::LoadNode, false, false},
    {"*RIGIDWALL_PLANAR", Kw::RigidWall, false, true},
    {"*RIGIDWALL_PLANAR_MOVING", Kw::RigidWall, false, true},
    {"*RIGIDWALL_PLANAR_FINITE", Kw::RigidWall, false, true},
    {"*RIGIDWALL_PLANAR_FINITE_MOVING", Kw::RigidWall, false, true},
    {"*RIGIDWALL_GEOMETRIC_FLAT", Kw::RigidWall, false, true},
    {"*RIGIDWALL_GEOMETRIC_CYLINDER", Kw::RigidWall, false, true},
};

constexpr const char* kReaderKeywords[] = {"*KEYWORD",
                                           "*END",
                                           "*INCLUDE",
                                           "*INCLUDE_PATH",
                                           "*INCLUDE_PATH_RELATIVE",
                                           "*PARAMETER",
                                           "*PARAMETER_EXPRESSION",
                                           "*COMMENT",
                                           "*DATABASE_*",
                                           "*SENSOR_DEFINE_*",
                                           "*CONTROL_MPP_*"};

bool ends_with(std::string_view s, std::string_view suffix) {
  return s.size() > suffix.size() && s.substr(s.size() - suffix.size()) == suffix;
}

/// The keyword's handler and its suffixes; false if not supported.
bool lookup(std::string_view k, Kw& kw, bool& title, bool& id) {
  title = id = false;
  if (k.rfind("*RIGIDWALL_PLANAR", 0) == 0) {
    // the options in any order: _ID, _FINITE, _MOVING (_ORTHO and _FORCES are not computed)
    std::string_view rest = k.substr(std::string_view("*RIGIDWALL_PLANAR").size());
    bool moving = false, finite = false;
    while (!rest.empty()) {
      if (!id && rest.rfind("_ID", 0) == 0 && (rest.size() == 3 || rest[3] == '_')) {
        id = true;
        rest.remove_prefix(3);
      } else if (!moving && rest.rfind("_MOVING", 0) == 0) {
        moving = true;
        rest.remove_prefix(7);
      } else if (!finite && rest.rfind("_FINITE", 0) == 0) {
        finite = true;
        rest.remove_prefix(7);
      } else {
        id = false;
        return false;
      }
    }
    kw = Kw::RigidWall;
    return true;
  }
  for (std::string_view g : {"*RIGIDWALL_GEOMETRIC_FLAT", "*RIGIDWALL_GEOMETRIC_CYLINDER"})
    if (k == g ||
        (k.size() == g.size() + 3 && k.substr(0, g.size()) == g && k.substr(g.size()) == "_ID")) {
      id = k.size() > g.size();
      kw = Kw::RigidWall;
      return true;
    }
  if (k.rfind("*DATABASE_", 0) == 0) {
    // The outputs whose intervals crashlink takes, and the node histories (probes); the rest of
    // *DATABASE_* is accepted without effect.
    static constexpr std::pair<const char*, Kw> kRead[] = {
        {"*DATABASE_GLSTAT", Kw::DatabaseAscii},
        {"*DATABASE_NODOUT", Kw::DatabaseAscii},
        {"*DATABASE_RCFORC", Kw::DatabaseAscii},
        {"*DATABASE_RWFORC", Kw::DatabaseAscii},
        {"*DATABASE_MATSUM", Kw::DatabaseAscii},
        {"*DATABASE_SLEOUT", Kw::DatabaseAscii},
        {"*DATABASE_RBDOUT", Kw::DatabaseAscii},
        {"*DATABASE_BINARY_D3PLOT", Kw::D3plot},
        {"*DATABASE_HISTORY_NODE", Kw::HistoryNode},
        {"*DATABASE_HISTORY_NODE_SET", Kw::HistoryNode}};
    kw = Kw::Database;
    for (const auto& [name, what] : kRead) {
      if (k == name) kw = what;
      if (k == "*DATABASE_HISTORY_NODE_ID" && what == Kw::HistoryNode) kw = what, id = true;
    }
    return true;
  }
  // a sensor feeds output only, the MPP options split the work of LS-DYNA's processes: without
  // effect on the answer
  if (k.rfind("*SENSOR_DEFINE_", 0) == 0 || k.rfind("*CONTROL_MPP_", 0) == 0) {
    kw = Kw::Database;
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

}  // namespace

namespace detail {

void Parser::keyword(std::string_view k, const CardRef& ref) {
  finish_block();
  b_ = Block{};
  b_.keyword = std::string(k);
  b_.ref = ref;
  bool title = false, id = false;
  if (std::find(ignored().begin(), ignored().end(), std::string(k.substr(1))) != ignored().end()) {
    b_.kw = Kw::Skip;
    d_.skipped_cards[b_.keyword] += 0;
    return;
  }
  if (k.rfind("*SENSOR_", 0) == 0 && k.rfind("*SENSOR_DEFINE_", 0) != 0)
    throw InputError(d_.files.name(ref.file), ref.line, std::string(k),
                     fmt::format("a sensor that switches something (*SENSOR_SWITCH, "
                                 "*SENSOR_CONTROL, ...) is not computed: the run would not do "
                                 "what the deck says; fix: remove it and what it switches, or "
                                 "pass --ignore {} if the switch never acts before the end time. "
                                 "*SENSOR_DEFINE_* (sensors that feed output) are accepted",
                                 k.substr(1)));
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
    w.finite = b_.keyword.find("_FINITE") != std::string::npos ||
               b_.keyword.rfind("*RIGIDWALL_GEOMETRIC_FLAT", 0) == 0;
    w.kind = b_.keyword.rfind("*RIGIDWALL_GEOMETRIC_FLAT", 0) == 0 ? RigidWallCard::Kind::Flat
             : b_.keyword.rfind("*RIGIDWALL_GEOMETRIC_CYLINDER", 0) == 0
                 ? RigidWallCard::Kind::Cylinder
                 : RigidWallCard::Kind::Planar;
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
  if (b_.kw == Kw::SetNodeList || b_.kw == Kw::SetNodeListGenerate || b_.kw == Kw::SetNodeGeneral ||
      b_.kw == Kw::SetPartList || b_.kw == Kw::SetPartListGenerate || b_.kw == Kw::SetShellList) {
    SetCard s;
    s.parts = b_.kw == Kw::SetPartList || b_.kw == Kw::SetPartListGenerate;
    s.shells = b_.kw == Kw::SetShellList;
    s.keyword = b_.keyword;
    s.ref = ref;
    d_.sets.push_back(std::move(s));
  }
  if (b_.kw == Kw::SetSegment) {
    SegmentSetCard s;
    s.keyword = b_.keyword;
    s.ref = ref;
    d_.segment_sets.push_back(std::move(s));
  }
  if (b_.keyword == "*DATABASE_RBDOUT") d_.rigid_body_output = true;
}

void Parser::card(const Card& c) {
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
    case Kw::SetShellList:
      return set(c);
    case Kw::SetNodeGeneral:
      return set_general(c);
    case Kw::SetSegment:
      return segment_set(c);
    case Kw::SpcNode:
    case Kw::SpcSet:
      return spc(c);
    case Kw::RigidConstraint:
      return rigid_constraint(c);
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

void Parser::finish() {
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

const std::vector<std::string>& Parser::ignored() {
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

std::size_t Parser::records_of(Kw kw) const {
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
    case Kw::RigidConstraint:
      return d_.rigid_constraints.size();
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

bool Parser::mid_record() const {
  if (b_.kw != Kw::RigidConstraint) return false;
  const std::string_view k = b_.keyword;
  if (k.starts_with("*CONSTRAINED_GENERALIZED_WELD_SPOT")) return b_.card % (b_.id ? 3 : 2) != 0;
  if (k.starts_with("*CONSTRAINED_NODAL_RIGID_BODY") &&
      (k.find("_INERTIA") != std::string_view::npos || k.find("_SPC") != std::string_view::npos))
    return b_.card > (b_.title ? 1 : 0);
  return false;
}

void Parser::finish_block() {
  // A keyword whose cards are missing would define nothing without a word.
  const std::size_t before = b_.before;
  const bool empty =
      (before != SIZE_MAX && records_of(b_.kw) == before) ||
      ((b_.kw == Kw::Termination || b_.kw == Kw::ControlHourglass || b_.kw == Kw::ControlBulk) &&
       b_.card == 0) ||
      (b_.kw == Kw::Contact && d_.contacts.back().cards == 0) ||
      (b_.kw == Kw::VelocityPlain && b_.card == 1) ||
      (b_.kw == Kw::RigidWall && d_.rigid_walls.back().cards < d_.rigid_walls.back().needed()) ||
      (b_.kw == Kw::DefineCurve && !d_.curves.empty() && records_of(b_.kw) != before &&
       d_.curves.back().a.empty()) ||
      (d_.sets.size() > 0 && b_.kw >= Kw::SetNodeList && b_.kw <= Kw::SetShellList &&
       d_.sets.back().id == 0) ||
      (b_.kw == Kw::SetSegment && d_.segment_sets.back().id == 0);
  if (empty && !b_.keyword.empty())
    throw InputError(d_.files.name(b_.ref.file), b_.ref.line, b_.keyword,
                     b_.kw == Kw::DefineCurve && records_of(b_.kw) != before
                         ? "the curve has no point; fix: add its points (A, O) after LCID"
                         : "its cards are missing (the next keyword or the end of the file "
                           "follows); fix: add them or remove the keyword");
  if (mid_record() || (b_.kw == Kw::RigidConstraint && b_.title && b_.card == 1))
    throw InputError(d_.files.name(last_.file), last_.line, b_.keyword,
                     "its last record is cut short (the next keyword or the end of the file "
                     "follows): a generalized weld takes (WID,) NSID ... and TFAIL ... cards, a "
                     "nodal body's _INERTIA three more cards and _SPC one; fix: add them");
  if (b_.kw == Kw::Part && b_.keyword == "*PART_INERTIA" && b_.card >= 2)
    throw InputError(d_.files.name(d_.parts.back().ref.file), d_.parts.back().ref.line, b_.keyword,
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

bool Parser::title_card(const Card& c) {
  if (b_.title && b_.card == 0) {
    b_.pending_title = std::string(trim(c.whole()));
    b_.card = 1;
    return true;
  }
  return false;
}

void Parser::node(const Card& c) {
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

void Parser::shell(const Card& c) {
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

void Parser::solid(const Card& c) {
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

void Parser::part(const Card& c) {
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

void read_inertia_card(const Card& c, int index, PartCard& p) {
  if (index == 0) {
    for (std::size_t k = 0; k < 3; ++k) p.centre[k] = c.field(L::kPartInertia3, k).real(0.0);
    const auto tm = c.field(L::kPartInertia3, 3);
    p.mass = tm.real(0.0);
    if (!(p.mass > 0.0)) tm.fail("the body's mass must be > 0; fix: write it (deck mass unit)");
    must_be_default(c.field(L::kPartInertia3, 4), 0.0,
                    "an inertia tensor in the principal or a local system (IRCS 1) is not "
                    "read; fix: write IRCS 0 and the tensor in global axes");
    p.centre_node = c.field(L::kPartInertia3, 5).integer(0);
    if (p.centre_node < 0)
      c.field(L::kPartInertia3, 5).fail("must be a node id or 0; fix: write one");
    p.inertia_ref = c.ref();
  } else if (index == 1) {
    for (std::size_t k = 0; k < 6; ++k) p.tensor[k] = c.field(L::kPartInertia4, k).real(0.0);
  } else {
    for (std::size_t k = 0; k < 3; ++k) {
      p.velocity[k] = c.field(L::kPartInertia5, k).real(0.0);
      p.angular_velocity[k] = c.field(L::kPartInertia5, 3 + k).real(0.0);
    }
  }
}

std::uint8_t read_rigid_dofs(const Card& c) {
  // CMO 1: CON1 the held translations, CON2 the held rotations (global axes), each 0 none, 1 x,
  // 2 y, 3 z, 4 x and y, 5 y and z, 6 z and x, 7 all
  const auto cmo = c.field(L::kMatRigid2, 0);
  const double mode = cmo.real(0.0);
  if (mode != 0.0 && mode != 1.0)
    cmo.fail(
        "crashlink reads CMO 0 (no constraint) or 1 (CON1/CON2 in global axes); constraints "
        "in a local system (CMO -1) are not computed; fix: write 1 with global codes");
  static constexpr std::uint8_t kCodes[8] = {0, 1, 2, 4, 3, 6, 5, 7};
  std::uint8_t fixed = 0;
  for (std::size_t f = 1; f <= 2 && mode == 1.0; ++f) {
    const auto con = c.field(L::kMatRigid2, f);
    const auto code = con.integer(0);
    if (code < 0 || code > 7)
      con.fail(
          "must be 0 to 7 (0 none, 1 x, 2 y, 3 z, 4 xy, 5 yz, 6 zx, 7 all); fix: write "
          "one of them");
    fixed |= static_cast<std::uint8_t>(kCodes[static_cast<std::size_t>(code)] << (f == 1 ? 0 : 3));
  }
  return fixed;
}

void Parser::part_inertia(const Card& c) {
  read_inertia_card(c, b_.card - 2, d_.parts.back());
  if (b_.card == 4) {
    b_.card = 0;  // the next part's title
    return;
  }
  ++b_.card;
}

void Parser::set(const Card& c) {
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
      if (hi < lo) e.fail(fmt::format("the range ends before it begins ({}); fix: swap them", lo));
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

void Parser::segment_set(const Card& c) {
  if (title_card(c)) return;
  SegmentSetCard& s = d_.segment_sets.back();
  if (card_index() == 0) {
    s.id = positive_id(c.field(L::kSetHeader, 0));
    s.ref = c.ref();
    b_.card = b_.title ? 2 : 1;
    return;
  }
  if (blank(c)) return;
  std::int64_t n[4];
  for (std::size_t k = 0; k < 4; ++k) n[k] = positive_id(c.field(L::kSetSegment, k));
  for (std::size_t a = 0; a < 4; ++a)
    for (std::size_t b = a + 1; b < 4; ++b)
      if (n[a] == n[b] && !(a == 2 && b == 3))
        c.field(L::kSetSegment, b)
            .fail("repeats a corner; a triangle is written N1 N2 N3 N3; fix: correct the corners");
  s.nodes.insert(s.nodes.end(), n, n + 4);
  s.segment_ref.push_back(c.ref());
}

void Parser::set_general(const Card& c) {
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

void Parser::box(const Card& c) {
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

void Parser::coordinate_system(const Card& c) {
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

void Parser::contact(const Card& c) {
  ContactCard& k = d_.contacts.back();
  if ((b_.id || b_.title) && b_.card == 0) {
    k.heading = std::string(trim(c.field(L::kIdHeading, 1).raw()));
    k.cid = c.field(L::kIdHeading, 0).integer(0);
    b_.card = 1;
    return;
  }
  read_contact_card(c, k.cards++, k, d_.notes);
}

void Parser::rigid_wall(const Card& c) {
  RigidWallCard& w = d_.rigid_walls.back();
  if (b_.id && b_.card == 0) {
    w.heading = std::string(trim(c.field(L::kIdHeading, 1).raw()));
    b_.card = 1;
    return;
  }
  read_rigid_wall_card(c, w.cards++, w);
}

}  // namespace detail

using detail::Parser;

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
