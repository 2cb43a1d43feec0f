#include "solver/integration/central_difference.h"

namespace crashlink::integration {

void update_velocity(double* __restrict v, const double* __restrict a, double dt_mid,
                     std::size_t len) {
  for (std::size_t i = 0; i < len; ++i) v[i] += dt_mid * a[i];
}

void update_displacement(double* __restrict u, const double* __restrict v, double dt,
                         std::size_t len) {
  for (std::size_t i = 0; i < len; ++i) u[i] += dt * v[i];
}

void compute_acceleration(double* __restrict a, const double* __restrict f_ext,
                          const double* __restrict f_int, const double* __restrict inv_mass,
                          std::size_t n_nodes) {
  for (std::size_t i = 0; i < n_nodes; ++i) {
    const double w = inv_mass[i];
    a[3 * i + 0] = (f_ext[3 * i + 0] - f_int[3 * i + 0]) * w;
    a[3 * i + 1] = (f_ext[3 * i + 1] - f_int[3 * i + 1]) * w;
    a[3 * i + 2] = (f_ext[3 * i + 2] - f_int[3 * i + 2]) * w;
  }
}

}  // namespace crashlink::integration
