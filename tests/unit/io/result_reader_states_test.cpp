// The reader's extensions for the gather of a coupled run (solver/gather): mesh ids, contact
// histories, field states and timing read back exactly; and the writer's extensions: file_stem
// (DIR/domains/<domain>.h5) and whole-column history appends with per-probe sample times.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "core/errors.h"
#include "solver/io/result_reader.h"
#include "solver/io/result_writer.h"
#include "tests/unit/io/result_h5_reader.h"

namespace crashlink::io {
namespace {

using test::fresh_dir;
using test::small_model;

model::Model model_with_contact() {
  auto m = small_model();
  model::Contact c;
  c.name = "plate/block";
  m.contacts.push_back(c);
  return m;
}

TEST(ResultReaderStates, FileStemMeshStatesContactsAndTimingRoundTrip) {
  const auto m = model_with_contact();
  const std::string dir = fresh_dir("out") + "/domains";
  ResultWriterOptions o;
  o.file_stem = "fine";
  const std::size_t n = m.nodes.count();
  std::vector<double> u(3 * n), v(3 * n);
  for (std::size_t i = 0; i < 3 * n; ++i) {
    u[i] = static_cast<double>(i) / 8.0;
    v[i] = -static_cast<double>(i) / 16.0;
  }
  const std::vector<double> eps = {0.25}, vm = {3e8}, stress = {1, 2, 3, 4, 5, 6};
  const std::vector<double> shell_vm = {1e6, 2e6};
  {
    ResultWriter w(dir, m, o);
    EXPECT_EQ(w.h5_path(), dir + "/fine.h5");
    EXPECT_EQ(w.xdmf_path(), dir + "/fine.xdmf");
    for (int i = 0; i < 3; ++i) {
      GlstatSample g;
      g.time_s = i / 1024.0;
      ContactSample c;
      c.force_N[0] = i;
      c.force_N[2] = -2.0 * i;
      w.append_history(g, std::vector<ProbeSample>(2), {c});
    }
    FieldState s;
    s.time_s = 0.5;
    s.displacement_m = u;
    s.velocity_m_s = v;
    s.parts = {{eps, vm, stress}, {{}, shell_vm, {}}};
    w.write_field_state(s);
    FieldState s2;  // no velocity, no element results
    s2.time_s = 0.75;
    s2.displacement_m = u;
    w.write_field_state(s2);
    w.write_timing(2.0, 0.0,
                   {{"fine", 1.5, 42, 1e-7, 3, 2, 0.25, 4200, 123456789, 0.125, 2, 0.5, 16, 0.75,
                     32, 0.0625}});
  }
  // The xdmf names its own h5 file.
  std::ifstream xdmf(dir + "/fine.xdmf");
  const std::string text((std::istreambuf_iterator<char>(xdmf)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("fine.h5:/states/1/coordinates"), std::string::npos);

  const ResultReader r(dir + "/fine.h5");
  EXPECT_EQ(r.node_ids(), m.nodes.id);
  const auto parts = r.mesh_parts();
  ASSERT_EQ(parts.size(), 2u);
  EXPECT_EQ(parts[0].name, "block");
  EXPECT_EQ(parts[0].kind, "hex8");
  EXPECT_EQ(parts[0].element_ids, (std::vector<std::int64_t>{11}));
  EXPECT_EQ(parts[1].name, "plate");
  EXPECT_EQ(parts[1].kind, "shell4");
  EXPECT_EQ(parts[1].element_ids, (std::vector<std::int64_t>{21, 22}));

  EXPECT_EQ(r.contact_names(), (std::vector<std::string>{"plate/block"}));
  const ContactHistory c = r.contact("plate/block");
  EXPECT_EQ(c.link, "plate_block");
  ASSERT_EQ(c.size(), 3u);
  EXPECT_EQ(c.time_s[2], 2.0 / 1024.0);
  EXPECT_EQ(c.force_N[6], 2.0);
  EXPECT_EQ(c.force_N[8], -4.0);
  EXPECT_EQ(r.contact("plate_block").name, "plate/block");  // by link name too
  EXPECT_THROW(r.contact("nope"), InputError);

  ASSERT_EQ(r.state_count(), 2u);
  EXPECT_EQ(r.state_time(1), 0.75);
  const StateData s = r.state(0);
  EXPECT_EQ(s.time_s, 0.5);
  EXPECT_EQ(s.displacement_m, u);
  EXPECT_EQ(s.velocity_m_s, v);
  ASSERT_EQ(s.parts.size(), 2u);
  EXPECT_EQ(s.parts[0].link, "block");
  EXPECT_EQ(s.parts[0].eps_p, eps);
  EXPECT_EQ(s.parts[0].von_mises_Pa, vm);
  EXPECT_EQ(s.parts[0].stress_Pa, stress);
  EXPECT_EQ(s.parts[1].link, "plate");
  EXPECT_TRUE(s.parts[1].eps_p.empty());
  EXPECT_EQ(s.parts[1].von_mises_Pa, shell_vm);
  const StateData s1 = r.state(1);
  EXPECT_TRUE(s1.velocity_m_s.empty());
  EXPECT_TRUE(s1.parts.empty());
  EXPECT_THROW(r.state(2), ResultFileError);

  const TimingData t = r.timing();
  EXPECT_TRUE(t.present);
  EXPECT_EQ(t.wall_seconds, 2.0);
  ASSERT_EQ(t.domains.size(), 1u);
  EXPECT_EQ(t.domains[0].name, "fine");
  EXPECT_EQ(t.domains[0].cpu_seconds, 1.5);
  EXPECT_EQ(t.domains[0].cycles, 42);
  EXPECT_EQ(t.domains[0].dt_min_s, 1e-7);
  EXPECT_EQ(t.domains[0].elements, 3);
  EXPECT_EQ(t.domains[0].threads, 2);
  EXPECT_EQ(t.domains[0].contact_seconds, 0.25);
  EXPECT_EQ(t.domains[0].contact_node_cycles, 4200);
  EXPECT_EQ(t.domains[0].peak_rss_bytes, 123456789);
  EXPECT_EQ(t.domains[0].setup_cpu_seconds, 0.125);
  EXPECT_EQ(t.domains[0].kernel_sampled_cycles, 2);
  EXPECT_EQ(t.domains[0].hex_kernel_seconds, 0.5);
  EXPECT_EQ(t.domains[0].hex_element_cycles, 16);
  EXPECT_EQ(t.domains[0].shell_kernel_seconds, 0.75);
  EXPECT_EQ(t.domains[0].shell_element_cycles, 32);
  EXPECT_EQ(t.domains[0].global_step_seconds, 0.0625);
}

TEST(ResultReaderStates, WholeColumnAppendsKeepEachProbesOwnTimes) {
  const auto m = model_with_contact();
  const std::string dir = fresh_dir("out");
  {
    ResultWriter w(dir, m);
    std::vector<GlstatSample> g(4);
    for (std::size_t i = 0; i < g.size(); ++i) {
      g[i].time_s = static_cast<double>(i);
      g[i].kinetic_energy_J = 10.0 + static_cast<double>(i);
    }
    w.append_glstat_rows(g);
    EXPECT_EQ(w.history_rows_written(), 4u);
    const std::vector<double> t_tip = {0.0, 0.5, 1.0, 1.5, 2.0}, t_head = {0.0, 3.0};
    std::vector<ProbeSample> tip(t_tip.size()), head(t_head.size());
    for (std::size_t i = 0; i < tip.size(); ++i) tip[i].velocity_m_s[1] = static_cast<double>(i);
    w.append_probe_rows(0, t_tip, tip);
    w.append_probe_rows(1, t_head, head);
    w.append_contact_rows(0, std::vector<double>{0.25}, std::vector<ContactSample>(1));
    EXPECT_THROW(w.append_probe_rows(2, t_head, head), ResultFileError);
    EXPECT_THROW(w.append_probe_rows(0, t_tip, head), ResultFileError);
    EXPECT_THROW(w.append_contact_rows(1, {}, {}), ResultFileError);
  }
  const ResultReader r(dir + "/result.h5");
  const auto g = r.glstat();
  ASSERT_EQ(g.size(), 4u);
  EXPECT_EQ(g[3].kinetic_energy_J, 13.0);
  const ProbeHistory tip = r.probe("tip");
  EXPECT_EQ(tip.time_s, (std::vector<double>{0.0, 0.5, 1.0, 1.5, 2.0}));
  EXPECT_EQ(tip.velocity_m_s[3 * 4 + 1], 4.0);
  EXPECT_EQ(r.probe("head").time_s, (std::vector<double>{0.0, 3.0}));
  EXPECT_EQ(r.contact("plate/block").time_s, (std::vector<double>{0.25}));
  EXPECT_EQ(r.state_count(), 0u);
  EXPECT_FALSE(r.timing().present);
}

}  // namespace
}  // namespace crashlink::io
