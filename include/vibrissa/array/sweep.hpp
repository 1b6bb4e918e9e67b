#pragma once
// Head-pitch sweeps (spec §3.4, last paragraph): how the base signals change across the array as the rat
// pitches its head relative to the object. Summaries of an ArrayResult per (pitch, whisker) and per pitch.
#include <string>
#include <vector>

#include "vibrissa/array/simulation.hpp"

namespace vibrissa::array {

struct WhiskerRunSummary {
  std::size_t contact_frames = 0;
  bool touched = false;
  bool pushed_past = false;
  double onset_time = 0.0;      ///< first contact frame's time [s] (meaningful if touched)
  double peak_FT = 0.0;         ///< [N]
  double peak_MB = 0.0;         ///< [N·m]
  double peak_abs_Fx = 0.0;     ///< axial force [N]
  double MD_at_peak_MB = 0.0;   ///< bending-moment direction at the peak [rad]
  double max_abs_z_error = 0.0;  ///< eq. (7) [m]
};

struct PitchSummary {
  double pitch = 0.0;  ///< [rad]
  std::size_t whiskers_touching = 0, whiskers_pushed_past = 0, contact_frames = 0;
  double peak_MB = 0.0;             ///< largest M_B over the array [N·m]
  std::string peak_MB_whisker;      ///< its label
  double mean_peak_MB = 0.0;        ///< mean over touching whiskers [N·m]
  double mean_peak_FT = 0.0;        ///< [N]
  double max_abs_z_error = 0.0;     ///< [m]
  double first_onset_time = 0.0;    ///< [s] (meaningful if whiskers_touching > 0)
  std::vector<WhiskerRunSummary> whiskers;
};

WhiskerRunSummary summarize_run(const ArrayResult& result, std::size_t pitch, std::size_t whisker);
std::vector<PitchSummary> summarize_pitches(const ArrayResult& result);

/// Plausibility warnings of a finished run (core/plausibility.hpp): a scene in which no whisker ever
/// touches an object (objects out of reach, or placed in mm-vs-m confusion).
std::vector<std::string> array_warnings(const ArrayResult& result);

}  // namespace vibrissa::array
