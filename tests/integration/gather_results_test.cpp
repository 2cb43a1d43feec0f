// The gather of a coupled run (solver/gather/gather_results.h): a split (common step) `layer` run
// in one process (cosim::SplitRunner, one Solver per domain) writes one io::ResultWriter file per
// domain, DIR/domains/<domain>.h5, each domain sampling on its own like a daemon; gather_results
// merges them into DIR/result.h5 + result.xdmf, which must agree with a mono run's result.h5 of
// the same model (run::run_single_domain): split reproduces mono to round-off
// (split_mono_test.cpp), so glstat, probes and states agree to 1e-9 relative, the mesh is
// identical, and element fields of the part split across domains (the coarse part's first layer
// moved into the fine domain, docs/design.md §2.7) come back complete and in global order.
// Also: a domain file cut short (a daemon that stopped early), a missing one, domains sampled at
// different instants (interpolation), and coordinator.h5 copied in.
#include "solver/gather/gather_results.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "core/errors.h"
#include "solver/contact/contact_interface.h"
#include "solver/integration/solver.h"
#include "solver/io/coupling_history_writer.h"
#include "solver/io/result_reader.h"
#include "solver/io/result_writer.h"
#include "solver/partition/decomposition.h"
#include "solver/run/domain_recorder.h"
#include "solver/run/run_single.h"
#include "tests/support/split_runner.h"
#include "tests/unit/io/result_h5_reader.h"
#include "tests/unit/partition/partition_models.h"

using namespace crashlink;
using crashlink::io::test::H5Reader;

namespace {

namespace fs = std::filesystem;

/// A fresh directory under the temp dir, per process (ctest runs the tests of this file in
/// parallel processes, each with its own suite set-up).
std::string fresh(const std::string& name) {
  const fs::path p = fs::temp_directory_path() / "crashlink_gather_tests" /
                     std::to_string(static_cast<long long>(::getpid())) / name;
  fs::remove_all(p);
  fs::create_directories(p);
  return p.string();
}

/// What a daemon writes (solver/daemon): its sub-model's result file DIR/domains/<domain>.h5,
/// sampled by run::DomainRecorder (the sampling the daemons and the mono run share) on the
/// domain's own step grid. `stop_s`: the daemon stops sampling after this time and never writes
/// /timing (it died).
class DaemonFile {
 public:
  DaemonFile(const std::string& dir, const partition::DomainModel& dm,
             const integration::Solver& solver, double stop_s)
      : writer_(dir + "/domains", dm.model, options(dm.name)),
        recorder_(writer_, solver),
        solver_(solver),
        stop_s_(stop_s) {}

  void sample() {
    if (solver_.time_s() <= stop_s_) recorder_.sample();
  }
  void finish() {
    if (solver_.time_s() <= stop_s_) {
      recorder_.finish();
      writer_.write_timing(1.0, 0.0,
                           {{solver_.domain_name(), 0.5, solver_.cycle(), solver_.dt_min_s(),
                             static_cast<std::int64_t>(solver_.model().element_count())}});
    }
    writer_.close();
  }

