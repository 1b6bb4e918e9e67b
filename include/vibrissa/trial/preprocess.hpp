#pragma once
// Pre-processing of a tracked trial (spec §2.3): roll during contact from the theta-zeta fit over
// non-contact frames, zero-phase 85 Hz Butterworth on base point, angles and contact point, and (on
// request) one undeflected shape per contact period, taken from the tracked shape at the end of contact.
#include <optional>
#include <string>
#include <vector>

#include "vibrissa/trial/format.hpp"
#include "vibrissa/trial/roll_regression.hpp"

namespace vibrissa::trial {

struct PreprocessOptions {
  bool filter = true;
  double cutoff_hz = 85.0;  ///< spec §2.3
  int filter_order = 2;     ///< per pass; filtfilt doubles it (docs/trials.md)
  bool roll_from_theta = true;  ///< replace zeta in contact frames by the non-contact fit (spec §2.3)
  bool rest_shape_per_contact = false;  ///< spec §2.3: shape at the last frame of each contact period
};

struct Preprocessed {
  Trial trial;  ///< filtered copy; zeta always present (0 if neither tracked nor fitted)
  std::optional<RollFit> roll;
  std::string zeta_source;  ///< "tracked", "tracked, contact frames from the theta fit", "not tracked: 0"
  double sample_rate_hz = 0.0;  ///< from the median time step
  std::vector<ContactPeriod> periods;
  /// Per period: the rest shape to use (points, world or any frame: only the shape matters).
  std::vector<std::vector<Eigen::Vector3d>> rest_shapes;
};

/// Throws std::invalid_argument naming the trial's file for impossible requests (per-period shapes
/// without tracked shapes, a cutoff above Nyquist).
Preprocessed preprocess(const Trial& trial, const PreprocessOptions& options = {});

}  // namespace vibrissa::trial
