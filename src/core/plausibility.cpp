#include "vibrissa/core/plausibility.hpp"

#include <algorithm>

#include "vibrissa/core/checks.hpp"

namespace vibrissa {

std::vector<std::string> plausibility_warnings(const Whisker& w) {
  std::vector<std::string> out;
  const double L = w.length();
  if (L < plausible::min_length_m || L > plausible::max_length_m)
    out.push_back("whisker length " + format_value(L) + " m lies outside the plausible " +
                  format_value(plausible::min_length_m * 1e3) + "-" + format_value(plausible::max_length_m * 1e3) +
                  " mm (a length in mm or um given as metres?)");
  const double r0 = w.node_radii().front();
  if (r0 > plausible::max_base_radius_m)
    out.push_back("whisker base radius " + format_value(r0) + " m is above the plausible " +
                  format_value(plausible::max_base_radius_m * 1e3) + " mm (a radius in um given as metres?)");
  const auto [lo, hi] = std::minmax_element(w.node_youngs_moduli().begin(), w.node_youngs_moduli().end());
  if (*lo < plausible::min_youngs_modulus_Pa || *hi > plausible::max_youngs_modulus_Pa)
    out.push_back("Young's modulus " + format_value(*lo < plausible::min_youngs_modulus_Pa ? *lo : *hi) +
                  " Pa lies outside the plausible " + format_value(plausible::min_youngs_modulus_Pa / 1e9) + "-" +
                  format_value(plausible::max_youngs_modulus_Pa / 1e9) + " GPa (a modulus in GPa given as Pa?)");
  return out;
}

}  // namespace vibrissa