 private:
  static io::ResultWriterOptions options(const std::string& name) {
    io::ResultWriterOptions o;
    o.file_stem = name;  // DIR/domains/<domain>.h5, as solver/daemon writes it
    return o;
  }
  io::ResultWriter writer_;
  run::DomainRecorder recorder_;
  const integration::Solver& solver_;
  double stop_s_;
};

/// The bar of partition_models.h (coarse part 0.1 m elements | fine part 0.05 m, fixed at x = 0,
/// pulled at the tip, probes "tip" (fine) and "j" (on J: owned by coarse, a ghost in fine)) in J2
/// steel, hit by 12 m/s so that it yields (rho c v ~ 490 MPa > 200 MPa).
model::Model plastic_bar() {
  auto m = crashlink::testing::bar_two_sizes();
  m.materials[0] = {"j2", materials::MaterialKind::J2Plastic,      7850.0, 210e9,
                    0.3,  {{0.0, 0.1, 0.5}, {200e6, 300e6, 400e6}}};
  m.initial_velocities[0].velocity_m_s = {12.0, 0.0, 0.0};
  m.controls.end_time_s = 3e-3;  // ~ 300 steps; the wave runs the bar's length 4 times
  m.controls.history_interval_s = 2e-5;
  m.controls.field_interval_s = 2e-4;
  m.controls.bulk_viscosity = true;
  return m;
}

/// block_on_floor of partition_models.h (a fine hex block, domain "block", over a coarse shell
/// floor "plate" + "frame", domain "floor"; contact block -> plate, so the plate moves into the
/// block's domain) with the floor clamped on its outer edges and the block falling at 5 m/s.
model::Model falling_block() {
  auto m = crashlink::testing::block_on_floor();
  for (std::size_t i = 0; i < m.nodes.count(); ++i) {
    const double x = m.nodes.x0[3 * i], y = m.nodes.x0[3 * i + 1], z = m.nodes.x0[3 * i + 2];
    const bool edge =
        std::abs(z) < 1e-9 && (x < 1e-9 || x > 1.0 - 1e-9 || y < 1e-9 || y > 0.5 - 1e-9);
    if (edge) m.fixed[i] = 63;
  }
  std::vector<std::int32_t> block;
  for (std::size_t i = 0; i < m.nodes.count(); ++i)
    if (m.nodes.x0[3 * i + 2] > 1e-3) block.push_back(static_cast<std::int32_t>(i));
  m.initial_velocities.push_back({block, {0.0, 0.0, -5.0}});
  m.probes.push_back({"block", model::Probe::Kind::Node, block.back()});
  m.controls.end_time_s = 2e-3;
  m.controls.history_interval_s = 1e-5;
  m.controls.field_interval_s = 5e-4;
  m.controls.bulk_viscosity = true;
  return m;
}

/// Runs `m` split in one process, writing the domain files into every directory of `dirs`;
/// `stop[i][k]`: sampling of solver k into dirs[i] stops after this time.
void run_split(const model::Model& m, const std::vector<std::string>& dirs,
               const std::vector<std::vector<double>>& stop) {
  cosim::SplitRunner split(m);
  std::vector<std::vector<std::unique_ptr<DaemonFile>>> files(dirs.size());
  for (std::size_t i = 0; i < dirs.size(); ++i)
    for (std::size_t k = 0; k < split.solver_count(); ++k)
      files[i].push_back(std::make_unique<DaemonFile>(
          dirs[i], split.decomposition().domains[static_cast<std::size_t>(split.solver_domain(k))],
          split.solver(k), stop[i][k]));
  split.initialize();
  for (;;) {
    split.begin_cycle();
    for (auto& set : files)
      for (auto& f : set) f->sample();
    if (split.finished()) break;
    split.end_cycle();
  }
  for (auto& set : files)
    for (auto& f : set) f->finish();
}

/// max |a - b| / max |b| over two equally long arrays (0 if b is all zero and a equals it).
double rel_diff(const std::vector<double>& a, const std::vector<double>& b) {
  EXPECT_EQ(a.size(), b.size());
  double scale = 0.0, worst = 0.0;
  for (std::size_t i = 0; i < a.size() && i < b.size(); ++i) {
    scale = std::max(scale, std::abs(b[i]));
    worst = std::max(worst, std::abs(a[i] - b[i]));
  }
  return scale > 0.0 ? worst / scale : worst;
}

std::vector<double> head(std::vector<double> v, std::size_t n) {
  v.resize(std::min(v.size(), n));
  return v;
}

std::string read_text(const std::string& path) {
  std::ifstream in(path);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

const char* const kGlstat[] = {"kinetic_energy", "internal_energy", "hourglass_energy",
                               "contact_energy", "external_work",   "total_energy"};

/// The split run of plastic_bar(), gathered, and its mono run; once for the whole suite.
class GatherBar : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    try {
      set_up();
    } catch (const std::exception& e) {  // reported by every test (not a silent skip)
      setup_error_ = e.what();
    }
  }
  void SetUp() override { ASSERT_TRUE(setup_error_.empty()) << "suite set-up: " << setup_error_; }
  static void set_up() {
    model_ = new model::Model(plastic_bar());
    dec_ = new partition::Decomposition(partition::decompose(*model_, partition::Scheme::Layer));
    mono_ = fresh("bar_mono");
    full_ = fresh("bar_split");
    cut_ = fresh("bar_split_cut");
    run::RunOptions o;
    o.out_dir = mono_;
    o.progress = false;
    run::run_single_domain(*model_, o);
    // cut_: the fine daemon stops sampling after 0.43 ms (solver order: decomposition order).
    std::vector<double> cut_stop;
    for (const auto& d : dec_->domains)
      if (!d.empty())
        cut_stop.push_back(d.name == "fine" ? 4.3e-4 : std::numeric_limits<double>::infinity());
    run_split(
        *model_, {full_, cut_},
        {std::vector<double>(cut_stop.size(), std::numeric_limits<double>::infinity()), cut_stop});
    // The coordinator's file for full_: one interface, timing with waits.
    {
      io::CouplingHistoryWriter w(full_ + "/coordinator.h5");
      const auto i = w.add_interface("fine|coarse", "link", "fine", "coarse", "layer", 4);
      for (int k = 0; k < 10; ++k) w.append(i, {1e-4 * k, 0.0, 0.0, 0.5 * k, 0.0, {1.0, 2.0, 3.0}});
      w.write_timing(3.25, 0.125, {{"fine", 0.5}, {"coarse", 0.25}});
    }
  }
  static void TearDownTestSuite() {
    delete model_;
    delete dec_;
  }
  static model::Model* model_;
  static partition::Decomposition* dec_;
  static std::string mono_, full_, cut_, setup_error_;
};
model::Model* GatherBar::model_ = nullptr;
partition::Decomposition* GatherBar::dec_ = nullptr;
std::string GatherBar::mono_, GatherBar::full_, GatherBar::cut_, GatherBar::setup_error_;

