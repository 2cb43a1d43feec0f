// Interface matching (docs/design.md §2.2): copies paired by global id, M = sum_k m^k, typed
// errors.
#include "coupling/interface_match.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

using crashlink::coupling::DomainInterface;
using crashlink::coupling::InterfaceError;
using crashlink::coupling::match_interfaces;

namespace {

// Three domains: car shares 10, 11 with wiper; 11 also with head (contact copy, no own mass);
// 20 between wiper and head. Node order differs per domain on purpose.
std::vector<DomainInterface> three_domains() {
  return {
      {"car", {11, 10}, {2.0, 1.0}, {1, 0, 0, 0, 0, 0}},
      {"wiper", {20, 10, 11}, {0.25, 0.5, 0.125}, {0, 1, 0, 0, 0, 0, 1, 0, 0}},
      {"head", {11, 20}, {0.0, 0.75}, {1, 0, 0, 0, 1, 1e-9}},
  };
}

}  // namespace

TEST(InterfaceMatch, SumsMassesOverDomains) {
  const auto d = three_domains();
  const auto t = match_interfaces(d, 1e-6);
  ASSERT_EQ(t.nodes.size(), 3u);
  EXPECT_EQ(t.nodes[0].id, 10);
  EXPECT_EQ(t.nodes[0].summed_mass_kg, 1.5);
  EXPECT_EQ(t.nodes[1].id, 11);
  EXPECT_EQ(t.nodes[1].summed_mass_kg, 2.125);  // 2 + 0.125 + 0 (contact copy)
  EXPECT_EQ(t.nodes[1].copies.size(), 3u);
  EXPECT_EQ(t.nodes[2].id, 20);
  EXPECT_EQ(t.nodes[2].summed_mass_kg, 1.0);
  EXPECT_EQ(t.nodes[2].position_m[1], 1.0);
  // Back in each domain's Register order, for Setup.summed_masses_kg.
  EXPECT_EQ(t.summed_masses(0), (std::vector<double>{2.125, 1.5}));
  EXPECT_EQ(t.summed_masses(1), (std::vector<double>{1.0, 1.5, 2.125}));
  EXPECT_EQ(t.summed_masses(2), (std::vector<double>{2.125, 1.0}));
  EXPECT_EQ(t.node_of[1], (std::vector<std::int32_t>{2, 0, 1}));
  const auto pairs = t.partner_pairs();
  EXPECT_EQ(pairs, (std::vector<std::pair<int, int>>{{0, 1}, {0, 2}, {1, 2}}));
}

TEST(InterfaceMatch, RejectsPositionsBeyondTheTolerance) {
  auto d = three_domains();
  d[2].positions_m[5] = 2e-6;  // node 20 in head is 2 um off wiper's copy
  try {
    match_interfaces(d, 1e-6);
    FAIL() << "expected InterfaceError";
  } catch (const InterfaceError& e) {
    EXPECT_EQ(e.node_id(), 20);
    EXPECT_EQ(e.domains(), (std::vector<std::string>{"wiper", "head"}));
    const std::string what = e.what();
    EXPECT_NE(what.find("interface node 20"), std::string::npos) << what;
    EXPECT_NE(what.find("'head'"), std::string::npos) << what;
    EXPECT_NE(what.find("tolerance"), std::string::npos) << what;
  }
  EXPECT_NO_THROW(match_interfaces(d, 3e-6));  // inside a looser tolerance
}

TEST(InterfaceMatch, RejectsANodeInOneDomainOnly) {
  auto d = three_domains();
  d[0].node_ids[1] = 99;  // car's node 10 renamed: 99 unmatched, 10 now only in wiper
  try {
    match_interfaces(d, 1e-6);
    FAIL() << "expected InterfaceError";
  } catch (const InterfaceError& e) {
    EXPECT_EQ(e.node_id(), 10);  // the lowest offending id
    EXPECT_EQ(e.domains(), (std::vector<std::string>{"wiper"}));
    EXPECT_NE(std::string(e.what()).find("only"), std::string::npos);
  }
}

TEST(InterfaceMatch, RejectsInconsistentInput) {
  auto sizes = three_domains();
  sizes[1].masses_kg.pop_back();
  EXPECT_THROW(match_interfaces(sizes, 1e-6), crashlink::ModelError);

  auto twice = three_domains();
  twice[1].node_ids[0] = 10;  // wiper lists node 10 twice
  EXPECT_THROW(match_interfaces(twice, 1e-6), crashlink::ModelError);

  auto negative = three_domains();
  negative[0].masses_kg[0] = -1.0;
  EXPECT_THROW(match_interfaces(negative, 1e-6), crashlink::ModelError);

  auto massless = three_domains();
  massless[0].masses_kg[0] = 0.0;
  massless[1].masses_kg[2] = 0.0;  // node 11 has no mass anywhere
  EXPECT_THROW(match_interfaces(massless, 1e-6), InterfaceError);

  EXPECT_THROW(match_interfaces(three_domains(), -1.0), crashlink::ModelError);
}
