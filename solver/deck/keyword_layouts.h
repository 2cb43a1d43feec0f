#pragma once
// The card layouts of the supported keywords: field names as in the LS-DYNA manual and their
// widths in standard format (long format: 20 each; free format: between commas).
#include "solver/deck/card.h"

namespace crashlink::deck::layout {

inline constexpr FieldSpec kNode[] = {{"NID", 8}, {"X", 16}, {"Y", 16},
                                      {"Z", 16},  {"TC", 8}, {"RC", 8}};
inline constexpr FieldSpec kElement[] = {{"EID", 8}, {"PID", 8}, {"N1", 8}, {"N2", 8}, {"N3", 8},
                                         {"N4", 8},  {"N5", 8},  {"N6", 8}, {"N7", 8}, {"N8", 8}};
/// *ELEMENT_SOLID's second card in the two-card layout.
inline constexpr FieldSpec kSolidNodes[] = {{"N1", 8}, {"N2", 8}, {"N3", 8}, {"N4", 8}, {"N5", 8},
                                            {"N6", 8}, {"N7", 8}, {"N8", 8}, {"N9", 8}, {"N10", 8}};
/// *ELEMENT_SHELL_THICKNESS's second card: the corner thicknesses and the material angle.
inline constexpr FieldSpec kShellThickness[] = {
    {"THIC1", 16}, {"THIC2", 16}, {"THIC3", 16}, {"THIC4", 16}, {"BETA", 16}};
inline constexpr FieldSpec kTitle[] = {{"TITLE", 80}};
inline constexpr FieldSpec kIdHeading[] = {{"ID", 10}, {"HEADING", 70}};
inline constexpr FieldSpec kPart[] = {{"PID", 10},  {"SECID", 10}, {"MID", 10},    {"EOSID", 10},
                                      {"HGID", 10}, {"GRAV", 10},  {"ADPOPT", 10}, {"TMID", 10}};
/// *PART_INERTIA's cards 3-5: centre and mass, inertia tensor, initial velocities.
inline constexpr FieldSpec kPartInertia3[] = {{"XC", 10}, {"YC", 10},   {"ZC", 10},
                                              {"TM", 10}, {"IRCS", 10}, {"NODEID", 10}};
inline constexpr FieldSpec kPartInertia4[] = {{"IXX", 10}, {"IXY", 10}, {"IXZ", 10},
                                              {"IYY", 10}, {"IYZ", 10}, {"IZZ", 10}};
inline constexpr FieldSpec kPartInertia5[] = {{"VTX", 10}, {"VTY", 10}, {"VTZ", 10},
                                              {"VRX", 10}, {"VRY", 10}, {"VRZ", 10}};
inline constexpr FieldSpec kSectionShell1[] = {{"SECID", 10}, {"ELFORM", 10}, {"SHRF", 10},
                                               {"NIP", 10},   {"PROPT", 10},  {"QR/IRID", 10},
                                               {"ICOMP", 10}, {"SETYP", 10}};
inline constexpr FieldSpec kSectionShell2[] = {{"T1", 10},   {"T2", 10},    {"T3", 10},
                                               {"T4", 10},   {"NLOC", 10},  {"MAREA", 10},
                                               {"IDOF", 10}, {"EDGSET", 10}};
inline constexpr FieldSpec kSectionSolid[] = {{"SECID", 10}, {"ELFORM", 10}, {"AET", 10}};
inline constexpr FieldSpec kMatElastic[] = {{"MID", 10}, {"RO", 10}, {"E", 10}, {"PR", 10},
                                            {"DA", 10},  {"DB", 10}, {"K", 10}};
inline constexpr FieldSpec kMatRigid1[] = {{"MID", 10}, {"RO", 10},     {"E", 10}, {"PR", 10},
                                           {"N", 10},   {"COUPLE", 10}, {"M", 10}, {"ALIAS", 10}};
inline constexpr FieldSpec kMatRigid2[] = {{"CMO", 10}, {"CON1", 10}, {"CON2", 10}};
inline constexpr FieldSpec kMat003a[] = {{"MID", 10},  {"RO", 10},   {"E", 10},   {"PR", 10},
                                         {"SIGY", 10}, {"ETAN", 10}, {"BETA", 10}};
inline constexpr FieldSpec kMat003b[] = {{"SRC", 10}, {"SRP", 10}, {"FS", 10}, {"VP", 10}};
inline constexpr FieldSpec kMat024a[] = {{"MID", 10},  {"RO", 10},   {"E", 10},    {"PR", 10},
                                         {"SIGY", 10}, {"ETAN", 10}, {"FAIL", 10}, {"TDEL", 10}};
inline constexpr FieldSpec kMat024b[] = {
    {"C", 10}, {"P", 10}, {"LCSS", 10}, {"LCSR", 10}, {"VP", 10}};
inline constexpr FieldSpec kMat024Eps[] = {{"EPS1", 10}, {"EPS2", 10}, {"EPS3", 10}, {"EPS4", 10},
                                           {"EPS5", 10}, {"EPS6", 10}, {"EPS7", 10}, {"EPS8", 10}};
inline constexpr FieldSpec kMat024Es[] = {{"ES1", 10}, {"ES2", 10}, {"ES3", 10}, {"ES4", 10},
                                          {"ES5", 10}, {"ES6", 10}, {"ES7", 10}, {"ES8", 10}};
inline constexpr FieldSpec kCurve[] = {{"LCID", 10}, {"SIDR", 10}, {"SFA", 10},    {"SFO", 10},
                                       {"OFFA", 10}, {"OFFO", 10}, {"DATTYP", 10}, {"LCINT", 10}};
inline constexpr FieldSpec kCurvePoint[] = {{"A", 20}, {"O", 20}};
inline constexpr FieldSpec kSetHeader[] = {{"SID", 10}, {"DA1", 10}, {"DA2", 10},
                                           {"DA3", 10}, {"DA4", 10}, {"SOLVER", 10}};
inline constexpr FieldSpec kSetList[] = {{"ID1", 10}, {"ID2", 10}, {"ID3", 10}, {"ID4", 10},
                                         {"ID5", 10}, {"ID6", 10}, {"ID7", 10}, {"ID8", 10}};
/// *SET_SEGMENT's data cards: the corners and four attributes.
inline constexpr FieldSpec kSetSegment[] = {{"N1", 10}, {"N2", 10}, {"N3", 10}, {"N4", 10},
                                            {"A1", 10}, {"A2", 10}, {"A3", 10}, {"A4", 10}};
inline constexpr FieldSpec kSetGenerate[] = {{"B1BEG", 10}, {"B1END", 10}, {"B2BEG", 10},
                                             {"B2END", 10}, {"B3BEG", 10}, {"B3END", 10},
                                             {"B4BEG", 10}, {"B4END", 10}};
/// *CONSTRAINED_NODAL_RIGID_BODY card 1.
inline constexpr FieldSpec kNodalRigidBody[] = {{"PID", 10},   {"CID", 10},  {"NSID", 10},
                                                {"PNODE", 10}, {"IPRT", 10}, {"DRFLAG", 10},
                                                {"RRFLAG", 10}};
/// *CONSTRAINED_EXTRA_NODES_NODE / _SET.
inline constexpr FieldSpec kExtraNodes[] = {{"PID", 10}, {"NID/NSID", 10}, {"IFLAG", 10}};
/// *CONSTRAINED_SPOTWELD (after the _ID card's WID).
inline constexpr FieldSpec kSpotWeld[] = {{"N1", 10}, {"N2", 10}, {"SN", 10}, {"SS", 10},
                                          {"N", 10},  {"M", 10},  {"TF", 10}, {"EP", 10}};
inline constexpr FieldSpec kSpotWeldId[] = {{"WID", 10}};
/// *CONSTRAINED_GENERALIZED_WELD_SPOT: card 1 (the nodes), card 2 (the failure).
inline constexpr FieldSpec kGeneralizedWeld1[] = {{"NSID", 10},   {"CID", 10}, {"FILTER", 10},
                                                  {"WINDOW", 10}, {"NPR", 10}, {"NPRT", 10}};
inline constexpr FieldSpec kGeneralizedWeldSpot[] = {{"TFAIL", 10}, {"EPSF", 10}, {"SN", 10},
                                                     {"SS", 10},    {"N", 10},    {"M", 10}};
/// *CONSTRAINED_RIGID_BODIES.
inline constexpr FieldSpec kRigidBodies[] = {{"PIDL", 10}, {"PIDC", 10}, {"IFLAG", 10}};
inline constexpr FieldSpec kSpcNode[] = {{"NID", 10},  {"CID", 10},   {"DOFX", 10},  {"DOFY", 10},
                                         {"DOFZ", 10}, {"DOFRX", 10}, {"DOFRY", 10}, {"DOFRZ", 10}};
inline constexpr FieldSpec kSpcSet[] = {{"NSID", 10}, {"CID", 10},   {"DOFX", 10},  {"DOFY", 10},
                                        {"DOFZ", 10}, {"DOFRX", 10}, {"DOFRY", 10}, {"DOFRZ", 10}};
inline constexpr FieldSpec kVelocityGeneration1[] = {{"ID", 10},    {"STYP", 10}, {"OMEGA", 10},
                                                     {"VX", 10},    {"VY", 10},   {"VZ", 10},
                                                     {"IVATN", 10}, {"ICID", 10}};
inline constexpr FieldSpec kVelocityGeneration2[] = {{"XC", 10},    {"YC", 10},    {"ZC", 10},
                                                     {"NX", 10},    {"NY", 10},    {"NZ", 10},
                                                     {"PHASE", 10}, {"IRIGID", 10}};
/// *INITIAL_VELOCITY: card 1 (the nodes), card 2 (the velocity).
inline constexpr FieldSpec kInitialVelocity1[] = {
    {"NSID", 10}, {"NSIDEX", 10}, {"BOXID", 10}, {"IRIGID", 10}, {"ICID", 10}};
inline constexpr FieldSpec kInitialVelocity2[] = {{"VX", 10},  {"VY", 10},  {"VZ", 10},
                                                  {"VXR", 10}, {"VYR", 10}, {"VZR", 10}};
inline constexpr FieldSpec kVelocityNode[] = {{"NID", 10}, {"VX", 10},  {"VY", 10},  {"VZ", 10},
                                              {"VXR", 10}, {"VYR", 10}, {"VZR", 10}, {"ICID", 10}};
/// *DATABASE_GLSTAT, _NODOUT, _RCFORC, _RWFORC, _MATSUM, _SLEOUT (the ASCII histories).
inline constexpr FieldSpec kDatabaseAscii[] = {
    {"DT", 10}, {"BINARY", 10}, {"LCUR", 10}, {"IOOPT", 10}};
inline constexpr FieldSpec kD3plot[] = {
    {"DT", 10}, {"LCDT", 10}, {"BEAM", 10}, {"NPLTC", 10}, {"PSETID", 10}};
/// *DATABASE_HISTORY_NODE and _SET: eight ids per card (_ID: kIdHeading per node).
inline constexpr FieldSpec kHistoryIds[] = {{"ID1", 10}, {"ID2", 10}, {"ID3", 10}, {"ID4", 10},
                                            {"ID5", 10}, {"ID6", 10}, {"ID7", 10}, {"ID8", 10}};
/// *BOUNDARY_PRESCRIBED_MOTION_NODE / _SET.
inline constexpr FieldSpec kMotionNode[] = {{"NID", 10}, {"DOF", 10}, {"VAD", 10},   {"LCID", 10},
                                            {"SF", 10},  {"VID", 10}, {"DEATH", 10}, {"BIRTH", 10}};
inline constexpr FieldSpec kMotionSet[] = {{"NSID", 10}, {"DOF", 10}, {"VAD", 10},   {"LCID", 10},
                                           {"SF", 10},   {"VID", 10}, {"DEATH", 10}, {"BIRTH", 10}};
inline constexpr FieldSpec kMotionRigid[] = {{"PID", 10},   {"DOF", 10},  {"VAD", 10},
                                             {"LCID", 10},  {"SF", 10},   {"VID", 10},
                                             {"DEATH", 10}, {"BIRTH", 10}};
/// *LOAD_NODE_POINT / _SET.
inline constexpr FieldSpec kLoadNode[] = {{"NID", 10}, {"DOF", 10}, {"LCID", 10}, {"SF", 10},
                                          {"CID", 10}, {"M1", 10},  {"M2", 10},   {"M3", 10}};
inline constexpr FieldSpec kLoadSet[] = {{"NSID", 10}, {"DOF", 10}, {"LCID", 10}, {"SF", 10},
                                         {"CID", 10},  {"M1", 10},  {"M2", 10},   {"M3", 10}};
/// *CONTROL_CONTACT card 1, *CONTROL_SHELL card 1, *CONTROL_ENERGY card 1.
inline constexpr FieldSpec kControlContact[] = {{"SLSFAC", 10}, {"RWPNAL", 10}, {"ISLCHK", 10},
                                                {"SHLTHK", 10}, {"PENOPT", 10}, {"THKCHG", 10},
                                                {"ORIEN", 10},  {"ENMASS", 10}};
inline constexpr FieldSpec kControlShell[] = {{"WRPANG", 10}, {"ESORT", 10},  {"IRNXX", 10},
                                              {"ISTUPD", 10}, {"THEORY", 10}, {"BWC", 10},
                                              {"MITER", 10},  {"PROJ", 10}};
inline constexpr FieldSpec kTermination[] = {{"ENDTIM", 10}, {"ENDCYC", 10}, {"DTMIN", 10},
                                             {"ENDENG", 10}, {"ENDMAS", 10}, {"NOSOL", 10}};
inline constexpr FieldSpec kTimestep[] = {{"DTINIT", 10}, {"TSSFAC", 10}, {"ISDO", 10},
                                          {"TSLIMT", 10}, {"DT2MS", 10},  {"LCTM", 10},
                                          {"ERODE", 10},  {"MS1ST", 10}};

inline constexpr FieldSpec kBox[] = {{"BOXID", 10}, {"XMN", 10}, {"XMX", 10}, {"YMN", 10},
                                     {"YMX", 10},   {"ZMN", 10}, {"ZMX", 10}};
/// *SET_NODE_GENERAL's data cards: an option and up to seven ids.
inline constexpr FieldSpec kSetGeneral[] = {{"OPTION", 10}, {"E1", 10}, {"E2", 10}, {"E3", 10},
                                            {"E4", 10},     {"E5", 10}, {"E6", 10}, {"E7", 10}};
inline constexpr FieldSpec kCoordinateSystem1[] = {{"CID", 10}, {"XO", 10},  {"YO", 10},
                                                   {"ZO", 10},  {"XL", 10},  {"YL", 10},
                                                   {"ZL", 10},  {"CIDL", 10}};
inline constexpr FieldSpec kCoordinateSystem2[] = {{"XP", 10}, {"YP", 10}, {"ZP", 10}};
inline constexpr FieldSpec kContact1[] = {{"SSID", 10},  {"MSID", 10},   {"SSTYP", 10},
                                          {"MSTYP", 10}, {"SBOXID", 10}, {"MBOXID", 10},
                                          {"SPR", 10},   {"MPR", 10}};
inline constexpr FieldSpec kContact2[] = {{"FS", 10},  {"FD", 10},     {"DC", 10}, {"VC", 10},
                                          {"VDC", 10}, {"PENCHK", 10}, {"BT", 10}, {"DT", 10}};
inline constexpr FieldSpec kContact3[] = {{"SFS", 10},  {"SFM", 10},  {"SST", 10}, {"MST", 10},
                                          {"SFST", 10}, {"SFMT", 10}, {"FSF", 10}, {"VSF", 10}};
inline constexpr FieldSpec kContactA[] = {{"SOFT", 10},   {"SOFSCL", 10}, {"LCIDAB", 10},
                                          {"MAXPAR", 10}, {"SBOPT", 10},  {"DEPTH", 10},
                                          {"BSORT", 10},  {"FRCFRQ", 10}};
inline constexpr FieldSpec kContactB[] = {{"PENMAX", 10}, {"THKOPT", 10}, {"SHLTHK", 10},
                                          {"SNLOG", 10},  {"ISYM", 10},   {"I2D3D", 10},
                                          {"SLDTHK", 10}, {"SLDSTF", 10}};
inline constexpr FieldSpec kContactC[] = {{"IGAP", 10},   {"IGNORE", 10}, {"DPRFAC", 10},
                                          {"DTSTIF", 10}, {"EDGEK", 10},  {"UNUSED", 10},
                                          {"FLANGL", 10}, {"CID_RCF", 10}};

inline constexpr FieldSpec kHourglass[] = {{"HGID", 10}, {"IHQ", 10}, {"QM", 10}, {"IBQ", 10},
                                           {"Q1", 10},   {"Q2", 10},  {"QB", 10}, {"QW", 10}};
inline constexpr FieldSpec kControlHourglass[] = {{"IHQ", 10}, {"QH", 10}};
inline constexpr FieldSpec kControlBulk[] = {{"Q1", 10}, {"Q2", 10}, {"TYPE", 10}, {"BTYPE", 10}};
inline constexpr FieldSpec kLoadBody[] = {{"LCID", 10}, {"SF", 10}, {"LCIDDR", 10}, {"XC", 10},
                                          {"YC", 10},   {"ZC", 10}, {"CID", 10}};

inline constexpr FieldSpec kRigidWall1[] = {{"NSID", 10},   {"NSIDEX", 10}, {"BOXID", 10},
                                            {"OFFSET", 10}, {"BIRTH", 10},  {"DEATH", 10},
                                            {"RWKSF", 10}};
inline constexpr FieldSpec kRigidWall2[] = {{"XT", 10}, {"YT", 10}, {"ZT", 10},   {"XH", 10},
                                            {"YH", 10}, {"ZH", 10}, {"FRIC", 10}, {"WVEL", 10}};
/// *RIGIDWALL_GEOMETRIC_...'s card 1 (no OFFSET, no RWKSF).
inline constexpr FieldSpec kRigidWallGeometric1[] = {
    {"NSID", 10}, {"NSIDEX", 10}, {"BOXID", 10}, {"BIRTH", 10}, {"DEATH", 10}};
/// *RIGIDWALL_PLANAR_FINITE's and *RIGIDWALL_GEOMETRIC_FLAT's card: the edge l from the tail to
/// (XHEV, YHEV, ZHEV), the lengths along l and m = n x l.
inline constexpr FieldSpec kRigidWallFinite[] = {{"XHEV", 10}, {"YHEV", 10}, {"ZHEV", 10},
                                                 {"LENL", 10}, {"LENM", 10}, {"NSEGS", 10}};
/// *RIGIDWALL_GEOMETRIC_CYLINDER's card 3.
inline constexpr FieldSpec kRigidWallCylinder[] = {{"RADCYL", 10}, {"LENCYL", 10}, {"NSEGS", 10}};
/// *RIGIDWALL_PLANAR_MOVING's card: the wall's mass and initial velocity along its normal.
inline constexpr FieldSpec kRigidWallMoving[] = {{"MASS", 10}, {"V0", 10}};

}  // namespace crashlink::deck::layout
