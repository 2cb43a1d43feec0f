// Element ranges (StepInfo::first_element / end_element, kernel_io.h): a part computed as [0, s)
// then [s, ne) gives the forces, moments and histories of one call over [0, ne) to the bit (the
// same elements in the same order, so the same additions into f at shared nodes), the same
// smallest step and critical element, and energies that differ only by the order of two partial
// sums (1e-14 relative). A solver relies on it to compute the elements that touch no ghost node
// while it waits for the ghosts' motion (Solver::end_cycle_interior_forces).
// Meshes: a strip of 19 hexes and one of 19 shells (two full batches of 8 and a tail of 3),
// randomly distorted, random velocities, J2 plasticity, several steps; splits at 8 and 16.
#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <random>
#include <vector>

#include "solver/elements/hex8.h"
#include "solver/elements/shell_bt.h"

namespace {

namespace el = crashlink::elements;
namespace model = crashlink::model;
using crashlink::materials::Material;
using crashlink::materials::MaterialKind;

constexpr int kElements = 19;

const Material kSteel{"j2", MaterialKind::J2Plastic, 7850.0, 210e9, 0.3, {{0.0, 0.1}, {2e8, 3e8}}};

/// A strip of n elements along x: hexes (nodes at y, z in {0, 1}) or shells (y in {0, 1}, z 0),
/// every node moved by up to 0.15 at random. x0 and the element count out.
model::Part strip(model::ElementKind kind, std::vector<double>& x0, std::mt19937& gen) {
  std::uniform_real_distribution<double> u(-0.15, 0.15);
  const bool hex = kind == model::ElementKind::Hex8;
  const int per_section = hex ? 4 : 2;
  model::Part part;
  part.name = hex ? "hexes" : "shells";
  part.kind = kind;
  part.thickness_m = 0.01;
  part.through_thickness_points = 5;
  for (int k = 0; k <= kElements; ++k)
    for (int c = 0; c < per_section; ++c) {
      const int y = (c == 1 || c == 2) ? 1 : 0, z = c >= 2 ? 1 : 0;
      x0.insert(x0.end(), {k + u(gen), y + u(gen), z + u(gen)});
    }
  auto node = [&](int k, int c) { return per_section * k + c; };
  for (int e = 0; e < kElements; ++e) {
    if (hex)
      for (int z = 0; z < 2; ++z)  // bottom then top: (e,0), (e+1,0), (e+1,1), (e,1)
        part.connectivity.insert(part.connectivity.end(),
                                 {node(e, z ? 3 : 0), node(e + 1, z ? 3 : 0),
                                  node(e + 1, z ? 2 : 1), node(e, z ? 2 : 1)});
    else
      part.connectivity.insert(part.connectivity.end(),
                               {node(e, 0), node(e + 1, 0), node(e + 1, 1), node(e, 1)});
    part.element_id.push_back(e + 1);
  }
  return part;
}

template <class State>
el::KernelResult call(const model::Part& part, State& st, const el::NodalView& nv,
                      const el::StepInfo& step) {
  if constexpr (std::is_same_v<State, el::Hex8State>)
    return el::hex8_internal_forces(part, kSteel, st, nv, step);
  else
    return el::shell_internal_forces(part, kSteel, st, nv, step);
}

std::vector<std::vector<double>*> history(el::Hex8State& s) {
  return {&s.stress, &s.eps_p, &s.hourglass_force, &s.volume0, &s.bulk_q_Pa};
}
std::vector<std::vector<double>*> history(el::ShellState& s) {
  return {&s.sigma_Pa,    &s.eps_p,     &s.resultant_Pa, &s.shear_Pa,
          &s.thickness_m, &s.bulk_q_Pa, &s.hourglass};
}

void expect_same_bits(const std::vector<double>& a, const std::vector<double>& b, const char* what,
                      std::size_t split) {
  ASSERT_EQ(a.size(), b.size()) << what;
  for (std::size_t i = 0; i < a.size(); ++i)
    ASSERT_EQ(std::bit_cast<std::uint64_t>(a[i]), std::bit_cast<std::uint64_t>(b[i]))
        << what << " [" << i << "]: " << a[i] << " vs " << b[i] << " (split at " << split << ")";
}

/// Five steps of the whole part and of the part in two ranges, side by side.
template <class State, class Make>
void check_ranges(model::ElementKind kind, Make make_state) {
  for (const std::size_t split : {std::size_t{8}, std::size_t{16}}) {
    std::mt19937 gen(11);
    std::vector<double> x0;
    const model::Part part = strip(kind, x0, gen);
    const std::size_t n3 = x0.size();
    std::uniform_real_distribution<double> uv(-40.0, 40.0), uw(-400.0, 400.0);
    std::vector<double> v(n3), w(n3);
    for (double& vi : v) vi = uv(gen);
    for (double& wi : w) wi = uw(gen);
    State whole = make_state(part), parts = make_state(part);
    std::vector<double> x = x0;
    for (int s = 0; s < 5; ++s) {
      el::StepInfo step;
      step.dt_s = s == 0 ? 0.0 : 2e-5;  // the initial call first, as a solver does
      std::vector<double> fw(n3, 0.0), mw(n3, 0.0), fp(n3, 0.0), mp(n3, 0.0);
      const auto rw = call(part, whole, {x.data(), v.data(), w.data(), fw.data(), mw.data()}, step);
      el::KernelResult r0, r1;
      if (s == 0) {
        r0 = call(part, parts, {x.data(), v.data(), w.data(), fp.data(), mp.data()}, step);
      } else {
        el::StepInfo first = step, rest = step;
        first.end_element = split;
        rest.first_element = split;
        r0 = call(part, parts, {x.data(), v.data(), w.data(), fp.data(), mp.data()}, first);
        r1 = call(part, parts, {x.data(), v.data(), w.data(), fp.data(), mp.data()}, rest);
      }
      expect_same_bits(fw, fp, "force", split);
      expect_same_bits(mw, mp, "moment", split);
      const auto hw = history(whole), hp = history(parts);
      for (std::size_t k = 0; k < hw.size(); ++k)
        expect_same_bits(*hw[k], *hp[k], "history", split);
      const bool r0_smaller = r0.dt_stable_s <= r1.dt_stable_s;
      EXPECT_EQ(rw.dt_stable_s, r0_smaller ? r0.dt_stable_s : r1.dt_stable_s);
      EXPECT_EQ(rw.critical_element, r0_smaller ? r0.critical_element : r1.critical_element);
      const double e_int = r0.internal_energy_increment_J + r1.internal_energy_increment_J;
      EXPECT_NEAR(e_int, rw.internal_energy_increment_J,
                  1e-14 * std::abs(rw.internal_energy_increment_J) + 1e-300);
      const double e_hg = r0.hourglass_energy_increment_J + r1.hourglass_energy_increment_J;
      EXPECT_NEAR(e_hg, rw.hourglass_energy_increment_J,
                  1e-14 * std::abs(rw.hourglass_energy_increment_J) + 1e-300);
      if (s > 0) {
        EXPECT_GT(std::abs(rw.internal_energy_increment_J), 0.0);
      }
      for (std::size_t i = 0; i < n3; ++i) x[i] += 2e-5 * v[i];
    }
    // plastic flow happened, so the J2 return ran in both ranges
    double ep = 0.0;
    for (double e : whole.eps_p) ep = std::max(ep, e);
    EXPECT_GT(ep, 0.0);
  }
}

}  // namespace

TEST(ElementRange, HexPartInTwoRangesEqualsOneCall) {
  check_ranges<el::Hex8State>(model::ElementKind::Hex8,
                              [](const model::Part& p) { return el::make_hex8_state(p); });
}

TEST(ElementRange, ShellPartInTwoRangesEqualsOneCall) {
  check_ranges<el::ShellState>(model::ElementKind::Shell4,
                               [](const model::Part& p) { return el::make_shell_state(p); });
}
