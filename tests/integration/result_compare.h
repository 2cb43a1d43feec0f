#pragma once
// Two result files of the same scene compared to the bit (checkpoint_restart_test,
// mono_checkpoint_test): a resumed run against the uninterrupted one.
#include <gtest/gtest.h>

#include <cstddef>
#include <string>

#include "solver/io/result_reader.h"

namespace crashlink::testing {

/// Histories, probes, contacts and every field state to the bit; at least `min_states` field
/// states.
inline void expect_same_results(const std::string& ref_h5, const std::string& run_h5,
                                std::size_t min_states = 3) {
  const io::ResultReader a(ref_h5), b(run_h5);
  const auto ga = a.glstat(), gb = b.glstat();
  ASSERT_EQ(ga.size(), gb.size());
  for (std::size_t i = 0; i < ga.size(); ++i) {
    ASSERT_EQ(ga[i].time_s, gb[i].time_s) << "row " << i;
    ASSERT_EQ(ga[i].kinetic_energy_J, gb[i].kinetic_energy_J) << "row " << i;
    ASSERT_EQ(ga[i].internal_energy_J, gb[i].internal_energy_J) << "row " << i;
    ASSERT_EQ(ga[i].contact_energy_J, gb[i].contact_energy_J) << "row " << i;
    ASSERT_EQ(ga[i].coupling_work_J, gb[i].coupling_work_J) << "row " << i;
  }
  for (const auto& name : a.probe_names()) {
    const auto pa = a.probe(name), pb = b.probe(name);
    EXPECT_EQ(pa.time_s, pb.time_s) << name;
    EXPECT_EQ(pa.displacement_m, pb.displacement_m) << name;
    EXPECT_EQ(pa.velocity_m_s, pb.velocity_m_s) << name;
    EXPECT_EQ(pa.acceleration_m_s2, pb.acceleration_m_s2) << name;
  }
  for (const auto& name : a.contact_names()) {
    EXPECT_EQ(a.contact(name).force_N, b.contact(name).force_N) << name;
    EXPECT_EQ(a.contact(name).energy_J, b.contact(name).energy_J) << name;
  }
  ASSERT_EQ(a.state_count(), b.state_count());
  ASSERT_GE(a.state_count(), min_states);
  for (std::size_t k = 0; k < a.state_count(); ++k) {
    const auto sa = a.state(k), sb = b.state(k);
    EXPECT_EQ(sa.time_s, sb.time_s) << "state " << k;
    EXPECT_EQ(sa.displacement_m, sb.displacement_m) << "state " << k;
    EXPECT_EQ(sa.velocity_m_s, sb.velocity_m_s) << "state " << k;
    ASSERT_EQ(sa.parts.size(), sb.parts.size());
    for (std::size_t p = 0; p < sa.parts.size(); ++p) {
      EXPECT_EQ(sa.parts[p].eps_p, sb.parts[p].eps_p) << "state " << k << sa.parts[p].link;
      EXPECT_EQ(sa.parts[p].stress_Pa, sb.parts[p].stress_Pa) << "state " << k << sa.parts[p].link;
    }
  }
}

}  // namespace crashlink::testing
