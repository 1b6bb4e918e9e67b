#include "vibrissa/array/head.hpp"

#include <algorithm>
#include <cmath>

#include "array_util.hpp"
#include "vibrissa/core/pose.hpp"

namespace vibrissa::array {

Eigen::Matrix3d head_rotation(double yaw, double pitch, double roll) {
  return rotation_z(yaw) * rotation_x(pitch) * rotation_y(roll);
}

HeadPose HeadMotion::at(double t, double extra_pitch) const {
  HeadPose pose;
  if (series.empty()) {
    pose.p_W_head = p_W_head + v_W_head * t;
    pose.R_WH = head_rotation(yaw + yaw_rate * t, pitch + pitch_rate * t + extra_pitch, roll + roll_rate * t);
    return pose;
  }
  const HeadSample* a = &series.front();
  const HeadSample* b = a;
  double f = 0.0;
  if (t >= series.back().time) {
    a = b = &series.back();
  } else if (t > series.front().time) {
    const auto it = std::upper_bound(series.begin(), series.end(), t,
                                     [](double v, const HeadSample& s) { return v < s.time; });
    b = &*it;
    a = b - 1;
    f = (t - a->time) / (b->time - a->time);
  }
  auto mix = [f](double x, double y) { return (1.0 - f) * x + f * y; };
  pose.p_W_head = (1.0 - f) * a->p_W_head + f * b->p_W_head;
  pose.R_WH = head_rotation(mix(a->yaw, b->yaw), mix(a->pitch, b->pitch) + extra_pitch, mix(a->roll, b->roll));
  return pose;
}

void validate(const HeadMotion& h, const std::string& field) {
  auto finite = [&](double v, const char* name, double shown) {
    if (!std::isfinite(v)) fail(field + "." + name + " must be finite, got " + fmt(shown));
  };
  for (int i = 0; i < 3; ++i) {
    finite(h.p_W_head[i], "position_mm", h.p_W_head[i] * 1e3);
    finite(h.v_W_head[i], "velocity_mm_per_s", h.v_W_head[i] * 1e3);
  }
  finite(h.yaw, "yaw_deg", to_deg(h.yaw));
  finite(h.pitch, "pitch_deg", to_deg(h.pitch));
  finite(h.roll, "roll_deg", to_deg(h.roll));
  finite(h.yaw_rate, "yaw_rate_deg_per_s", to_deg(h.yaw_rate));
  finite(h.pitch_rate, "pitch_rate_deg_per_s", to_deg(h.pitch_rate));
  finite(h.roll_rate, "roll_rate_deg_per_s", to_deg(h.roll_rate));
  for (std::size_t i = 0; i < h.series.size(); ++i) {
    const HeadSample& s = h.series[i];
    const std::string at = field + ".series[" + std::to_string(i) + "]";
    if (!std::isfinite(s.time) || !s.p_W_head.allFinite() || !std::isfinite(s.yaw) || !std::isfinite(s.pitch) ||
        !std::isfinite(s.roll))
      fail(at + " has a non-finite value");
    if (i > 0 && !(s.time > h.series[i - 1].time))
      fail(at + ".time_s must be later than the previous sample, got " + fmt(s.time));
  }
}

}  // namespace vibrissa::array
