#pragma once
// The bilinear yield curve of a yield stress and a tangent modulus, as the scenario's
// `yield_stress` / `tangent_modulus` and the decks' SIGY / ETAN (*MAT_003, *MAT_024) give it.
#include "solver/materials/material.h"

namespace crashlink::materials {

/// sigma_y0 [Pa] and the tangent modulus E_t [Pa] (the slope of the uniaxial stress-strain curve
/// past yield, 0 <= E_t < E): plastic modulus H = E E_t / (E - E_t), the 1-D elastoplastic
/// tangent E_t = E H / (E + H) solved for H; a single point (perfect plasticity) if E_t = 0.
HardeningCurve bilinear_hardening(double sigma_y0_Pa, double E_Pa, double Et_Pa);

}  // namespace crashlink::materials