TEST_F(GatherBar, SplitRunGatheredAgreesWithMono) {
  // The decomposition really splits the coarse part (its first layer is in the fine domain).
  int holders = 0;
  for (const auto& d : dec_->domains)
    for (int gp : d.part_global) holders += gp == 0 ? 1 : 0;
  ASSERT_EQ(holders, 2) << "part 'coarse' should be split across both domains";

  const gather::GatherReport rep = gather::gather_results(*model_, *dec_, full_);
  EXPECT_EQ(rep.domains_read, (std::vector<std::string>{"coarse", "fine"}));
  EXPECT_TRUE(rep.missing.empty());
  for (const auto& n : rep.notes) std::printf("note: %s\n", n.c_str());

  const H5Reader g(full_ + "/result.h5");
  const H5Reader m(mono_ + "/result.h5");
  // Mesh: identical.
  EXPECT_EQ(g.doubles("/mesh/coordinates"), m.doubles("/mesh/coordinates"));
  EXPECT_EQ(g.int64s("/mesh/node_ids"), m.int64s("/mesh/node_ids"));
  EXPECT_EQ(g.strings("/mesh/part_names"), m.strings("/mesh/part_names"));
  for (const auto& p : model_->parts) {
    const std::string base = "/mesh/parts/" + p.name;
    EXPECT_EQ(g.int32s(base + "/connectivity"), m.int32s(base + "/connectivity"));
    EXPECT_EQ(g.int64s(base + "/element_ids"), m.int64s(base + "/element_ids"));
    EXPECT_EQ(g.attr_string(base, "kind"), m.attr_string(base, "kind"));
  }
  EXPECT_EQ(g.attr_string("/", "model"), m.attr_string("/", "model"));

  // glstat: same sample times, every energy to 1e-9 of the largest energy.
  const auto tg = g.doubles("/history/glstat/time");
  const auto tm = m.doubles("/history/glstat/time");
  ASSERT_EQ(tg.size(), tm.size());
  EXPECT_EQ(rep.history_samples, static_cast<std::int64_t>(tg.size()));
  EXPECT_LE(rel_diff(tg, tm), 1e-12);
  double energy_scale = 0.0;
  for (const char* c : kGlstat)
    for (double x : m.doubles(std::string("/history/glstat/") + c))
      energy_scale = std::max(energy_scale, std::abs(x));
  double glstat_worst = 0.0;
  for (const char* c : kGlstat) {
    const auto a = g.doubles(std::string("/history/glstat/") + c);
    const auto b = m.doubles(std::string("/history/glstat/") + c);
    ASSERT_EQ(a.size(), b.size()) << c;
    double worst = 0.0;
    for (std::size_t i = 0; i < a.size(); ++i) worst = std::max(worst, std::abs(a[i] - b[i]));
    std::printf(
        "[measured] gather vs mono glstat %-16s max |d| = %.3e J (%.3e of max energy "
        "%.4e J)\n",
        c, worst, worst / energy_scale, energy_scale);
    glstat_worst = std::max(glstat_worst, worst / energy_scale);
    EXPECT_LE(worst, 1e-9 * energy_scale) << c;
  }
  const auto err_g = g.doubles("/history/glstat/energy_balance_error");
  const auto err_m = m.doubles("/history/glstat/energy_balance_error");
  ASSERT_EQ(err_g.size(), err_m.size());
  double err_diff = 0.0;
  for (std::size_t i = 0; i < err_g.size(); ++i)
    err_diff = std::max(err_diff, std::abs(err_g[i] - err_m[i]));
  std::printf(
      "[measured] energy_balance_error (recomputed from the summed energies over the "
      "samples): max |d| = %.3e\n",
      err_diff);
  EXPECT_LE(err_diff, 1e-6);

  // Probes: "tip" from fine, "j" (J node) from its owner coarse, not from fine's ghost.
  double probe_worst = 0.0;
  for (const auto& p : model_->probes) {
    const std::string base = "/history/probes/" + p.name;
    EXPECT_EQ(g.doubles(base + "/time"), tg) << p.name;
    for (const char* q : {"displacement", "velocity", "acceleration"}) {
      const double d = rel_diff(g.doubles(base + "/" + q), m.doubles(base + "/" + q));
      probe_worst = std::max(probe_worst, d);
      EXPECT_LE(d, 1e-9) << p.name << " " << q;
    }
    EXPECT_EQ(g.attr_string(base, "kind"), "node");
    EXPECT_EQ(g.attr_int64(base, "node_id"), m.attr_int64(base, "node_id"));
  }
  std::printf("[measured] gather vs mono probes: max |d|/max|mono| = %.3e\n", probe_worst);

  // States: same count and times; nodal and element fields to 1e-9, complete, global order.
  const auto count = g.attr_int64("/states", "count");
  ASSERT_EQ(count, m.attr_int64("/states", "count"));
  EXPECT_EQ(rep.states, count);
  ASSERT_GE(count, 5);
  double node_worst = 0.0, elem_worst = 0.0, eps_max = 0.0;
  for (std::int64_t k = 0; k < count; ++k) {
    const std::string s = "/states/" + std::to_string(k);
    EXPECT_NEAR(g.attr_double(s, "time"), m.attr_double(s, "time"), 1e-15);
    for (const char* q : {"displacement", "coordinates", "velocity"}) {
      const double d = rel_diff(g.doubles(s + "/" + q), m.doubles(s + "/" + q));
      node_worst = std::max(node_worst, d);
      EXPECT_LE(d, 1e-9) << s << " " << q;
    }
    for (const auto& p : model_->parts) {
      for (const char* q : {"eps_p", "von_mises", "stress"}) {
        const std::string path = s + "/parts/" + p.name + "/" + q;
        const auto a = g.doubles(path);
        const auto b = m.doubles(path);
        ASSERT_EQ(a.size(), b.size()) << path;
        for (double x : a) ASSERT_TRUE(std::isfinite(x)) << path << ": incomplete";
        const double d = rel_diff(a, b);
        elem_worst = std::max(elem_worst, d);
        EXPECT_LE(d, 1e-9) << path;
        if (std::string(q) == "eps_p")
          for (double x : b) eps_max = std::max(eps_max, x);
      }
    }
  }
  EXPECT_GT(eps_max, 0.0) << "the bar should yield";
  std::printf(
      "[measured] gather vs mono states (%lld): nodes max |d|/max|mono| = %.3e, element "
      "fields %.3e (max eps_p %.3e)\n",
      static_cast<long long>(count), node_worst, elem_worst, eps_max);

  // Timing from the domain files and the coordinator, /coupling copied.
  EXPECT_EQ(g.attr_double("/timing", "wall_seconds"), 3.25);
  EXPECT_EQ(g.attr_double("/timing", "coordinator_cpu_seconds"), 0.125);
  for (const auto& d : dec_->domains) {
    const std::string t = "/timing/" + d.name;
    EXPECT_EQ(g.attr_double(t, "cpu_seconds"), 0.5);
    EXPECT_GT(g.attr_int64(t, "cycles"), 0);
    EXPECT_GT(g.attr_double(t, "dt_min"), 0.0);
    EXPECT_EQ(g.attr_int64(t, "elements"), static_cast<std::int64_t>(d.model.element_count()));
  }
  EXPECT_EQ(g.attr_double("/timing/fine", "wait_seconds"), 0.5);
  EXPECT_EQ(g.attr_double("/timing/coarse", "wait_seconds"), 0.25);
  EXPECT_EQ(g.doubles("/coupling/fine|coarse/link_work").size(), 10u);
  EXPECT_EQ(g.attr_string("/coupling/fine|coarse/force", "units"), "N");
  EXPECT_EQ(g.attr_string("/coupling/fine|coarse", "scheme"), "layer");

  // The file reads back through the result reader (crashlink hic's path).
  const io::ResultReader r(full_ + "/result.h5");
  EXPECT_EQ(r.glstat().size(), tg.size());
  EXPECT_EQ(r.probe("tip").size(), tg.size());
}

