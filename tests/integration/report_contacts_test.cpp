// `crashlink report` and tools/report.py on the contacts (issue 21, item 5): the contact forces
// are filtered by SAE J211/1 CFC 180 on the C++ side (DIR/contact_forces_cfc180.csv, which the
// plot reads and names), the energy plot shows each interface's energy, and a file written before
// /history/contacts/<name>/energy existed still gives every plot.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "solver/io/hdf5_handles.h"
#include "solver/io/result_writer.h"
#include "tests/integration/process_test_support.h"
#include "tests/integration/shell_command.h"
#include "tests/unit/io/result_h5_reader.h"

using namespace crashlink;

namespace {

constexpr double kPi = 3.14159265358979323846;

/// tiny (result_h5_reader.h) without its probes, two contacts; 1501 history rows at 100 kHz
/// (15 ms): a 10 ms half-sine force of 10 kN along z with a 20 kHz ripple of 2 kN on it (what CFC
/// 180 removes; the pulse's 50 Hz pass), and contact energies 0.5 sin(pi t / 30 ms) J
/// ('hood_wiper': its negative, energy it created).
std::string write_result(const std::filesystem::path& dir) {
  auto m = io::test::small_model();
  m.probes.clear();
  m.contacts.resize(2);
  m.contacts[0].name = "head_hood";
  m.contacts[1].name = "hood_wiper";
  io::ResultWriter w(dir.string(), m);
  for (int i = 0; i <= 1500; ++i) {
    const double t = 1e-5 * i;
    io::GlstatSample g{t};
    g.kinetic_energy_J = 10.0;
    g.total_energy_J = 10.0;
    std::vector<io::ContactSample> c(2);
    for (int k = 0; k < 2; ++k) {
      const double pulse = t < 1e-2 ? 1e4 * std::sin(kPi * t / 1e-2) : 0.0;
      c[k].force_N[2] = pulse + (pulse > 0.0 ? 2e3 * std::sin(2.0 * kPi * 2e4 * t) : 0.0);
      c[k].energy_J = (k == 0 ? 0.5 : -0.5) * std::sin(kPi * t / 3e-2);
    }
    w.append_history(g, {}, c);
  }
  const std::string h5 = w.h5_path();
  w.close();
  return h5;
}

/// contact -> {filter, force_kN[]} of the report's CSV.
std::map<std::string, std::pair<std::string, std::vector<double>>> read_csv(
    const std::filesystem::path& path) {
  std::map<std::string, std::pair<std::string, std::vector<double>>> out;
  std::ifstream f(path);
  std::string line;
  std::getline(f, line);
  EXPECT_EQ(line, "contact,filter,time_ms,force_kN");
  while (std::getline(f, line)) {
    const auto a = line.find(','), b = line.find(',', a + 1), c = line.find(',', b + 1);
    auto& entry = out[line.substr(0, a)];
    entry.first = line.substr(a + 1, b - a - 1);
    entry.second.push_back(std::stod(line.substr(c + 1)));
  }
  return out;
}

std::string crashlink_exe() {
  return std::string(CRASHLINK_BINARY_DIR) + "/apps/crashlink";
}

}  // namespace

TEST(ReportContacts, ForcesAreFilteredByCfc180AndEnergiesPlotted) {
  const auto dir = proc_test::fresh_dir("report-contacts");
  const proc_test::RemoveIfPassed cleanup{dir};
  const std::string h5 = write_result(dir / "run");
  int status = -1;
  const std::string out = crashlink::testing::run_command(
      crashlink_exe() + " report " + h5 + " --out " + (dir / "report").string(), status);
  ASSERT_EQ(status, 0) << out;
  for (const char* file : {"energy.png", "contact_forces.png", "contact_forces_cfc180.csv"}) {
    EXPECT_TRUE(std::filesystem::exists(dir / "report" / file)) << file << "\n" << out;
  }
  const auto csv = read_csv(dir / "report" / "contact_forces_cfc180.csv");
  ASSERT_EQ(csv.size(), 2u);
  for (const auto& [name, entry] : csv) {
    EXPECT_EQ(entry.first, "CFC 180") << name;
    ASSERT_EQ(entry.second.size(), 1501u) << name;  // uniform sampling: not resampled
    double peak = 0.0;
    for (double f : entry.second) peak = std::max(peak, f);
    // the ripple (up to 12 kN raw) is gone, the half-sine's 10 kN kept
    std::printf("[measured] %s: filtered peak %.3f kN (raw 10 kN half-sine + 2 kN at 20 kHz)\n",
                name.c_str(), peak);
    EXPECT_GT(peak, 9.8) << name;
    EXPECT_LT(peak, 10.1) << name;
  }
}

// A result.h5 without /history/contacts/<name>/energy (written before it existed): the report
// still draws every plot, through `crashlink report` and through the script alone (whose force
// plot then says the forces are unfiltered).
TEST(ReportContacts, OlderFilesWithoutContactEnergyStillReport) {
  const auto dir = proc_test::fresh_dir("report-old-file");
  const proc_test::RemoveIfPassed cleanup{dir};
  const std::string h5 = write_result(dir / "run");
  {
    io::FileHandle f(H5Fopen(h5.c_str(), H5F_ACC_RDWR, H5P_DEFAULT));
    ASSERT_TRUE(f.valid());
    for (const char* c :
         {"/history/contacts/head_hood/energy", "/history/contacts/hood_wiper/energy"})
      ASSERT_GE(H5Ldelete(f.get(), c, H5P_DEFAULT), 0) << c;
  }
  int status = -1;
  const std::string out = crashlink::testing::run_command(
      crashlink_exe() + " report " + h5 + " --out " + (dir / "a").string(), status);
  EXPECT_EQ(status, 0) << out;
  const std::string script = std::string(CRASHLINK_SOURCE_DIR) + "/tools/report.py";
  const std::string alone = crashlink::testing::run_command(
      "/usr/bin/python3 " + script + " " + h5 + " " + (dir / "b").string(), status);
  EXPECT_EQ(status, 0) << alone;
  for (const char* sub : {"a", "b"}) {
    for (const char* png : {"energy.png", "contact_forces.png"}) {
      const auto path = dir / sub / png;
      ASSERT_TRUE(std::filesystem::exists(path)) << path << "\n" << out << alone;
      EXPECT_GT(std::filesystem::file_size(path), 1000u) << path;
    }
  }
}
