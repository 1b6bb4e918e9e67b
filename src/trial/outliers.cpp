#include "vibrissa/trial/outliers.hpp"

#include <cmath>
#include <limits>

#include "vibrissa/core/checks.hpp"
#include "vibrissa/trial/statistics.hpp"

namespace vibrissa::trial {

std::vector<DroppedFrame> impossible_frames(const Trial& t) {
  const std::size_t n = t.frames();
  // The median base over the frames whose base is finite (a robust centre: one outlier cannot move it).
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (int a = 0; a < 3; ++a) {
    std::vector<double> v;
    for (std::size_t i = 0; i < n && i < t.base_W.size(); ++i)
      if (t.is_reconstructed(i) && std::isfinite(t.base_W[i][a])) v.push_back(t.base_W[i][a]);
    centre[a] = v.empty() ? 0.0 : median(v);
  }
  std::vector<DroppedFrame> out;
  for (std::size_t i = 0; i < n; ++i) {
    if (!t.is_reconstructed(i)) continue;
    std::string reason;
    const Eigen::Vector3d& base = t.base_W[i];
    const auto angle = [&](const std::vector<double>& column, const char* name) {
      if (!reason.empty() || column.empty()) return;
      if (!(std::abs(column[i]) <= max_abs_angle_rad))
        reason = std::string(name) + " = " + format_value(column[i]) + " rad (allowed: finite, |" + name +
                 "| <= " + format_value(max_abs_angle_rad) + ")";
    };
    if (!base.allFinite())
      reason = "base = " + format_value(base) + " m is not finite";
    else if (!((base - centre).norm() <= max_base_excursion_m))
      reason = "base = " + format_value(base) + " m is " + format_value((base - centre).norm()) +
               " m from the trial's median base (allowed: " + format_value(max_base_excursion_m) + " m)";
    angle(t.theta, "theta");
    angle(t.phi, "phi");
    angle(t.zeta, "zeta");
    if (reason.empty() && t.contact[i] && t.has_contact_point()) {
      const Eigen::Vector3d& c = t.contact_W[i];
      if (!c.allFinite())
        reason = "contact point = " + format_value(c) + " m is not finite in a contact frame";
      else if (!((c - base).norm() <= max_contact_distance_m))
        reason = "contact point = " + format_value(c) + " m is " + format_value((c - base).norm()) +
                 " m from the base (allowed: " + format_value(max_contact_distance_m) + " m)";
    }
    if (!reason.empty()) out.push_back({i, t.time[i], reason});
  }
  return out;
}

Trial without_frames(const Trial& trial, const std::vector<DroppedFrame>& dropped) {
  if (dropped.empty()) return trial;
  Trial t = trial;
  if (t.reconstructed.empty()) t.reconstructed.assign(t.frames(), 1);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (const DroppedFrame& d : dropped) {
    t.reconstructed[d.frame] = 0;
    t.contact[d.frame] = 0;
    t.base_W[d.frame] = Eigen::Vector3d::Constant(nan);
    t.theta[d.frame] = t.phi[d.frame] = nan;
    if (t.has_zeta()) t.zeta[d.frame] = nan;
    if (t.has_contact_point()) t.contact_W[d.frame] = Eigen::Vector3d::Constant(nan);
  }
  return t;
}

}  // namespace vibrissa::trial