TEST_F(GatherBar, XdmfOfTheGatheredFileListsTheStates) {
  const gather::GatherReport rep = gather::gather_results(*model_, *dec_, full_);
  const std::string x = read_text(full_ + "/result.xdmf");
  const H5Reader g(full_ + "/result.h5");
  ASSERT_GT(rep.states, 0);
  std::size_t collections = 0;
  for (std::size_t at = x.find("<Grid Name=\"state_"); at != std::string::npos;
       at = x.find("<Grid Name=\"state_", at + 1))
    ++collections;
  EXPECT_EQ(collections, static_cast<std::size_t>(rep.states));
  for (std::int64_t k = 0; k < rep.states; ++k) {
    const std::string s = std::to_string(k);
    const std::size_t at = x.find("<Grid Name=\"state_" + s + "\"");
    ASSERT_NE(at, std::string::npos) << "state " << k;
    // The collection's time is the state's time attribute.
    const std::size_t tv = x.find("<Time Value=\"", at);
    ASSERT_NE(tv, std::string::npos);
    const double t = std::stod(x.substr(tv + 13, 40));
    EXPECT_NEAR(t, g.attr_double("/states/" + s, "time"), 1e-15) << "state " << k;
    for (const auto& p : model_->parts)
      EXPECT_NE(x.find("result.h5:/states/" + s + "/parts/" + p.name + "/eps_p"), std::string::npos)
          << "state " << k << " part " << p.name;
    EXPECT_NE(x.find("result.h5:/states/" + s + "/coordinates"), std::string::npos) << k;
  }
  EXPECT_EQ(x.find("result.h5:/states/" + std::to_string(rep.states) + "/"), std::string::npos);
}

