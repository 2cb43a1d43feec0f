// /history/contacts/<name>/{time, force, energy}: one row per history sample, resultant force
// [k,3] in N, the interface's contact energy [k] in J (issue 21: like LS-DYNA's sleout).
#include <gtest/gtest.h>

#include <cmath>
#include <span>

#include "solver/io/result_reader.h"
#include "solver/io/result_writer.h"
#include "tests/unit/io/result_h5_reader.h"

namespace crashlink::io {
namespace {

TEST(ResultWriter, ContactHistoriesAreWrittenPerInterface) {
  auto m = test::small_model();
  m.contacts.push_back({});
  m.contacts.back().name = "head/plate";  // '/' is not allowed in a link name: becomes '_'
  m.contacts.push_back({});
  m.contacts.back().name = "plate_wiper";
  const auto dir = test::fresh_dir("contacts");
  {
    ResultWriter w(dir, m);
    std::vector<ProbeSample> probes(m.probes.size());
    for (int i = 0; i < 5; ++i) {
      std::vector<ContactSample> c(2);
      for (int k = 0; k < 2; ++k)
        for (int d = 0; d < 3; ++d) c[k].force_N[d] = 100.0 * k + 10.0 * i + d;
      w.append_history(GlstatSample{1e-4 * i}, probes, c);
    }
    EXPECT_THROW(w.append_history(GlstatSample{}, probes, {}), ResultFileError);
  }
  test::H5Reader r(dir + "/result.h5");
  const auto t = r.doubles("/history/contacts/head_plate/time");
  const auto f = r.doubles("/history/contacts/plate_wiper/force");
  ASSERT_EQ(t.size(), 5u);
  ASSERT_EQ(f.size(), 15u);
  EXPECT_EQ(t[4], 4e-4);
  EXPECT_EQ(f[3 * 4 + 2], 100.0 + 40.0 + 2.0);
}

/// Two contacts, five rows each: energy of contact k at row i = (1 - 2k) (0.5 i) J (the second
/// goes below zero: energy it created), written by append_history (buffered) or
/// append_contact_rows (the gather's whole columns).
void write_energies(const std::string& dir, const model::Model& m, bool columns) {
  ResultWriter w(dir, m);
  std::vector<ProbeSample> probes(m.probes.size());
  std::vector<double> time_s;
  std::vector<std::vector<ContactSample>> rows(2);
  for (int i = 0; i < 5; ++i) {
    std::vector<ContactSample> c(2);
    for (int k = 0; k < 2; ++k) {
      c[k].force_N[0] = 10.0 * i + k;
      c[k].energy_J = (1.0 - 2.0 * k) * 0.5 * i;
      rows[k].push_back(c[k]);
    }
    time_s.push_back(1e-4 * i);
    if (!columns) w.append_history(GlstatSample{1e-4 * i}, probes, c);
  }
  if (columns)
    for (std::size_t k = 0; k < 2; ++k) w.append_contact_rows(k, time_s, rows[k]);
}

model::Model two_contacts() {
  auto m = test::small_model();
  m.contacts.push_back({});
  m.contacts.back().name = "head_plate";
  m.contacts.push_back({});
  m.contacts.back().name = "plate/wiper";
  return m;
}

TEST(ResultWriter, ContactEnergyIsWrittenPerInterfaceInJoules) {
  const auto m = two_contacts();
  for (const bool columns : {false, true}) {
    const auto dir = test::fresh_dir(columns ? "columns" : "rows");
    write_energies(dir, m, columns);
    test::H5Reader r(dir + "/result.h5");
    const std::string c = "/history/contacts/plate_wiper";
    ASSERT_TRUE(r.exists(c + "/energy")) << (columns ? "append_contact_rows" : "append_history");
    EXPECT_EQ(r.dims(c + "/energy"), (std::vector<hsize_t>{5}));
    EXPECT_EQ(r.attr_string(c + "/energy", "units"), "J");
    EXPECT_EQ(r.doubles(c + "/energy"), (std::vector<double>{0.0, -0.5, -1.0, -1.5, -2.0}));
    EXPECT_EQ(r.doubles("/history/contacts/head_plate/energy"),
              (std::vector<double>{0.0, 0.5, 1.0, 1.5, 2.0}));
    EXPECT_EQ(r.doubles(c + "/time").size(), 5u);  // same rows as time and force
  }
}

TEST(ResultReader, ContactEnergyRoundTripsAndOlderFilesHaveNone) {
  const auto m = two_contacts();
  const auto dir = test::fresh_dir("energy");
  write_energies(dir, m, false);
  {
    const ResultReader r(dir + "/result.h5");
    const ContactHistory h = r.contact("plate/wiper");
    EXPECT_EQ(h.energy_J, (std::vector<double>{0.0, -0.5, -1.0, -1.5, -2.0}));
    const auto rows = contact_samples(h, 3);
    EXPECT_EQ(rows[2].energy_J, -1.0);  // what the gather and a restart copy
    EXPECT_EQ(rows[2].force_N[0], 21.0);
  }
  // A file written before the dataset existed: no energy, and copies say "not known" (NaN).
  {
    FileHandle f(H5Fopen((dir + "/result.h5").c_str(), H5F_ACC_RDWR, H5P_DEFAULT));
    ASSERT_TRUE(f.valid());
    for (const char* c :
         {"/history/contacts/head_plate/energy", "/history/contacts/plate_wiper/energy"})
      ASSERT_GE(H5Ldelete(f.get(), c, H5P_DEFAULT), 0) << c;
  }
  const ResultReader r(dir + "/result.h5");
  const ContactHistory h = r.contact("head_plate");
  EXPECT_EQ(h.size(), 5u);
  EXPECT_TRUE(h.energy_J.empty());
  const auto rows = contact_samples(h, 5);
  EXPECT_TRUE(std::isnan(rows[4].energy_J));
  EXPECT_EQ(rows[4].force_N[0], 40.0);
}

}  // namespace
}  // namespace crashlink::io
