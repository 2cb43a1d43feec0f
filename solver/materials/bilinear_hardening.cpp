#include "solver/materials/bilinear_hardening.h"

namespace crashlink::materials {

HardeningCurve bilinear_hardening(double sigma_y0_Pa, double E_Pa, double Et_Pa) {
  const double H = E_Pa * Et_Pa / (E_Pa - Et_Pa);
  if (H > 0.0) return {{0.0, 1.0}, {sigma_y0_Pa, sigma_y0_Pa + H}};
  return {{0.0}, {sigma_y0_Pa}};
}

}  // namespace crashlink::materials
