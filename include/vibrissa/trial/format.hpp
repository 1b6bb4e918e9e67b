#pragma once
// A whisking trial (docs/trials.md): per-frame kinematics of one whisker touching one or more straight edges,
// plus the metadata needed to simulate it (spec §2.3). Everything is held in SI units (m, s, rad, N, Pa);
// the readers convert from the file's declared units.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "vibrissa/core/whisker.hpp"
#include "vibrissa/solve/options.hpp"

namespace vibrissa::trial {

/// Units a trial file may declare. Unknown names are rejected with std::invalid_argument.
struct Units {
  std::string length = "m";  ///< "m", "mm" or "um"
  std::string angle = "rad";  ///< "rad" or "deg"
  std::string time = "s";     ///< "s" or "ms"
};
/// Metres per declared length unit; throws naming `where` for an unknown unit.
double length_scale(const std::string& unit, const std::string& where);
/// Radians per declared angle unit.
double angle_scale(const std::string& unit, const std::string& where);
/// Seconds per declared time unit.
double time_scale(const std::string& unit, const std::string& where);

/// Material and discretisation of the trial's whisker (spec §2.1 defaults).
struct TrialMaterial {
  double youngs_modulus = 3.3e9;  ///< [Pa]
  double poisson_ratio = 0.38;
  double base_radius = 100e-6;    ///< [m]
  double taper_ratio = 15.0;      ///< base radius / tip radius
  int links = 100;
};

struct TrialMetadata {
  /// Undeflected 3D shape, base first (>= 3 points) [m]; only its shape matters (the pose places it).
  std::vector<Eigen::Vector3d> rest_shape;
  TrialMaterial material;
  std::vector<Edge> edges;  ///< the object: one or more straight edges (a peg is one), world [m]
  double frame_rate = 1000.0;  ///< [Hz] (informational; time stamps are authoritative)
  Units declared_units;       ///< the units the source file used (data here are SI)
};

/// Per-frame data, columns of equal length n. Optional columns are empty when absent.
struct Trial {
  std::string source;  ///< file name, for messages
  std::vector<double> time;               ///< [s], strictly increasing
  std::vector<Eigen::Vector3d> base_W;    ///< whisker base point, world [m]
  std::vector<double> theta, phi;         ///< protraction, elevation [rad] (core/pose.hpp convention)
  std::vector<double> zeta;               ///< roll [rad]; empty if not tracked
  std::vector<std::uint8_t> contact;      ///< 1 while the whisker touches the object
  /// Tracked contact point, world [m]; empty if not tracked; NaN allowed in frames without contact.
  std::vector<Eigen::Vector3d> contact_W;
  /// Tracked deflected shape per frame, world [m], base first; empty vector where not tracked.
  std::vector<std::vector<Eigen::Vector3d>> shape_W;
  /// Reconstruction quality (vibrissa reconstruct, docs/reconstruction.md); each empty when absent.
  /// reconstructed[i] == 0: frame i could not be reconstructed; its base, angles and contact point are NaN,
  /// contact is 0, and the analysis skips it (reconstructed_frames_only).
  std::vector<std::uint8_t> reconstructed;
  std::vector<double> reprojection_px;  ///< RMS reprojection error of the points used [px]
  std::vector<double> likelihood;       ///< mean tracker likelihood of the points used
  TrialMetadata meta;

  [[nodiscard]] std::size_t frames() const { return time.size(); }
  [[nodiscard]] bool has_zeta() const { return !zeta.empty(); }
  [[nodiscard]] bool has_contact_point() const { return !contact_W.empty(); }
  [[nodiscard]] bool has_shapes() const { return !shape_W.empty(); }
  [[nodiscard]] bool is_reconstructed(std::size_t i) const { return reconstructed.empty() || reconstructed[i] != 0; }
};

/// A maximal run of contact frames [first, last] (inclusive).
struct ContactPeriod {
  std::size_t first = 0, last = 0;
  [[nodiscard]] std::size_t size() const { return last - first + 1; }
};
std::vector<ContactPeriod> contact_periods(const std::vector<std::uint8_t>& contact);

/// The trial without its frames flagged reconstructed == 0 (the trial itself when none is flagged).
Trial reconstructed_frames_only(const Trial& trial);

/// Throws std::invalid_argument naming file, row (1-based data row) and column for the first problem:
/// size mismatch, non-finite values in required columns, non-increasing time, contact frames without a
/// tracked contact point (when that column exists), no contact periods, bad metadata.
/// `file_rows`, if given, maps frame index to the row number to report (e.g. a CSV line number); otherwise
/// frame i is reported as data row i + 1.
void validate(const Trial& trial, const std::vector<std::size_t>* file_rows = nullptr);

/// Formats "file: row R, column 'C': message" (row 0 = not row-specific) for reader errors.
std::string located_message(const std::string& source, std::size_t row, const std::string& column,
                            const std::string& message);

/// Whisker properties from the trial's material (spec §2.1).
WhiskerProperties whisker_properties(const TrialMaterial& material);

}  // namespace vibrissa::trial
