// result.xdmf: well-formed XML whose every HDF5 reference exists in result.h5 with the declared
// dimensions.
#include "solver/io/xdmf_writer.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include "solver/io/result_writer.h"
#include "tests/unit/io/result_h5_reader.h"

namespace crashlink::io {
namespace {

std::string slurp(const std::string& path) {
  std::ifstream f(path);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

/// A tiny well-formedness check: tags balance and nest, attribute values are quoted, no stray '&'.
::testing::AssertionResult well_formed(const std::string& xml) {
  std::vector<std::string> open;
  std::size_t i = 0;
  if (xml.rfind("<?xml", 0) != 0) return ::testing::AssertionFailure() << "no XML declaration";
  while ((i = xml.find('<', i)) != std::string::npos) {
    const std::size_t end = xml.find('>', i);
    if (end == std::string::npos)
      return ::testing::AssertionFailure() << "unterminated tag at " << i;
    const std::string tag = xml.substr(i + 1, end - i - 1);
    i = end + 1;
    if (tag.empty() || tag[0] == '?' || tag[0] == '!') continue;
    if (tag[0] == '/') {
      if (open.empty() || open.back() != tag.substr(1)) {
        return ::testing::AssertionFailure()
               << "</" << tag.substr(1) << "> closes " << (open.empty() ? "nothing" : open.back());
      }
      open.pop_back();
      continue;
    }
    if (std::count(tag.begin(), tag.end(), '"') % 2 != 0) {
      return ::testing::AssertionFailure() << "unbalanced quotes in <" << tag << ">";
    }
    const std::string name = tag.substr(0, tag.find_first_of(" \t\n/"));
    if (tag.back() != '/') open.push_back(name);
  }
  if (!open.empty()) return ::testing::AssertionFailure() << "<" << open.back() << "> never closed";
  if (std::regex_search(xml, std::regex("&(?!(amp|lt|gt|quot|apos);)"))) {
    return ::testing::AssertionFailure() << "unescaped '&'";
  }
  return ::testing::AssertionSuccess();
}

/// Every DataItem "result.h5:/path" exists in the file with the declared Dimensions.
void expect_references_exist(const std::string& xml, const std::string& h5, std::size_t expected) {
  test::H5Reader r(h5);
  const std::regex item("<DataItem Dimensions=\"([0-9 ]+)\"[^>]*>result\\.h5:([^<]+)</DataItem>");
  std::size_t count = 0;
  for (auto it = std::sregex_iterator(xml.begin(), xml.end(), item); it != std::sregex_iterator();
       ++it) {
    ++count;
    const std::string dims = (*it)[1], path = (*it)[2];
    ASSERT_TRUE(r.exists(path)) << path;
    std::string actual;
    for (hsize_t d : r.dims(path)) {
      if (!actual.empty()) actual.push_back(' ');
      actual.append(std::to_string(d));
    }
    EXPECT_EQ(actual, dims) << path;
  }
  EXPECT_EQ(count, expected);
}

TEST(XdmfWriter, MeshOnlyFileReferencesTheReferenceCoordinates) {
  const std::string dir = test::fresh_dir("out");
  ResultWriter w(dir, test::small_model());
  const std::string xml = slurp(w.xdmf_path());
  EXPECT_TRUE(well_formed(xml)) << xml;
  EXPECT_NE(xml.find("result.h5:/mesh/coordinates"), std::string::npos);
  expect_references_exist(xml, w.h5_path(), 4);  // 2 parts x (topology + geometry)
}

TEST(XdmfWriter, TemporalCollectionOfStatesReferencesExistingDatasets) {
  const std::string dir = test::fresh_dir("out");
  const model::Model m = test::small_model();
  std::vector<double> u(3 * m.nodes.count(), 0.1), eps{0.2}, vm{3e8}, sig(6, 1e6), vm2{1.0, 2.0};
  {
    ResultWriter w(dir, m);
    w.write_field_state(
        FieldState{0.0, u, u, {PartFieldState{eps, vm, sig}, PartFieldState{{}, vm2, {}}}});
    w.write_field_state(FieldState{0.5e-3, u, {}, {}});
  }
  const std::string xml = slurp(dir + "/result.xdmf");
  EXPECT_TRUE(well_formed(xml)) << xml;
  EXPECT_NE(xml.find("CollectionType=\"Temporal\""), std::string::npos);
  EXPECT_NE(xml.find("TopologyType=\"Hexahedron\""), std::string::npos);
  EXPECT_NE(xml.find("TopologyType=\"Quadrilateral\""), std::string::npos);
  EXPECT_NE(xml.find("<Time Value=\"0.0005\"/>"), std::string::npos);
  // state 0: 2 parts x (topology, geometry, displacement, velocity) + block eps_p, von_mises,
  // stress + plate von_mises = 12; state 1: 2 x (topology, geometry, displacement) = 6
  expect_references_exist(xml, dir + "/result.h5", 18);
  EXPECT_FALSE(std::filesystem::exists(dir + "/result.xdmf.tmp"));
  // A real XML parser agrees, when one is at hand.
  if (std::filesystem::exists("/usr/bin/python3")) {
    const std::string cmd =
        "/usr/bin/python3 -c \"import sys, xml.etree.ElementTree as E; "
        "sys.exit(0 if E.parse(sys.argv[1]).getroot().tag == 'Xdmf' else 1)\" " +
        dir + "/result.xdmf";
    EXPECT_EQ(std::system(cmd.c_str()), 0);
  }
}

TEST(XdmfWriter, EscapesPartNames) {
  XdmfDocument doc;
  doc.node_count = 4;
  doc.reference_coordinates = "/mesh/coordinates";
  doc.parts.push_back(XdmfPart{"A&B <\"x\">", false, 1, "/mesh/parts/A&B/connectivity"});
  const std::string xml = xdmf_text(doc);
  EXPECT_TRUE(well_formed(xml)) << xml;
  EXPECT_NE(xml.find("A&amp;B &lt;&quot;x&quot;&gt;"), std::string::npos) << xml;
}

}  // namespace
}  // namespace crashlink::io
