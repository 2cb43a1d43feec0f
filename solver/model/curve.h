#pragma once
// A piecewise-linear function of time (load curves, prescribed velocities). Constant beyond ends.
#include <vector>

namespace crashlink::model {

struct Curve {
  std::vector<double> t_s;    ///< abscissae, strictly increasing [s]
  std::vector<double> value;  ///< ordinates (unit given by the user of the curve)

  /// Value at time t; a curve with one point (or none: 0) is a constant.
  double at(double t) const;
  static Curve constant(double v) { return Curve{{0.0}, {v}}; }
};

}  // namespace crashlink::model