TEST_F(GatherBar, TruncatedDomainFileGathersUpToItsEnd) {
  const gather::GatherReport rep = gather::gather_results(*model_, *dec_, cut_);
  EXPECT_EQ(rep.domains_read, (std::vector<std::string>{"coarse", "fine"}));
  EXPECT_TRUE(rep.missing.empty());
  EXPECT_LE(rep.end_time_s, 4.3e-4);
  EXPECT_GT(rep.end_time_s, 4.3e-4 - 2.5e-5);
  bool told = false, no_timing = false;
  for (const auto& n : rep.notes) {
    std::printf("note: %s\n", n.c_str());
    told = told ||
           (n.find("'fine'") != std::string::npos && n.find("stopped early") != std::string::npos);
    no_timing = no_timing || n.find("no /timing") != std::string::npos;
  }
  EXPECT_TRUE(told) << "the report should say the fine domain's history ends early";
  EXPECT_TRUE(no_timing);

  // Readable, and what is there is the mono run's beginning.
  const io::ResultReader r(cut_ + "/result.h5");
  const auto gl = r.glstat();
  ASSERT_EQ(static_cast<std::int64_t>(gl.size()), rep.history_samples);
  EXPECT_EQ(gl.back().time_s, rep.end_time_s);
  const H5Reader g(cut_ + "/result.h5");
  const H5Reader m(mono_ + "/result.h5");
  const std::size_t k = gl.size();
  ASSERT_LT(k, m.doubles("/history/glstat/time").size());
  for (const char* c : kGlstat) {
    const std::string path = std::string("/history/glstat/") + c;
    EXPECT_LE(rel_diff(g.doubles(path), head(m.doubles(path), k)), 1e-9) << c;
  }
  for (const auto& p : model_->probes) {
    const std::string path = "/history/probes/" + p.name + "/displacement";
    const auto a = g.doubles(path);
    EXPECT_EQ(a.size(), 3 * k) << p.name;  // cut at the same end
    EXPECT_LE(rel_diff(a, head(m.doubles(path), a.size())), 1e-9) << p.name;
  }
  const auto states = g.attr_int64("/states", "count");
  EXPECT_EQ(states, rep.states);
  ASSERT_GE(states, 1);
  EXPECT_LE(g.attr_double("/states/" + std::to_string(states - 1), "time"), 4.3e-4);
  EXPECT_LE(rel_diff(g.doubles("/states/1/displacement"), m.doubles("/states/1/displacement")),
            1e-9);
  // Timing: only the domain that finished; no coordinator file: zeros.
  EXPECT_TRUE(g.exists("/timing/coarse"));
  EXPECT_FALSE(g.exists("/timing/fine"));
  EXPECT_EQ(g.attr_double("/timing", "wall_seconds"), 0.0);
  EXPECT_FALSE(g.exists("/coupling"));
  EXPECT_NE(g.attr_string("/", "gather_notes").find("stopped early"), std::string::npos);
  EXPECT_NE(read_text(cut_ + "/result.xdmf").find("/states/" + std::to_string(states - 1) + "/"),
            std::string::npos);
}

