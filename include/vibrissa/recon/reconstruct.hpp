#pragma once
// From N >= 2 tracked, named camera views to 3D whiskers and a trial (docs/reconstruction.md). Per frame: drop
// points below the likelihood threshold, match the reference view's points (the first view tracked in the
// frame) to every other view's polyline by the epipolar constraint (the intersection nearest the same relative
// arc length, kept monotonic along the whisker), triangulate each point from every view that sees it,
// reject reprojection outliers, fit a smooth 3D curve (cubic B-spline, Tukey-weighted IRLS, weights
// = likelihoods), resample it, and read base point, theta/phi (base tangent), zeta (core/rest_curve.hpp
// whisker_frame, core/pose.hpp) and the closest approach to the object's edges. Frames that fail are flagged
// with a status and carry NaN, never invented values.
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "vibrissa/core/run_control.hpp"
#include "vibrissa/recon/camera.hpp"
#include "vibrissa/recon/tracks.hpp"
#include "vibrissa/solve/options.hpp"
#include "vibrissa/trial/format.hpp"

namespace vibrissa::recon {

struct ReconstructOptions {
  double min_likelihood = 0.5;        ///< points below are ignored
  int min_points = 6;                 ///< matched points needed per frame
  double max_reprojection_px = 2.0;   ///< frame flagged when the RMS reprojection error exceeds this [px]
  double outlier_px = 4.0;            ///< points farther than max(this, 3 median) from the projected curve are dropped
  int fit_segments = 6;               ///< knot intervals of the cubic B-spline 3D curve
  int nodes = 40;                     ///< points of the reconstructed shape (nodes + 1 written)
  double contact_threshold = 0.3e-3;  ///< closest approach to an edge counted as contact [m]
  double base_jump = 1.0e-3;          ///< base farther than this from the local median base is flagged [m]
  int base_window = 25;               ///< frames on each side for that median
  double frame_rate = 1000.0;         ///< [Hz]: time = frame / frame_rate
  std::int64_t front_frame_offset = 0;  ///< the view named "front": its frame f is frame f + offset of the others
  /// Per view name: its frame f is frame f + offset (views whose videos start at different times); "front"
  /// here and front_frame_offset together are an error.
  std::map<std::string, std::int64_t> frame_offsets;
  [[nodiscard]] std::int64_t frame_offset(const std::string& view) const;
  /// Checks of the inputs (Reconstruction::problems; reconstruct_files throws InconsistentViews on any):
  double min_yield = 0.5;             ///< reconstructed / frames seen by both views below this: a problem
  double max_unpaired = 0.05;         ///< frames seen by one view only / all frames above this (and > 2), or ranges
                                      ///< differing by more than max(2, 1 %) frames: a problem (1: accept any)
  double max_epipolar_px = 2.0;       ///< median epipolar distance of the base points of a pair of views above
                                      ///< this and above 4x the median reprojection error (about the noise): a problem
  std::vector<Edge> edges;            ///< the object (a peg is one edge); empty: no contact detection
  void validate() const;              ///< throws std::invalid_argument naming the field
};

enum class FrameStatus : std::uint8_t {
  ok,
  missing_view,        ///< tracked in fewer than two views
  too_few_points,      ///< fewer than min_points above the likelihood threshold or matched
  reprojection,        ///< RMS reprojection error above max_reprojection_px
  inconsistent_base,   ///< base jumps away from its neighbours (tracker identity swap)
  base_not_reached,    ///< the curve stops short of a base point a view tracked (its partner lost in the other view)
};
const char* frame_status_name(FrameStatus status);

struct ReconstructedFrame {
  std::int64_t frame = 0;
  FrameStatus status = FrameStatus::missing_view;
  std::size_t points_used = 0;  ///< triangulated points in the curve fit
  std::size_t views_used = 0;   ///< views tracked in this frame with at least two usable points
  /// Reprojection error [px]: RMS distance of the tracked points of every view (likelihood above the threshold,
  /// outliers excluded) to the fitted 3D curve projected into that view; NaN if no curve was fitted.
  double reprojection_px;
  std::vector<double> view_reprojection_px;  ///< the same per view (Reconstruction::view_names); empty if no curve
  /// Per view, per tracked point: its distance to the projected curve [px]; NaN below the likelihood threshold.
  std::vector<std::vector<double>> point_reprojection_px;
  std::size_t outliers = 0;  ///< tracked points farther than max(outlier_px, 3 median) from the projected curve
  double likelihood;       ///< mean likelihood of the points used; NaN if none
  Eigen::Vector3d base_W;  ///< NaN unless ok
  double theta, phi, zeta;  ///< [rad], NaN unless ok
  std::vector<Eigen::Vector3d> shape_W;  ///< base first; empty unless ok
  bool contact = false;
  Eigen::Vector3d contact_W;  ///< point of the edge nearest the whisker (contact frames), else NaN
  double contact_s = 0.0;     ///< its arc length from the base [m] (NaN outside contact)
  double approach = 0.0;      ///< closest distance to the edges [m] (NaN without edges or when not ok)
  ReconstructedFrame();
  [[nodiscard]] bool ok() const { return status == FrameStatus::ok; }
};

/// The undeflected shape of one contact period: the mean, in each frame's whisker frame, of the shapes of the
/// free (ok, no contact) frames between the previous period and this one (else between it and the next),
/// placed at the pose of the free frame nearest the period.
struct UndeflectedShape {
  std::int64_t first_frame = 0, last_frame = 0;  ///< the contact period
  std::int64_t source_frame = -1;                ///< the free frame whose pose places the shape (-1: none)
  std::size_t frames_averaged = 0;               ///< free frames in the mean
  std::vector<Eigen::Vector3d> shape_W;
};

/// Agreement of two views with the calibration: the median over frames of the symmetric epipolar distance of
/// their base points (point 0 of both tracks, above the likelihood threshold) [ideal px]; about the pixel noise
/// when they agree; NaN if no frame has both. `swapped_epipolar_px`: the same with the two views' tracks
/// exchanged.
struct ViewPairCheck {
  std::size_t a = 0, b = 0;  ///< indices into Reconstruction::view_names
  double base_epipolar_px, swapped_epipolar_px;
  ViewPairCheck();
};

struct Reconstruction {
  std::vector<std::string> view_names;     ///< the views, in the order of the per-view fields of the frames
  std::vector<ReconstructedFrame> frames;  ///< every frame tracked in any view, in order
  std::vector<UndeflectedShape> undeflected;
  std::size_t frames_in_both = 0;          ///< frames tracked in at least two views (both, with two)
  std::vector<ViewPairCheck> view_pairs;   ///< every pair of views (a < b)
  /// The largest of the pairs' base epipolar medians, and the swapped distance of that pair.
  double base_epipolar_px, swapped_epipolar_px;
  /// Per view, the median over frames with a fitted curve of its reprojection error [px] (NaN if none).
  std::vector<double> view_reprojection_px_median;
  /// The trackers' pixel noise estimated from the tracks' smoothness alone [px] (third differences across the
  /// curve; NaN without four consecutive tracked points). With three or more views the reprojection error and
  /// the pairs' base epipolar distances are compared with it.
  double track_noise_px;
  /// Inconsistent inputs, each naming the likely cause (views out of step, swapped, a wrong calibration, a low
  /// yield); empty when none. reconstruct_files throws InconsistentViews listing them.
  std::vector<std::string> problems;
  Reconstruction();
  [[nodiscard]] std::size_t count(FrameStatus status) const;
};

/// One named camera view: its tracks and camera (the name is the one in the calibration and the report).
struct View {
  std::string name;
  Tracks2D tracks;
  Camera camera;
};

/// Reconstructs every frame tracked in any view from every view that sees it (>= 2 views, distinct names);
/// progress and cancellation per frame. Throws std::invalid_argument for fewer than two views or a repeated name.
Reconstruction reconstruct(const std::vector<View>& views, const ReconstructOptions& options,
                           const RunControl& control = {});

/// Two views named "top" and "front" (the spec's set-up, §2.2).
Reconstruction reconstruct(const Tracks2D& top, const Camera& top_camera, const Tracks2D& front,
                           const Camera& front_camera, const ReconstructOptions& options,
                           const RunControl& control = {});

/// The trial of a reconstruction (docs/trials.md): every frame, with the columns reconstructed,
/// reprojection_px and likelihood; frames not reconstructed carry NaN and contact 0. Rest shape = the
/// undeflected shape of the first contact period; edges from the options.
trial::Trial to_trial(const Reconstruction& reconstruction, const ReconstructOptions& options,
                      const trial::TrialMaterial& material = {}, const std::string& source = {});

}  // namespace vibrissa::recon
