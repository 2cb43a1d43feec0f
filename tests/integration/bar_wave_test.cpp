// 1-D wave in a bar of hexahedra against d'Alembert's solution (issue 2 acceptance):
// a force step F on the end of a bar with nu = 0 (uniaxial stress = uniaxial strain) launches a
// front at c = sqrt(E/rho) behind which the particle velocity is v = sigma / (rho c).
// Tolerance 2 % (the acceptance bound): the discrete front is spread over a few elements and the
// half-amplitude arrival time of a dispersive central-difference front lags by well under 1 %.
#include <gtest/gtest.h>

#include <cstdio>

#include "tests/integration/run_helpers.h"
#include "tests/integration/test_models.h"

using namespace crashlink;
using namespace crashlink::testing;

namespace {

struct BarSetup {
  model::Model m;
  double sigma_Pa, c, v_expected, x_probe;
};

BarSetup make_bar(bool bulk_viscosity) {
  const double length = 1.0, a = 0.005, sigma = 10e6;
  BarSetup b{bar(200, length, a, steel(0.0)), sigma, 0.0, 0.0, 0.5};
  b.c = std::sqrt(210e9 / 7850.0);
  b.v_expected = sigma / (7850.0 * b.c);
  auto end_nodes = nodes_where(b.m, [](const Vec3& x) { return x[0] < 1e-9; });
  b.m.loads.push_back({"push", end_nodes, 0, model::Curve::constant(sigma * a * a / 4.0)});
  const auto mid = nodes_where(b.m, [&](const Vec3& x) {
    return std::abs(x[0] - b.x_probe) < 1e-9 && x[1] < 1e-9 && x[2] < 1e-9;
  });
  add_probe(b.m, "mid", mid.at(0));
  b.m.controls.end_time_s = 1.3 * length / b.c;  // before the reflection returns to the middle
  b.m.controls.bulk_viscosity = bulk_viscosity;
  return b;
}

}  // namespace

TEST(BarWave, ArrivalTimeAndAmplitudeMatchDAlembert) {
  for (bool q : {true, false}) {
    auto b = make_bar(q);
    integration::Solver s(b.m);
    const auto h = run_and_sample(s, 0);
    const double t_arrival = b.x_probe / b.c;
    double t_half = -1.0;
    for (std::size_t i = 1; i < h.size(); ++i)
      if (h[i].probe.velocity_m_s[0] >= 0.5 * b.v_expected) {
        const double f0 = h[i - 1].probe.velocity_m_s[0] - 0.5 * b.v_expected;
        const double f1 = h[i].probe.velocity_m_s[0] - 0.5 * b.v_expected;
        t_half = h[i - 1].t + (h[i].t - h[i - 1].t) * (-f0) / (f1 - f0);
        break;
      }
    ASSERT_GT(t_half, 0.0) << "the front never reached the probe";
    EXPECT_NEAR(t_half / t_arrival, 1.0, 0.02) << "bulk viscosity " << q;
    // Plateau: mean velocity from 0.2 L/c after arrival to the end (no reflection yet).
    double sum = 0.0;
    int count = 0;
    for (const auto& smp : h)
      if (smp.t > t_arrival + 0.2 / b.c) {
        sum += smp.probe.velocity_m_s[0];
        ++count;
      }
    ASSERT_GT(count, 10);
    EXPECT_NEAR(sum / count / b.v_expected, 1.0, 0.02) << "bulk viscosity " << q;
    std::printf(
        "[measured] bar wave (bulk viscosity %d): arrival %.4f, amplitude %.4f of d'Alembert\n",
        q ? 1 : 0, t_half / t_arrival, sum / count / b.v_expected);
    // The work of the load equals kinetic + internal energy (the balance the guard watches):
    // bound 1 % of the input work.
    const auto& last = h.back();
    EXPECT_NEAR(last.kinetic_J + last.internal_J + last.hourglass_J, last.external_J,
                0.01 * last.external_J);
  }
}
