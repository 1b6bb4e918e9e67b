#include "vibrissa/array/error_bound.hpp"

#include <cmath>
#include <numbers>

namespace vibrissa::array {

double cone_length(double arc_length, double taper_ratio) {
  // eq. (5): L = R_base / (R_base − R_tip) · S, with R_tip = R_base / taper.
  return arc_length * taper_ratio / (taper_ratio - 1.0);
}

double contact_error_bound(double direction, double mu, double normal_force, double s, double arc_length,
                           double base_radius, double taper_ratio, double youngs_modulus) {
  const double sign = direction > 0.0 ? 1.0 : (direction < 0.0 ? -1.0 : 0.0);
  const double L = cone_length(arc_length, taper_ratio);
  const double r4 = base_radius * base_radius * base_radius * base_radius;
  // eq. (7)
  return sign * 4.0 * L / (3.0 * youngs_modulus * std::numbers::pi * r4) * mu * std::abs(normal_force) * s * s * s /
         (L - s);
}

}  // namespace vibrissa::array