TEST_F(GatherBar, MissingDomainFileIsReportedAndTheRestWritten) {
  const std::string dir = fresh("bar_missing");
  fs::create_directories(dir + "/domains");
  fs::copy_file(full_ + "/domains/coarse.h5", dir + "/domains/coarse.h5");
  const gather::GatherReport rep = gather::gather_results(*model_, *dec_, dir);
  EXPECT_EQ(rep.domains_read, (std::vector<std::string>{"coarse"}));
  EXPECT_EQ(rep.missing, (std::vector<std::string>{"fine"}));
  ASSERT_FALSE(rep.notes.empty());
  EXPECT_NE(rep.notes.front().find("domains/fine.h5"), std::string::npos) << rep.notes.front();
  const H5Reader g(dir + "/result.h5");
  const H5Reader c(full_ + "/domains/coarse.h5");
  // glstat = the coarse domain's alone; its probe "j" complete, fine's "tip" empty.
  EXPECT_EQ(g.doubles("/history/glstat/kinetic_energy"),
            c.doubles("/history/glstat/kinetic_energy"));
  EXPECT_EQ(g.doubles("/history/probes/j/velocity"), c.doubles("/history/probes/j/velocity"));
  EXPECT_TRUE(g.doubles("/history/probes/tip/time").empty());
  // States: fine-owned nodes at rest (u = 0, v NaN), the fine part's results NaN.
  const auto v = g.doubles("/states/1/velocity");
  const auto u = g.doubles("/states/1/displacement");
  std::size_t nan_nodes = 0;
  for (std::size_t i = 0; i < v.size(); i += 3)
    if (std::isnan(v[i])) {
      ++nan_nodes;
      EXPECT_EQ(u[i], 0.0);
    }
  EXPECT_GT(nan_nodes, 0u);
  EXPECT_LT(nan_nodes, model_->nodes.count());
  // The part wholly in the missing domain has no results; the split part's moved layer is NaN.
  EXPECT_FALSE(g.exists("/states/1/parts/fine/eps_p"));
  const auto eps = g.doubles("/states/1/parts/coarse/eps_p");
  const auto& fine =
      dec_->domains[static_cast<std::size_t>(crashlink::testing::domain_index(*dec_, "fine"))];
  std::vector<char> moved(eps.size(), 0);
  for (std::size_t p = 0; p < fine.part_global.size(); ++p)
    if (fine.part_global[p] == 0)
      for (auto e : fine.part_elements[p]) moved[static_cast<std::size_t>(e)] = 1;
  ASSERT_EQ(eps.size(), model_->parts[0].element_count());
  for (std::size_t e = 0; e < eps.size(); ++e) EXPECT_EQ(std::isnan(eps[e]), moved[e] == 1) << e;
  // Nothing at all to gather: a typed error naming the directory.
  const std::string empty = fresh("bar_nothing");
  try {
    gather::gather_results(*model_, *dec_, empty);
    FAIL() << "no exception";
  } catch (const io::ResultFileError& e) {
    EXPECT_NE(std::string(e.what()).find("domains"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("coarse.h5"), std::string::npos) << e.what();
  }
}

// A daemon killed outright (no close, no /timing): its file holds what was flushed; the gather
// reads it like any shorter file.
TEST_F(GatherBar, KilledDaemonsUnclosedFileIsGathered) {
  const std::string dir = fresh("bar_killed");
  fs::create_directories(dir + "/domains");
  fs::copy_file(full_ + "/domains/coarse.h5", dir + "/domains/coarse.h5");
  const auto& fine =
      dec_->domains[static_cast<std::size_t>(crashlink::testing::domain_index(*dec_, "fine"))];
  constexpr std::size_t kRows = 20, kStates = 2;
  EXPECT_EXIT(
      {
        // Replays the first rows of the complete run's fine file, then dies without closing.
        const io::ResultReader src(full_ + "/domains/fine.h5");
        io::ResultWriterOptions o;
        o.file_stem = "fine";
        io::ResultWriter w(dir + "/domains", fine.model, o);
        const auto g = src.glstat();
        std::vector<io::ProbeHistory> probes;
        for (const auto& p : fine.model.probes) probes.push_back(src.probe(p.name));
        for (std::size_t k = 0; k < kRows; ++k) {
          std::vector<io::ProbeSample> rows(probes.size());
          for (std::size_t j = 0; j < probes.size(); ++j)
            for (std::size_t c = 0; c < 3; ++c) {
              rows[j].displacement_m[c] = probes[j].displacement_m[3 * k + c];
              rows[j].velocity_m_s[c] = probes[j].velocity_m_s[3 * k + c];
              rows[j].acceleration_m_s2[c] = probes[j].acceleration_m_s2[3 * k + c];
            }
          w.append_history(g[k], rows, {});
        }
        w.flush();
        for (std::size_t k = 0; k < kStates; ++k) {
          const io::StateData sd = src.state(k);
          io::FieldState f;
          f.time_s = sd.time_s;
          f.displacement_m = sd.displacement_m;
          f.velocity_m_s = sd.velocity_m_s;
          for (const auto& p : fine.model.parts)
            for (const auto& ps : sd.parts)
              if (ps.link == p.name) f.parts.push_back({ps.eps_p, ps.von_mises_Pa, ps.stress_Pa});
          w.write_field_state(f);
        }
        std::_Exit(0);
      },
      ::testing::ExitedWithCode(0), "");
  const gather::GatherReport rep = gather::gather_results(*model_, *dec_, dir);
  EXPECT_TRUE(rep.missing.empty());
  EXPECT_EQ(rep.history_samples, static_cast<std::int64_t>(kRows));
  EXPECT_EQ(rep.states, static_cast<std::int64_t>(kStates));
  bool told = false;
  for (const auto& n : rep.notes) told = told || n.find("stopped early") != std::string::npos;
  EXPECT_TRUE(told);
  const H5Reader g(dir + "/result.h5");
  const H5Reader m(mono_ + "/result.h5");
  EXPECT_LE(rel_diff(g.doubles("/history/glstat/total_energy"),
                     head(m.doubles("/history/glstat/total_energy"), kRows)),
            1e-9);
  EXPECT_LE(rel_diff(g.doubles("/states/1/velocity"), m.doubles("/states/1/velocity")), 1e-9);
}

// A contact inside one domain: /history/contacts from the domain holding it, contact energy in
// the summed glstat, agreeing with mono like the rest.
TEST(GatherResults, ContactHistoryComesFromTheDomainHoldingIt) {
  const auto m = falling_block();
  const auto dec = partition::decompose(m, partition::Scheme::Layer);
  const std::string mono = fresh("block_mono"), split = fresh("block_split");
  run::RunOptions o;
  o.out_dir = mono;
  o.progress = false;
  run::run_single_domain(m, o);
  std::size_t solvers = 0;
  for (const auto& d : dec.domains) solvers += d.empty() ? 0 : 1;
  run_split(m, {split}, {std::vector<double>(solvers, std::numeric_limits<double>::infinity())});
  const gather::GatherReport rep = gather::gather_results(m, dec, split);
  EXPECT_TRUE(rep.missing.empty());
  const H5Reader g(split + "/result.h5");
  const H5Reader r(mono + "/result.h5");
  const std::string c = "/history/contacts/block_on_plate";
  const auto f = g.doubles(c + "/force");
  double f_max = 0.0;
  for (double x : f) f_max = std::max(f_max, std::abs(x));
  EXPECT_GT(f_max, 0.0) << "the block should hit the plate";
  EXPECT_EQ(g.doubles(c + "/time"), g.doubles("/history/glstat/time"));
  const double df = rel_diff(f, r.doubles(c + "/force"));
  double e_max = 0.0, e_contact = 0.0, de = 0.0;
  for (const char* col : kGlstat) {
    const auto a = g.doubles(std::string("/history/glstat/") + col);
    const auto b = r.doubles(std::string("/history/glstat/") + col);
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t i = 0; i < a.size(); ++i) {
      e_max = std::max(e_max, std::abs(b[i]));
      de = std::max(de, std::abs(a[i] - b[i]));
      if (std::string(col) == "contact_energy") e_contact = std::max(e_contact, std::abs(b[i]));
    }
  }
  const auto count = g.attr_int64("/states", "count");
  ASSERT_EQ(count, r.attr_int64("/states", "count"));
  double du = 0.0;
  for (std::int64_t k = 0; k < count; ++k) {
    const std::string s = "/states/" + std::to_string(k) + "/displacement";
    du = std::max(du, rel_diff(g.doubles(s), r.doubles(s)));
  }
  const double dp = rel_diff(g.doubles("/history/probes/block/velocity"),
                             r.doubles("/history/probes/block/velocity"));
  std::printf(
      "[measured] falling block, gather vs mono: contact force %.3e (max %.3e N), glstat "
      "%.3e of max energy %.3e J (contact energy up to %.3e J), probe velocity %.3e, "
      "states (%lld) %.3e\n",
      df, f_max, de / e_max, e_max, e_contact, dp, static_cast<long long>(count), du);
  EXPECT_LE(df, 1e-9);
  EXPECT_LE(de, 1e-9 * e_max);
  EXPECT_LE(dp, 1e-9);
  EXPECT_LE(du, 1e-9);

  // The run's cost figures (/timing, the scale benchmark's): every contact evaluation, at
  // initialize() and after each cycle, tests the interface's slave nodes once.
  const std::vector<double> unit_mass(m.nodes.count(), 1.0);
  const contact::ContactInterface c0(m, m.contacts[0], unit_mass.data());
  const std::int64_t cycles = r.attr_int64("/timing/model", "cycles");
  EXPECT_GT(c0.slave_node_count(), 0u);
  EXPECT_EQ(r.attr_int64("/timing/model", "contact_node_cycles"),
            (cycles + 1) * static_cast<std::int64_t>(c0.slave_node_count()));
  const double cpu = r.attr_double("/timing/model", "cpu_seconds");
  const double contact_s = r.attr_double("/timing/model", "contact_seconds");
  const double setup_s = r.attr_double("/timing/model", "setup_cpu_seconds");
  EXPECT_GT(contact_s, 0.0);
  EXPECT_LT(contact_s, r.attr_double("/timing", "wall_seconds"));
  EXPECT_GT(setup_s, 0.0);
  EXPECT_LT(setup_s, cpu);
  EXPECT_GT(r.attr_int64("/timing/model", "peak_rss_bytes"), std::int64_t{1} << 20);  // > 1 MiB
  // The kernels' cost, sampled on one cycle in 16: each sampled cycle computes every element of
  // a kind once (18 hexes, 32 shells); the CPU is the run's.
  std::int64_t hexes = 0, shells = 0;
  for (const auto& p : m.parts)
    (p.kind == model::ElementKind::Hex8 ? hexes : shells) +=
        static_cast<std::int64_t>(p.element_count());
  ASSERT_EQ(hexes, 18);
  ASSERT_EQ(shells, 32);
  const std::int64_t sampled = r.attr_int64("/timing/model", "kernel_sampled_cycles");
  EXPECT_EQ(sampled, cycles / integration::Solver::kKernelSampleCycles);
  const std::pair<std::string, std::int64_t> kinds[] = {{"hex", hexes}, {"shell", shells}};
  for (const auto& [kind, of_kind] : kinds) {
    const double sec = r.attr_double("/timing/model", kind + "_kernel_seconds");
    EXPECT_EQ(r.attr_int64("/timing/model", kind + "_element_cycles"), sampled * of_kind) << kind;
    EXPECT_GT(sec, 0.0) << kind;
    EXPECT_LT(sec, cpu - setup_s) << kind;
  }

  // /history/contacts/<name>/energy (issue 21): the interface's own energy. With one contact it
  // is glstat's contact_energy, in mono and gathered (from the domain that computes the contact,
  // at that domain's sample times), and the two runs agree.
  const auto e_mono = r.doubles(c + "/energy");
  const auto e_gather = g.doubles(c + "/energy");
  const auto total_mono = r.doubles("/history/glstat/contact_energy");
  const auto total_gather = g.doubles("/history/glstat/contact_energy");
  ASSERT_EQ(e_mono.size(), r.doubles(c + "/time").size());
  ASSERT_EQ(e_gather.size(), g.doubles(c + "/time").size());
  ASSERT_EQ(e_mono.size(), total_mono.size());
  ASSERT_EQ(e_gather.size(), total_gather.size());
  double de_mono = 0.0, de_gather = 0.0, de_runs = 0.0, e_abs = 0.0;
  for (std::size_t i = 0; i < e_mono.size(); ++i) {
    e_abs = std::max(e_abs, std::abs(total_mono[i]));
    de_mono = std::max(de_mono, std::abs(e_mono[i] - total_mono[i]));
    de_gather = std::max(de_gather, std::abs(e_gather[i] - total_gather[i]));
    de_runs = std::max(de_runs, std::abs(e_gather[i] - e_mono[i]));
  }
  std::printf(
      "[measured] block_on_plate energy vs glstat contact_energy (max %.3e J): mono %.3e J, "
      "gathered %.3e J; gathered vs mono %.3e J; at the end %.6e J\n",
      e_abs, de_mono, de_gather, de_runs, e_mono.back());
  EXPECT_GT(e_abs, 1e-6 * e_max) << "the contact should hold energy";
  EXPECT_LE(de_mono, 1e-9 * e_max);
  EXPECT_LE(de_gather, 1e-9 * e_max);
  EXPECT_LE(de_runs, 1e-9 * e_max);
}

