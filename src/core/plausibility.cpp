#include "vibrissa/core/plausibility.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <numbers>

#include "vibrissa/core/checks.hpp"

namespace vibrissa {

namespace {

std::string sig(double v) { return format_significant(v, 4); }

/// A length as a person writes it: "40 m", "35 um", "12.5 mm".
std::string length_text(double m) {
  const double a = std::abs(m);
  if (a >= 1.0 || a == 0.0) return sig(m) + " m";
  if (a >= 1e-3) return sig(m * 1e3) + " mm";
  return sig(m * 1e6) + " um";
}

/// The suggestion for a length outside [lo, hi]: the factor 10^-3, 10^-6, 10^3 or 10^6 that brings it in.
std::string length_hint(double v, double lo, double hi) {
  struct Slip {
    double factor;
    const char* mistake;
  };
  static constexpr std::array<Slip, 4> slips = {{{1e-3, "a length in mm given as metres"},
                                                 {1e-6, "a length in um given as metres"},
                                                 {1e3, "metres given or declared as mm"},
                                                 {1e6, "metres given or declared as um"}}};
  for (const Slip& s : slips)
    if (v * s.factor >= lo && v * s.factor <= hi)
      return ": did you mean " + length_text(v * s.factor) + " (" + s.mistake + ")?";
  return "";
}

}  // namespace

std::string format_significant(double v, int digits) {
  std::array<char, 64> buf{};
  const auto [end, ec] = std::to_chars(buf.data(), buf.data() + buf.size(), v, std::chars_format::general, digits);
  return ec == std::errc() ? std::string(buf.data(), end) : format_value(v);
}

std::optional<std::string> length_warning(std::string_view quantity, double L) {
  if (!(L < plausible::min_length_m || L > plausible::max_length_m)) return std::nullopt;
  return std::string(quantity) + " " + format_value(L) + " m (" + length_text(L) +
         ") lies outside the plausible " + sig(plausible::min_length_m * 1e3) + "-" +
         sig(plausible::max_length_m * 1e3) + " mm of a rodent whisker" +
         length_hint(L, plausible::min_length_m, plausible::max_length_m);
}

std::vector<std::string> plausibility_warnings(const Whisker& w) {
  std::vector<std::string> out;
  if (auto m = length_warning("whisker length", w.length())) out.push_back(std::move(*m));
  const double r0 = w.node_radii().front();
  if (r0 > plausible::max_base_radius_m)
    out.push_back("whisker base radius " + format_value(r0) + " m is above the plausible " +
                  sig(plausible::max_base_radius_m * 1e3) + " mm: did you mean " + length_text(r0 * 1e-3) +
                  " or " + length_text(r0 * 1e-6) + " (a radius in mm or um given as metres)?");
  const auto [lo, hi] = std::minmax_element(w.node_youngs_moduli().begin(), w.node_youngs_moduli().end());
  if (*lo < plausible::min_youngs_modulus_Pa || *hi > plausible::max_youngs_modulus_Pa)
    out.push_back("Young's modulus " + format_value(*lo < plausible::min_youngs_modulus_Pa ? *lo : *hi) +
                  " Pa lies outside the plausible " + sig(plausible::min_youngs_modulus_Pa / 1e9) + "-" +
                  sig(plausible::max_youngs_modulus_Pa / 1e9) + " GPa (a modulus in GPa given as Pa?)");
  return out;
}

std::vector<std::string> pose_warnings(const Pose& p, std::string_view field) {
  std::vector<std::string> out;
  const std::array<std::pair<const char*, double>, 3> angles = {{{"theta", p.theta}, {"phi", p.phi}, {"zeta", p.zeta}}};
  for (const auto& [name, v] : angles)
    if (std::abs(v) > plausible::max_pose_angle_rad)
      out.push_back(std::string(field) + "." + name + " " + format_value(v) + " rad (" +
                    sig(v * 180.0 / std::numbers::pi) + " deg) is beyond +-pi: did you mean " + sig(v) +
                    " deg (pose angles are in radians)?");
  return out;
}

std::optional<std::string> force_warning(std::string_view field, double f) {
  if (!(std::abs(f) > plausible::max_force_N)) return std::nullopt;
  return std::string(field) + " " + format_value(f) + " N is above the plausible " + sig(plausible::max_force_N) +
         " N on a rodent whisker (uN to mN): did you mean " + sig(f * 1e3) + " mN (a force in mN given as N)?";
}

std::optional<std::string> angle_series_warning(std::string_view field, const std::vector<double>& values,
                                                bool declared_degrees) {
  double largest = 0.0;
  bool any = false;
  for (double v : values)
    if (std::isfinite(v)) {
      largest = std::max(largest, std::abs(v));
      any = true;
    }
  if (!any) return std::nullopt;
  const double deg = 180.0 / std::numbers::pi;
  if (largest > 2.0 * std::numbers::pi)
    return std::string(field) + " reaches " + sig(largest) + " rad (" + sig(largest * deg) +
           " deg), beyond a full turn" +
           (declared_degrees ? std::string(": not an angle in degrees?")
                             : std::string(": degrees declared as radians (angle=rad)?"));
  if (declared_degrees && largest > 0.0 && largest < plausible::min_degree_series_span_rad)
    return std::string(field) + " stays within +-" + sig(largest * deg) + " deg although the file declares " +
           "angle=deg: all its values lie within +-pi, as radians would: radians declared as degrees?";
  return std::nullopt;
}

std::optional<std::string> reach_warning(std::string_view field, const Eigen::Vector3d& point_W,
                                         const Eigen::Vector3d& direction_W, const Eigen::Vector3d& base_W,
                                         double L) {
  if (!(point_W.allFinite() && base_W.allFinite() && std::isfinite(L) && L > 0.0)) return std::nullopt;
  Eigen::Vector3d d = point_W - base_W;
  const double n = direction_W.norm();
  if (n > 0.0 && std::isfinite(n)) d -= d.dot(direction_W / n) * (direction_W / n);
  const double distance = d.norm();
  if (!(distance > plausible::max_reach_lengths * L)) return std::nullopt;
  std::string hint;  // a unit slip only if no set-up is that large (beyond 1 m); else just out of reach
  if (distance > 1.0 && distance * 1e-3 <= plausible::max_reach_lengths * L)
    hint = ": positions in mm given as metres?";
  else if (distance > 1.0 && distance * 1e-6 <= plausible::max_reach_lengths * L)
    hint = ": positions in um given as metres?";
  return std::string(field) + " passes " + length_text(distance) + " from the whisker base, beyond the reach of a " +
         length_text(L) + " whisker (" + sig(plausible::max_reach_lengths) + " lengths): it can never be touched" +
         hint;
}

}  // namespace vibrissa
