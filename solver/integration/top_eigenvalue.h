#pragma once
// The largest eigenvalue of a symmetric positive semi-definite operator A (m x m) given only as
// products A q, by the Lanczos process (Golub & Van Loan, Matrix Computations, 4th ed., §10.1):
// the global stable-step estimate's omega_max^2 of M^-1/2 K M^-1/2 (docs/elements.md "Global
// stable step"). Storage for the basis is made once (reset()); run() allocates nothing.
#include <cstddef>
#include <vector>

namespace crashlink::integration {

class TopEigenvalue {
 public:
  /// Largest Lanczos basis kept (steps of one run()).
  static constexpr int kMaxSteps = 32;

  /// The operator's size m and the most steps a run() takes (<= kMaxSteps). Forgets the last
  /// Ritz vector: the next run() starts from a fixed pseudo-random vector.
  void reset(std::size_t m, int max_steps);
  std::size_t size() const { return m_; }

  struct Estimate {
    double theta = 0.0;     ///< the largest Ritz value: <= lambda_max(A) in exact arithmetic
    double residual = 0.0;  ///< |A s - theta s| of its Ritz vector s (|s| = 1): some eigenvalue
                            ///< of A lies within this of theta
    int steps = 0;          ///< Lanczos steps taken (products A q)
  };

  /// `steps` Lanczos steps from the last run's Ritz vector (or the fixed start), apply(in, out):
  /// out = A in over [m] (in has norm 1). Keeps the new Ritz vector for the next run. Stops early
  /// when the Krylov space is invariant (beta below 1e-12 of the largest alpha): theta is then
  /// exact. Dot products in a fixed order (eight partial sums): the same bits for the same inputs.
  template <class Apply>
  Estimate run(int steps, Apply&& apply);

  /// The next run starts from the fixed pseudo-random vector alone (a cold start).
  void forget();

  /// The Ritz vector of the last run ([m], norm 1; the fixed start before any run).
  const std::vector<double>& vector() const { return start_; }
  /// Replaces it (a checkpoint's); size m.
  void set_vector(const std::vector<double>& v) { start_ = v; }

 private:
  /// theta, residual and the Ritz vector from the tridiagonal alpha_[0..k), beta_[1..k].
  Estimate finish(int k);
  void begin();
  double orthogonalise(int j, double* w);

  std::size_t m_ = 0;
  int max_steps_ = 0;
  std::vector<double> basis_;  ///< [(max_steps + 1) m]: q_0 .. q_k
  std::vector<double> start_;  ///< [m]
  double alpha_[kMaxSteps] = {};
  double beta_[kMaxSteps + 1] = {};
};

template <class Apply>
TopEigenvalue::Estimate TopEigenvalue::run(int steps, Apply&& apply) {
  if (m_ == 0) return {};
  if (steps > max_steps_) steps = max_steps_;
  begin();
  int k = 0;
  double scale = 0.0;
  for (; k < steps; ++k) {
    double* q = basis_.data() + static_cast<std::size_t>(k) * m_;
    double* w = q + m_;
    apply(static_cast<const double*>(q), w);
    const double beta = orthogonalise(k, w);
    scale = alpha_[k] > scale ? alpha_[k] : scale;
    beta_[k + 1] = beta;
    if (!(beta > 1e-12 * scale)) {  // an invariant subspace: T's eigenvalues are A's
      ++k;
      beta_[k] = 0.0;
      break;
    }
    const double inv = 1.0 / beta;
    for (std::size_t i = 0; i < m_; ++i) w[i] *= inv;
  }
  return finish(k);
}

}  // namespace crashlink::integration