// Domains sampled at different instants (each on its own step grid): glstat summed on the times
// of the domain with fewer samples, the other interpolated linearly (exact for series linear in
// t); probes keep their own domain's times; states matched by nearest time.
TEST(GatherResults, DomainsOnDifferentGridsAreInterpolatedOntoTheCoarserOne) {
  const auto m = plastic_bar();
  const auto dec = partition::decompose(m, partition::Scheme::Layer);
  const std::string dir = fresh("grids");
  // coarse: 6 samples at 0, 0.2, ..., 1.0 ms; fine: 11 at 0, 0.1, ... shifted by +3 us except
  // t = 0, ending at 1.003 ms. Energies linear in t.
  auto kinetic = [](double t, double a) { return a * (1.0 + 1e3 * t); };
  for (const auto& d : dec.domains) {
    const bool fine = d.name == "fine";
    io::ResultWriterOptions o;
    o.file_stem = d.name;
    io::ResultWriter w(dir + "/domains", d.model, o);
    const int n = fine ? 11 : 6;
    for (int i = 0; i < n; ++i) {
      const double t = fine ? (i == 0 ? 0.0 : 1e-4 * i + 3e-6) : 2e-4 * i;
      io::GlstatSample g{t, kinetic(t, fine ? 2.0 : 1.0), 0.5, 0.0, 0.0, 1e3 * t, 0.0, 0.0};
      g.total_energy_J = g.kinetic_energy_J + g.internal_energy_J;
      std::vector<io::ProbeSample> probes(d.model.probes.size());
      for (auto& p : probes) p.displacement_m[0] = t;
      w.append_history(g, probes, {});
      if (i % (fine ? 4 : 2) == 0) {
        io::FieldState s;
        s.time_s = t;
        const std::vector<double> u(3 * d.model.nodes.count(), fine ? 2.0 : 1.0);
        s.displacement_m = u;
        w.write_field_state(s);
      }
    }
  }
  const gather::GatherReport rep = gather::gather_results(m, dec, dir);
  for (const auto& n : rep.notes) std::printf("note: %s\n", n.c_str());
  const H5Reader g(dir + "/result.h5");
  const auto t = g.doubles("/history/glstat/time");
  ASSERT_EQ(t.size(), 6u);  // coarse grid, every time <= 1.0 ms (fine ends at 1.003 ms)
  const auto ek = g.doubles("/history/glstat/kinetic_energy");
  const auto ew = g.doubles("/history/glstat/external_work");
  for (std::size_t i = 0; i < t.size(); ++i) {
    EXPECT_EQ(t[i], 2e-4 * static_cast<double>(i));
    EXPECT_NEAR(ek[i], kinetic(t[i], 1.0) + kinetic(t[i], 2.0), 1e-12) << i;
    EXPECT_NEAR(ew[i], 2e3 * t[i], 1e-12) << i;
  }
  // Probe "tip" (fine) keeps the fine times up to the gathered end (1.0 ms): 10 rows.
  const auto tip = g.doubles("/history/probes/tip/time");
  ASSERT_EQ(tip.size(), 10u);
  EXPECT_EQ(tip[1], 1e-4 + 3e-6);
  EXPECT_EQ(g.doubles("/history/probes/j/time").size(), 6u);
  // States: fine has 3 (0, 0.403, 0.803 ms), coarse 3 (0, 0.4, 0.8 ms): coarse's times (the
  // first with the fewest), nodes from their owners.
  ASSERT_EQ(g.attr_int64("/states", "count"), 3);
  EXPECT_EQ(g.attr_double("/states/1", "time"), 4e-4);
  const auto u = g.doubles("/states/2/displacement");
  const auto& fine =
      dec.domains[static_cast<std::size_t>(crashlink::testing::domain_index(dec, "fine"))];
  for (std::size_t l = 0; l < fine.global_node.size(); ++l) {
    const auto gi = static_cast<std::size_t>(fine.global_node[l]);
    EXPECT_EQ(u[3 * gi], fine.ghost[l] ? 1.0 : 2.0) << "node " << m.nodes.id[gi];
  }
  bool matched = false;
  for (const auto& n : rep.notes) matched = matched || n.find("nearest time") != std::string::npos;
  EXPECT_TRUE(matched);
}

}  // namespace
