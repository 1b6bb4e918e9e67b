#pragma once
// Samples no whisker can have (docs/trials.md, "Impossible samples"): found before the low-pass filter, so a
// single bad frame (a tracker glitch, a base 1e308 m away) is dropped instead of being spread over the trial.
#include <cstddef>
#include <string>
#include <vector>

#include "vibrissa/trial/format.hpp"

namespace vibrissa::trial {

/// A base farther than this from the trial's median base [m] (a head-fixed or tracked rat moves its
/// whisker base by millimetres).
inline constexpr double max_base_excursion_m = 0.1;
/// A contact point farther than this from the frame's base [m] (rat whiskers are at most ~70 mm long).
inline constexpr double max_contact_distance_m = 0.2;
/// |theta|, |phi|, |zeta| beyond this [rad] (two turns: no unwrapped angle of a whisker gets there).
inline constexpr double max_abs_angle_rad = 4.0 * 3.14159265358979323846;

struct DroppedFrame {
  std::size_t frame = 0;  ///< row of the trial as read (from 0)
  double time = 0.0;      ///< [s]
  std::string reason;     ///< the column, its value and the limit
};

/// The reconstructed frames with a non-finite or impossible base, angle or (in contact) contact point, in
/// frame order, one entry per frame (its first reason).
std::vector<DroppedFrame> impossible_frames(const Trial& trial);
/// `trial` with `dropped` marked as not reconstructed (NaN kinematics, contact 0), so that
/// reconstructed_frames_only skips them like frames that could not be reconstructed.
Trial without_frames(const Trial& trial, const std::vector<DroppedFrame>& dropped);

}  // namespace vibrissa::trial
