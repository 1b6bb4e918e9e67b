#pragma once
// Frame-by-frame simulation of a trial (spec §2.4, §3.2-§3.3): in every contact frame the whisker is
// placed at its filtered pose and solved in contact-point mode (tracked contact point), edge mode
// (frictionless slip on the peg line) and, if a friction coefficient is given, frictional edge mode.
// Warm starts run along time inside each contact period; periods are independent (solved in parallel).
#include <cmath>
#include <functional>
#include <optional>
#include <vector>

#include "vibrissa/contact/tracker.hpp"
#include "vibrissa/core/run_control.hpp"
#include "vibrissa/solve/options.hpp"
#include "vibrissa/solve/solution.hpp"
#include "vibrissa/trial/preprocess.hpp"

namespace vibrissa::trial {

/// The three ways a trial's contact frames are solved: the library's contact modes (contact/tracker.hpp).
using Mode = ContactMode;

/// One mode's result in one frame (world frame unless the name says otherwise). NaN where not solved.
struct ModeFrame {
  bool solved = false;  ///< a solve was attempted (contact frame)
  Status status = Status::no_contact;
  FrictionState friction = FrictionState::none;  ///< stick / slip (frictional edge mode)
  Eigen::Vector3d contact_W = Eigen::Vector3d::Constant(std::nan(""));  ///< [m]
  double s_applied = std::nan("");                                       ///< arc length of contact [m]
  Eigen::Vector3d force_W = Eigen::Vector3d::Constant(std::nan(""));    ///< force on the whisker [N]
  Eigen::Vector3d moment_W = Eigen::Vector3d::Constant(std::nan(""));   ///< about the base [N·m]
  WhiskerFrameSignals signals_B;  ///< Fx, Mx, FT, MB, FD, MD (spec §2.4); NaN-free only if converged
  double normal_force = std::nan("");    ///< |F| normal to the edge [N]
  double friction_force = std::nan("");  ///< F along the edge direction (world +z for a vertical peg) [N]
  double height = std::nan("");          ///< contact height along the edge [m]
  double shape_error = std::nan("");     ///< mean distance base..contact to the tracked shape [m] (Fig. 2b)
  int iterations = 0;
  [[nodiscard]] bool ok() const { return solved && status == Status::converged; }
};

struct FrameResult {
  double time = 0.0;  ///< [s]
  bool contact = false;
  int period = -1;              ///< index into Preprocessed::periods, -1 outside contact
  bool period_edge = false;     ///< among the first two or last two frames of its period (spec §2.4)
  ModeFrame contact_point, edge, frictional;
  double kinematic_height = std::nan("");  ///< Fig. 2f prediction of the contact height [m]
  [[nodiscard]] const ModeFrame& mode(Mode m) const {
    return m == Mode::contact_point ? contact_point : (m == Mode::edge ? edge : frictional);
  }
};

struct PipelineOptions {
  PreprocessOptions preprocess;
  SolveOptions solve;  ///< compute_shape is switched on only when tracked shapes need it
  bool contact_point_mode = true;   ///< needs a tracked contact point (skipped if the trial has none)
  bool edge_mode = true;
  std::optional<double> mu;         ///< run frictional edge mode with this coefficient
  /// Horizontal viewing axis of the Fig. 2f projection (the camera's line of sight, normal to the projection
  /// plane); default: normal to the edge and to the mean base-to-edge direction (a front-on view).
  std::optional<Eigen::Vector3d> view_direction_W;
};

struct PeriodInfo {
  int edge_index = 0;                   ///< which object edge the period touches
  Eigen::Vector3d approach_W = Eigen::Vector3d::Zero();  ///< direction of motion into the edge at onset
  double onset_height_edge = std::nan("");  ///< z_onset of eq. (7): edge-mode height at the first solved frame
};

struct PipelineResult {
  Preprocessed pre;
  std::vector<FrameResult> frames;
  std::vector<PeriodInfo> periods;
  bool has_contact_point_mode = false, has_edge_mode = false, has_frictional_mode = false;
  std::optional<double> mu;
  Eigen::Vector3d view_direction_W = Eigen::Vector3d::Zero();
};

/// Progress counts contact frames solved (total: the trial's contact frames); cancel is polled per frame.
PipelineResult run_pipeline(const Trial& trial, const PipelineOptions& options = {}, const RunControl& control = {});

}  // namespace vibrissa::trial
