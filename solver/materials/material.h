#pragma once
// Material parameters (input data) and the derived moduli every kernel needs. SI units.
// Update kernels (stress return mappings) live beside this file, one per concept.
#include <cstdint>
#include <string>
#include <vector>

namespace crashlink::materials {

enum class MaterialKind : std::uint8_t {
  Elastic,    ///< isotropic linear elastic (hypoelastic rate form in the elements)
  J2Plastic,  ///< von Mises plasticity, isotropic piecewise-linear hardening
  Rigid,      ///< the part is a rigid body; elements carry geometry and mass only
};

/// Piecewise-linear yield curve sigma_y(eps_p): points (eps_p[i], sigma_y[i]), eps_p[0] = 0,
/// strictly increasing eps_p; extrapolated beyond the last point with the last slope.
struct HardeningCurve {
  std::vector<double> eps_p;       ///< effective plastic strain [-]
  std::vector<double> sigma_y_Pa;  ///< yield stress [Pa]

  /// Yield stress at effective plastic strain ep [Pa].
  double yield(double ep) const;
  /// Hardening modulus d sigma_y / d eps_p at ep [Pa] (right-hand slope at a kink).
  double slope(double ep) const;
};

struct Material {
  std::string name;
  MaterialKind kind = MaterialKind::Elastic;
  double density_kg_m3 = 0.0;
  double youngs_modulus_Pa = 0.0;
  double poisson_ratio = 0.0;
  HardeningCurve hardening;  ///< J2Plastic only
  /// Cowper-Symonds rate scaling of the yield stress (cowper_symonds.h), J2Plastic only:
  /// C [1/s] (0: none) and P [-].
  double rate_c_per_s = 0.0;
  double rate_p = 0.0;

  bool rate_dependent() const { return kind == MaterialKind::J2Plastic && rate_c_per_s > 0.0; }

  double shear_modulus_Pa() const { return youngs_modulus_Pa / (2.0 * (1.0 + poisson_ratio)); }
  double bulk_modulus_Pa() const { return youngs_modulus_Pa / (3.0 * (1.0 - 2.0 * poisson_ratio)); }
  double lame_lambda_Pa() const {
    return youngs_modulus_Pa * poisson_ratio /
           ((1.0 + poisson_ratio) * (1.0 - 2.0 * poisson_ratio));
  }
  /// Dilatational (P-wave) speed sqrt((lambda + 2 mu)/rho) [m/s]: the solid elements' Courant
  /// speed.
  double dilatational_wave_speed_m_s() const;
  /// Plate speed sqrt(E / (rho (1 - nu^2))) [m/s]: the shells' Courant speed.
  double plate_wave_speed_m_s() const;
};

/// Throws ModelError if the parameters are not physical (rho, E > 0, -1 < nu < 0.5,
/// a well-formed hardening curve for J2). `where` names the material in the message.
void validate(const Material& m);

}  // namespace crashlink::materials
