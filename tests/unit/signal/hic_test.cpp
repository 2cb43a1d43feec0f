// HIC (49 CFR 571.208 S6.2): closed forms for a rectangular pulse and a half-sine, window limits,
// non-uniform sampling, the O(n w) search against the direct O(n w^2) reference, and its cost.
#include "solver/signal/hic.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>
#include <vector>

#include "core/errors.h"

namespace crashlink::signal {
namespace {

struct Signal {
  std::vector<double> t, a;
};

/// a(t) sampled every `step_s` on [0, end_s].
template <class F>
Signal sample(F a_of_t, double end_s, double step_s) {
  Signal s;
  const auto n = static_cast<std::size_t>(std::llround(end_s / step_s)) + 1;
  for (std::size_t k = 0; k < n; ++k) {
    const double t = static_cast<double>(k) * step_s;
    s.t.push_back(t);
    s.a.push_back(a_of_t(t));
  }
  return s;
}

/// Half-sine of peak A [g] and duration T [s] starting at t0.
auto half_sine(double A, double T, double t0) {
  return [=](double t) {
    return (t >= t0 && t <= t0 + T) ? A * std::sin(std::numbers::pi * (t - t0) / T) : 0.0;
  };
}

/// Half-sine HIC for a centred window of fraction x of the pulse, divided by A^2.5 T:
/// x * (mean over the window / A)^2.5, mean/A = 2 sin(pi x / 2) / (pi x).
double half_sine_factor(double x) {
  return x * std::pow(2.0 * std::sin(std::numbers::pi * x / 2.0) / (std::numbers::pi * x), 2.5);
}

/// max over x in (0, 1] of half_sine_factor (golden section; the function is unimodal).
double half_sine_optimum(double* x_best) {
  double lo = 0.05, hi = 1.0;
  const double r = (std::sqrt(5.0) - 1.0) / 2.0;
  while (hi - lo > 1e-12) {
    const double m1 = hi - r * (hi - lo), m2 = lo + r * (hi - lo);
    if (half_sine_factor(m1) < half_sine_factor(m2))
      lo = m1;
    else
      hi = m2;
  }
  *x_best = 0.5 * (lo + hi);
  return half_sine_factor(*x_best);
}

TEST(Hic, RectangularPulse100gFor10msGives1000) {
  // 100 g from 5 to 15 ms: HIC = 0.010 s * 100^2.5 = 1000 (the window is the pulse: extending it
  // adds time faster than integral).
  for (double step : {1e-5, 1e-4}) {
    const Signal s =
        sample([](double t) { return (t >= 0.005 - 1e-12 && t <= 0.015 + 1e-12) ? 100.0 : 0.0; },
               0.03, step);
    for (double w : {kHic15Window_s, kHic36Window_s}) {
      const HicResult r = hic(s.t, s.a, w);
      EXPECT_NEAR(r.hic, 1000.0, 1.0) << "step " << step << " window " << w;  // 0.1 %
      EXPECT_NEAR(r.t1_s, 0.005, 1e-9);
      EXPECT_NEAR(r.t2_s, 0.015, 1e-9);
      std::printf("rectangular 100 g x 10 ms, step %g s, W %g s: HIC = %.6f\n", step, w, r.hic);
    }
  }
}

TEST(Hic, HalfSineClosedFormWhenTheOptimalWindowFits) {
  double x_best = 0.0;
  const double factor = half_sine_optimum(&x_best);  // 0.4146..., window 0.670 T
  EXPECT_NEAR(factor, 0.4147, 1e-4);
  std::printf("half-sine: HIC = %.6f A^2.5 T, optimal window %.5f T\n", factor, x_best);

  // T = 10 ms, A = 80 g: window 6.7 ms fits HIC15 and HIC36.
  {
    const double A = 80.0, T = 0.010;
    const Signal s = sample(half_sine(A, T, 0.002), 0.03, 2e-5);
    const double expected = factor * std::pow(A, 2.5) * T;
    for (double w : {kHic15Window_s, kHic36Window_s}) {
      const HicResult r = hic(s.t, s.a, w);
      EXPECT_NEAR(r.hic / expected, 1.0, 5e-3) << "W " << w;
      EXPECT_NEAR(r.t2_s - r.t1_s, x_best * T, 2e-4);
      EXPECT_NEAR(0.5 * (r.t1_s + r.t2_s), 0.002 + T / 2, 2e-5);  // centred
      std::printf("half-sine A 80 g T 10 ms, W %g: HIC %.4f, closed form %.4f (ratio %.6f)\n", w,
                  r.hic, expected, r.hic / expected);
    }
  }
  // T = 30 ms, A = 60 g: the optimal window 20.1 ms fits HIC36 only; HIC15 is the centred 15 ms
  // window (x = 0.5, where the factor still increases).
  {
    const double A = 60.0, T = 0.030;
    const Signal s = sample(half_sine(A, T, 0.005), 0.05, 2e-5);
    const double hic36 = factor * std::pow(A, 2.5) * T;
    const double hic15 = half_sine_factor(0.5) * std::pow(A, 2.5) * T;
    const HicResult r36 = hic(s.t, s.a, kHic36Window_s);
    const HicResult r15 = hic(s.t, s.a, kHic15Window_s);
    EXPECT_NEAR(r36.hic / hic36, 1.0, 5e-3);
    EXPECT_NEAR(r15.hic / hic15, 1.0, 5e-3);
    EXPECT_NEAR(r15.t2_s - r15.t1_s, 0.015, 1e-9);
    EXPECT_NEAR(r15.t1_s, 0.005 + 0.0075, 2e-5);
    std::printf(
        "half-sine A 60 g T 30 ms: HIC36 %.4f (closed form %.4f), HIC15 %.4f (centred "
        "15 ms: %.4f)\n",
        r36.hic, hic36, r15.hic, hic15);
  }
}

TEST(Hic, WindowLongerThanThePulseAndTheRecord) {
  // The record (12 ms) is shorter than both windows: HIC is the pulse's 1000.
  const Signal s =
      sample([](double t) { return (t >= 0.001 - 1e-12 && t <= 0.011 + 1e-12) ? 100.0 : 0.0; },
             0.012, 1e-5);
  EXPECT_NEAR(hic(s.t, s.a, kHic36Window_s).hic, 1000.0, 1.0);
  EXPECT_NEAR(hic(s.t, s.a, kHic15Window_s).hic, 1000.0, 1.0);
  // A constant 50 g for 40 ms: HIC grows with the window, so the window limit decides.
  const Signal c = sample([](double) { return 50.0; }, 0.04, 1e-4);
  const double a25 = std::pow(50.0, 2.5);
  const HicResult r15 = hic(c.t, c.a, kHic15Window_s);
  const HicResult r36 = hic(c.t, c.a, kHic36Window_s);
  EXPECT_NEAR(r15.hic, 0.015 * a25, 1e-9 * a25);
  EXPECT_NEAR(r36.hic, 0.036 * a25, 1e-9 * a25);
  EXPECT_NEAR(r36.t2_s - r36.t1_s, 0.036, 1e-12);
}

TEST(Hic, NonUniformSampling) {
  // Half-sine A 100 g, T 8 ms sampled with steps between 6 and 14 us (random, fixed seed).
  std::mt19937_64 rng(42);
  std::uniform_real_distribution<double> step(6e-6, 14e-6);
  const auto a = half_sine(100.0, 0.008, 0.001);
  Signal s;
  for (double t = 0.0; t < 0.012; t += step(rng)) {
    s.t.push_back(t);
    s.a.push_back(a(t));
  }
  double x_best = 0.0;
  const double expected = half_sine_optimum(&x_best) * std::pow(100.0, 2.5) * 0.008;
  const HicResult r = hic(s.t, s.a, kHic15Window_s);
  EXPECT_NEAR(r.hic / expected, 1.0, 5e-3);
  std::printf("non-uniform half-sine (%zu samples): HIC %.4f, closed form %.4f\n", s.t.size(),
              r.hic, expected);
}

TEST(Hic, MatchesTheDirectReference) {
  // Random signs and steps: the cumulative-sum search finds the same window as direct summation.
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> step(2e-4, 8e-4), value(-50.0, 150.0);
  Signal s;
  double t = 0.0;
  for (int k = 0; k < 400; ++k, t += step(rng)) {
    s.t.push_back(t);
    s.a.push_back(value(rng));
  }
  for (double w : {kHic15Window_s, kHic36Window_s}) {
    const HicResult fast = hic(s.t, s.a, w);
    const HicResult ref = hic_reference(s.t, s.a, w);
    EXPECT_NEAR(fast.hic, ref.hic, 1e-9 * ref.hic);
    EXPECT_EQ(fast.t1_s, ref.t1_s);
    EXPECT_EQ(fast.t2_s, ref.t2_s);
    EXPECT_LE(fast.t2_s - fast.t1_s, w * (1 + 1e-9));
  }
}

TEST(Hic, SignedOneDimensionalSignal) {
  // Used as given: a pulse of -100 g has no positive mean anywhere, HIC = 0; flipped it is 1000.
  const auto pulse = [](double t) {
    return (t >= 0.005 - 1e-12 && t <= 0.015 + 1e-12) ? 100.0 : 0.0;
  };
  const Signal neg = sample([&](double t) { return -pulse(t); }, 0.03, 1e-4);
  const HicResult r = hic(neg.t, neg.a, kHic15Window_s);
  EXPECT_EQ(r.hic, 0.0);
  EXPECT_EQ(r.t1_s, r.t2_s);
  const Signal pos = sample(pulse, 0.03, 1e-4);
  EXPECT_NEAR(hic(pos.t, pos.a, kHic15Window_s).hic, 1000.0, 1.0);
}

TEST(Hic, BadInput) {
  const std::vector<double> t{0.0, 1e-3, 1e-3}, a{1.0, 2.0, 3.0};
  EXPECT_THROW(hic(t, a, kHic15Window_s), InputError);  // t not increasing
  EXPECT_THROW(hic(std::vector<double>{0.0}, std::vector<double>{1.0}, 0.015), InputError);
  EXPECT_THROW(hic(std::vector<double>{0.0, 1.0}, std::vector<double>{1.0}, 0.015), InputError);
  EXPECT_THROW(hic(std::vector<double>{0.0, 1.0}, std::vector<double>{1.0, 1.0}, 0.0), InputError);
  try {
    hic(t, a, kHic15Window_s);
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("not increasing at sample 2"), std::string::npos)
        << e.what();
  }
}

TEST(Hic, CostOf1e5Samples) {
  // 1e5 samples at 100 kHz (1 s) of a noisy signal: O(n w), w = 1500 (HIC15) and 3600 (HIC36).
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> noise(0.0, 20.0);
  const Signal s = sample(
      [&](double t) { return noise(rng) + 80.0 * std::exp(-std::pow((t - 0.5) / 0.004, 2)); },
      1.0 - 1e-5, 1e-5);
  ASSERT_EQ(s.t.size(), 100000u);
  for (double w : {kHic15Window_s, kHic36Window_s}) {
    const auto start = std::chrono::steady_clock::now();
    const HicResult r = hic(s.t, s.a, w);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::printf("HIC of 1e5 samples at 100 kHz, W %g ms: %.3f s (HIC %.2f)\n", 1e3 * w, seconds,
                r.hic);
    RecordProperty(w < 0.02 ? "hic15_1e5_seconds" : "hic36_1e5_seconds", std::to_string(seconds));
    EXPECT_LT(seconds, 20.0);  // generous: a debug build or a loaded machine must not fail
    EXPECT_GT(r.hic, 0.0);
  }
}

}  // namespace
}  // namespace crashlink::signal
