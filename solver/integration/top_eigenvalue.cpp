#include "solver/integration/top_eigenvalue.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

#include "core/errors.h"
#include "solver/model/unit_noise.h"

namespace crashlink::integration {

namespace {

/// The pseudo-random vector's share in a warm start (norm relative to the Ritz vector's).
constexpr double kWarmNoise = 0.05;

/// a . b over [m] in eight partial sums (lane j of the two 4-wide accumulators takes the
/// indices i = j mod 8), added pairwise at the end: a fixed order, so the same bits for the
/// same inputs. One chain of m dependent additions (the plain loop, which GCC keeps in order)
/// was latency-bound: a third of the global step's time on the head impact (2 of 6 s).
double dot(const double* a, const double* b, std::size_t m) {
  double s0[4] = {0.0, 0.0, 0.0, 0.0}, s1[4] = {0.0, 0.0, 0.0, 0.0};
  std::size_t i = 0;
  for (; i + 8 <= m; i += 8)
    for (std::size_t j = 0; j < 4; ++j) {
      s0[j] += a[i + j] * b[i + j];
      s1[j] += a[i + 4 + j] * b[i + 4 + j];
    }
  double tail = 0.0;
  for (; i < m; ++i) tail += a[i] * b[i];
  return (((s0[0] + s1[0]) + (s0[1] + s1[1])) + ((s0[2] + s1[2]) + (s0[3] + s1[3]))) + tail;
}

/// Eigenvalues of the symmetric tridiagonal T (diagonal a[0..k), off-diagonal b[1..k-1]) below
/// x: the sign changes of its Sturm sequence (Golub & Van Loan §8.4.1, the LDL^T form).
int count_below(const double* a, const double* b, int k, double x) {
  int count = 0;
  double d = 1.0;
  for (int i = 0; i < k; ++i) {
    const double off = i > 0 ? b[i] * b[i] : 0.0;
    d = a[i] - x - (i > 0 ? off / d : 0.0);
    if (d == 0.0) d = -1e-300;  // x on an eigenvalue of a leading block: count it below
    if (d < 0.0) ++count;
  }
  return count;
}

using Square = std::array<double, TopEigenvalue::kMaxSteps * TopEigenvalue::kMaxSteps>;

/// Solves A x = r in place (x <- r), A k x k row-major, Gaussian elimination with partial
/// pivoting; a zero pivot is replaced by a tiny one (inverse iteration wants the near-singular
/// system).
void solve(Square& A, double* r, int k) {
  const auto at = [&](int i, int j) -> double& { return A[static_cast<std::size_t>(i * k + j)]; };
  for (int c = 0; c < k; ++c) {
    int p = c;
    for (int i = c + 1; i < k; ++i)
      if (std::abs(at(i, c)) > std::abs(at(p, c))) p = i;
    if (p != c) {
      for (int j = 0; j < k; ++j) std::swap(at(c, j), at(p, j));
      std::swap(r[c], r[p]);
    }
    if (at(c, c) == 0.0) at(c, c) = 1e-300;
    for (int i = c + 1; i < k; ++i) {
      const double f = at(i, c) / at(c, c);
      if (f == 0.0) continue;
      for (int j = c; j < k; ++j) at(i, j) -= f * at(c, j);
      r[i] -= f * r[c];
    }
  }
  for (int i = k - 1; i >= 0; --i) {
    double s = r[i];
    for (int j = i + 1; j < k; ++j) s -= at(i, j) * r[j];
    r[i] = s / at(i, i);
  }
}

}  // namespace

void TopEigenvalue::reset(std::size_t m, int max_steps) {
  CRASHLINK_ASSERT(max_steps >= 1 && max_steps <= kMaxSteps);
  m_ = m;
  max_steps_ = max_steps;
  basis_.assign(static_cast<std::size_t>(max_steps + 1) * m, 0.0);
  start_.resize(m);
  forget();
}

void TopEigenvalue::forget() {
  for (std::size_t i = 0; i < m_; ++i) start_[i] = model::unit_noise(i + 7919);
}

void TopEigenvalue::begin() {
  double norm = std::sqrt(dot(start_.data(), start_.data(), m_));
  if (!(norm > 0.0) || !std::isfinite(norm)) {
    for (std::size_t i = 0; i < m_; ++i) start_[i] = model::unit_noise(i + 7919);
    norm = std::sqrt(dot(start_.data(), start_.data(), m_));
  }
  // A warm start keeps a little of the fixed pseudo-random vector: a mode that has become the
  // highest since the last run, far from where the last Ritz vector lives, still has a share
  // for the Krylov space to amplify (a cold start is that vector alone).
  double noise = 0.0;
  for (std::size_t i = 0; i < m_; ++i) {
    const double r = model::unit_noise(i + 7919);
    noise += r * r;
  }
  const double a = 1.0 / norm, b = noise > 0.0 ? kWarmNoise / std::sqrt(noise) : 0.0;
  for (std::size_t i = 0; i < m_; ++i) basis_[i] = start_[i] * a + b * model::unit_noise(i + 7919);
  const double renorm = 1.0 / std::sqrt(dot(basis_.data(), basis_.data(), m_));
  for (std::size_t i = 0; i < m_; ++i) basis_[i] *= renorm;
  beta_[0] = 0.0;
}

/// Step j of the three-term recurrence w = A q_j - alpha_j q_j - beta_j q_{j-1}, alpha_j =
/// q_j . A q_j, then once more against q_j and q_{j-1} (local re-orthogonalisation: enough for
/// the extreme Ritz value over a few dozen steps); returns beta_{j+1} = |w|.
double TopEigenvalue::orthogonalise(int j, double* w) {
  const double* q = basis_.data() + static_cast<std::size_t>(j) * m_;
  const double* p = j > 0 ? q - m_ : nullptr;
  alpha_[j] = dot(q, w, m_);
  for (int pass = 0; pass < 2; ++pass) {
    const double a = pass == 0 ? alpha_[j] : dot(q, w, m_);
    const double b = p == nullptr ? 0.0 : (pass == 0 ? beta_[j] : dot(p, w, m_));
    if (pass == 1) alpha_[j] += a;
    for (std::size_t i = 0; i < m_; ++i) w[i] -= a * q[i] + (p == nullptr ? 0.0 : b * p[i]);
  }
  return std::sqrt(dot(w, w, m_));
}

TopEigenvalue::Estimate TopEigenvalue::finish(int k) {
  Estimate e;
  e.steps = k;
  if (k == 0) return e;
  // theta: bisection on the Sturm count inside the Gershgorin interval.
  double lo = alpha_[0], hi = alpha_[0];
  for (int i = 0; i < k; ++i) {
    const double r =
        (i > 0 ? std::abs(beta_[i]) : 0.0) + (i + 1 < k ? std::abs(beta_[i + 1]) : 0.0);
    lo = std::min(lo, alpha_[i] - r);
    hi = std::max(hi, alpha_[i] + r);
  }
  for (int it = 0; it < 200 && hi - lo > 1e-15 * std::max(std::abs(hi), std::abs(lo)); ++it) {
    const double mid = 0.5 * (lo + hi);
    if (count_below(alpha_, beta_, k, mid) == k)
      hi = mid;  // every eigenvalue below mid
    else
      lo = mid;
  }
  e.theta = hi;
  // Its eigenvector s by inverse iteration on T - theta I (three solves from a flat start).
  std::array<double, kMaxSteps> s{};
  for (int i = 0; i < k; ++i) s[static_cast<std::size_t>(i)] = 1.0;
  for (int it = 0; it < 3; ++it) {
    Square T{};
    for (int i = 0; i < k; ++i) {
      T[static_cast<std::size_t>(i * k + i)] = alpha_[i] - e.theta * (1.0 + 1e-14);
      if (i + 1 < k) {
        T[static_cast<std::size_t>(i * k + i + 1)] = beta_[i + 1];
        T[static_cast<std::size_t>((i + 1) * k + i)] = beta_[i + 1];
      }
    }
    solve(T, s.data(), k);
    double norm = 0.0;
    for (int i = 0; i < k; ++i)
      norm += s[static_cast<std::size_t>(i)] * s[static_cast<std::size_t>(i)];
    norm = std::sqrt(norm);
    if (!(norm > 0.0) || !std::isfinite(norm)) {
      s.fill(0.0);
      s[0] = 1.0;
      break;
    }
    for (int i = 0; i < k; ++i) s[static_cast<std::size_t>(i)] /= norm;
  }
  // |A y - theta y| = beta_k |s_{k-1}| for y = Q s (the Lanczos relation).
  e.residual = std::abs(beta_[k] * s[static_cast<std::size_t>(k - 1)]);
  // The next start: y = Q s.
  std::fill(start_.begin(), start_.end(), 0.0);
  for (int j = 0; j < k; ++j) {
    const double c = s[static_cast<std::size_t>(j)];
    const double* q = basis_.data() + static_cast<std::size_t>(j) * m_;
    for (std::size_t i = 0; i < m_; ++i) start_[i] += c * q[i];
  }
  return e;
}

}  // namespace crashlink::integration
