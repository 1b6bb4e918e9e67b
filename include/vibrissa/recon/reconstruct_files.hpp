#pragma once
// `vibrissa reconstruct` as one library call (docs/reconstruction.md), shared by the CLI and the Python
// binding (vibrissa.reconstruct): read the calibration and every named view's tracks, reconstruct every frame,
// build the trial, and describe the result as the report JSON text.
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "vibrissa/core/run_control.hpp"
#include "vibrissa/recon/reconstruct.hpp"
#include "vibrissa/recon/tracks.hpp"
#include "vibrissa/trial/format.hpp"

namespace vibrissa::recon {

/// One camera view: its name (in the report and messages), its track file and the camera's name in the
/// calibration (empty: the view's name).
struct ViewFile {
  std::string name, path, camera;
  TrackSelection selection;
  [[nodiscard]] const std::string& camera_name() const { return camera.empty() ? name : camera; }
};

struct ReconstructFiles {
  std::vector<ViewFile> views;  ///< >= 2, distinct names (the CLI's --view NAME=FILE, --top, --front)
  std::string calibration;    ///< a calibration (read_calibration: vibrissa JSON, anipose TOML, NAME=OpenCV file)
  std::vector<std::string> more_calibrations;  ///< further ones (e.g. one OpenCV file per camera), merged
  std::string calibration_unit;  ///< length unit of anipose / OpenCV files (m, mm, um)
};

struct ReconstructedTrial {
  Reconstruction reconstruction;
  trial::Trial trial;  ///< to_trial(reconstruction, options, {}, source)
};

/// Inconsistent inputs (Reconstruction::problems): the summary line, then each problem with its likely cause.
struct InconsistentViews : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// Reads, reconstructs and builds the trial; progress and cancellation per frame. Errors name the file;
/// inconsistent inputs throw InconsistentViews.
ReconstructedTrial reconstruct_files(const ReconstructFiles& files, const ReconstructOptions& options,
                                     const std::string& source, const RunControl& control = {});

/// One whisker of a video that holds several (docs/reconstruction.md, "Many whiskers per video"): its name and
/// how every view's tracks select it: DeepLabCut keypoints (base to tip) or a Janelia label.
struct WhiskerSelection {
  std::string name;
  std::vector<std::string> bodyparts;  ///< DeepLabCut keypoints, base to tip (when identity < 0)
  int identity = -1;                   ///< Janelia whisker label (measurements 'state'), or -1
};
/// `NAME=SPEC` (the CLI's --whisker): SPEC an integer is a Janelia label, else comma-separated keypoints.
/// Throws std::invalid_argument naming the argument.
WhiskerSelection parse_whisker(const std::string& spec);
/// Every whisker label (>= 0) of a Janelia .measurements file, in increasing order, named by the label.
std::vector<WhiskerSelection> janelia_whiskers(const std::string& measurements_path);

struct WhiskerTrial {
  std::string name;
  std::optional<ReconstructedTrial> result;  ///< empty when this whisker failed
  std::string error;                         ///< why it failed (inconsistent inputs, a missing keypoint, ...)
};
/// reconstruct_files once per whisker, each view's selection replaced by the whisker's; a failure of one
/// whisker (an error or inconsistent inputs) is recorded, the others go on. Names must be distinct.
std::vector<WhiskerTrial> reconstruct_whiskers(const ReconstructFiles& files,
                                               const std::vector<WhiskerSelection>& whiskers,
                                               const ReconstructOptions& options, const std::string& source,
                                               const RunControl& control = {});

/// The `--report` JSON text: per frame (status, points used, reprojection, closest approach, contact arc
/// length) and per contact period (undeflected shape and where it comes from).
std::string report_json(const Reconstruction& reconstruction, int indent = 1);

/// One line: frames, tracked in two or more views, reconstructed, in contact, periods, and why the others were not.
std::string summary_line(const ReconstructedTrial& result);

}  // namespace vibrissa::recon
