#include "solver/model/curve.h"

namespace crashlink::model {

double Curve::at(double t) const {
  const std::size_t n = t_s.size();
  if (n == 0) return 0.0;
  if (n == 1 || t <= t_s[0]) return value[0];
  if (t >= t_s[n - 1]) return value[n - 1];
  std::size_t i = 1;
  while (t > t_s[i]) ++i;
  const double w = (t - t_s[i - 1]) / (t_s[i] - t_s[i - 1]);
  return (1.0 - w) * value[i - 1] + w * value[i];
}

}  // namespace crashlink::model
