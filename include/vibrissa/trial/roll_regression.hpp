#pragma once
// Roll during contact (spec §2.3, §4.3): zeta measured during contact is distorted, so it is replaced by
// the best linear fit zeta = slope theta + intercept over the non-contact frames.
#include <cstdint>
#include <string>
#include <vector>

#include "vibrissa/trial/statistics.hpp"

namespace vibrissa::trial {

struct RollFit {
  double slope = 0.0;      ///< d zeta / d theta [rad/rad]
  double intercept = 0.0;  ///< [rad]
  double r2 = 0.0;
  std::size_t frames = 0;  ///< non-contact frames used
};

/// Fits zeta(theta) over frames with contact == 0. Throws std::invalid_argument (naming `source`) if
/// fewer than 2 non-contact frames exist or theta does not vary over them.
RollFit fit_roll(const std::vector<double>& theta, const std::vector<double>& zeta,
                 const std::vector<std::uint8_t>& contact, const std::string& source = {});

/// zeta with every contact frame replaced by slope theta + intercept.
std::vector<double> extrapolate_roll(const RollFit& fit, const std::vector<double>& theta,
                                     const std::vector<double>& zeta, const std::vector<std::uint8_t>& contact);

}  // namespace vibrissa::trial
