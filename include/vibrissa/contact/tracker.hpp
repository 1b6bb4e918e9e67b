#pragma once
// One whisker's contact across frames: the single per-frame loop under trials, synthetic trials, array
// simulations and Python batches (docs/conventions.md, "Contact tracking"). The policy, in one place:
//
//  * Onset. Simulated frames (step): free -> contact when the rest whisker crosses an edge between the last
//    frame and this one (contact/crossing.hpp; a finite edge only between its ends); the earliest crossing
//    wins. Tracked frames (step_tracked): contact whenever the data say so.
//  * Contact side. At onset the approach direction is the crossing's (simulated) or the motion of the rest
//    point nearest the edge since the last frame (tracked); the edge must push against it.
//  * Warm start. Each frame starts from the last converged frame of the same contact; a cold start uses the
//    crossing's arc length (simulated), the caller's hint or the last converged arc length (tracked).
//  * Friction start. Where the rest whisker first meets the edge: the crossing point (simulated) or the
//    nearest point of the rest whisker on the edge line at onset (tracked); then the last converged contact.
//  * Stick / slip. Coulomb, quasi-static (solve_frictional_edge); reported in Solution::friction.
//  * Slip-off, push-past, release (simulated). slipped_off (past the tip, or a fold of the equilibrium
//    branch), no equilibrium (not_converged), or a contact beyond a finite edge's end -> pushed_past;
//    no_contact (the edge would have to pull) -> free. pushed_past -> free when the rest whisker crosses that
//    edge's line back (retraction), or -> contact when it crosses another edge.
//  * Tracked frames that fail to solve keep the data's contact but restart cold at the next frame.
//
// The tracker holds a reference to its Whisker (the immutable model) and owns per-frame buffers sized once:
// with SolveOptions::compute_shape off, warm frames allocate nothing.
#include <cstddef>
#include <cstdint>
#include <limits>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "vibrissa/contact/edge_segment.hpp"
#include "vibrissa/core/whisker.hpp"
#include "vibrissa/objects/shape.hpp"
#include "vibrissa/solve/options.hpp"
#include "vibrissa/solve/solution.hpp"

namespace vibrissa {

/// Which equations hold the contact (spec §2.1): the tracked point, a frictionless edge, a Coulomb edge.
enum class ContactMode : std::int8_t { contact_point = 0, edge = 1, frictional_edge = 2 };
std::string_view to_string(ContactMode mode);
/// Inverse of to_string; throws std::invalid_argument naming `field` for an unknown name.
ContactMode contact_mode_from_string(std::string_view name, const char* field = "mode");

struct TrackerOptions {
  /// edge: frictionless; frictional_edge: Coulomb with `mu`. Against objects (step with PlacedShape) the same
  /// two are the frictionless and frictional object modes.
  ContactMode mode = ContactMode::edge;
  double mu = 0.0;     ///< Coulomb friction coefficient (frictional_edge) [-]
  SolveOptions solve;  ///< per-frame solves (find_other_roots is not used per frame)
  bool thickness = true;  ///< objects: the whisker's surface touches them (ObjectContact::thickness)
};
void validate(const TrackerOptions& options);

/// What the data say about one tracked frame, besides the placement and the edge.
struct TrackedInput {
  bool in_contact = true;                      ///< the whisker touches in this frame
  std::optional<Eigen::Vector3d> p_W_contact;  ///< contact_point mode: the tracked contact point [m] (required)
  std::optional<double> arc_length_hint;       ///< for cold starts [m]
  std::optional<Eigen::Vector3d> approach_W;   ///< overrides the approach direction the tracker derives at onset
  std::optional<Eigen::Vector3d> initial_contact_W;  ///< frictional: overrides where friction starts at onset [m]
};

/// The tracker's account of one frame.
struct TrackedFrame {
  ContactState state = ContactState::free;  ///< after this frame
  int edge = -1;         ///< index of the touched (or pushed-past) edge in the frame's edge list; -1: none
  bool onset = false;    ///< contact began at this frame
  bool solved = false;   ///< a solve ran at this frame; its outcome is `solution`
  /// Contact position along the edge from its p0 [m] (converged contact frames; NaN otherwise).
  double edge_coordinate = std::numeric_limits<double>::quiet_NaN();
  /// edge_coordinate at the first converged frame of this contact: z_onset of eq. (7) [m].
  double onset_edge_coordinate = std::numeric_limits<double>::quiet_NaN();
  /// Direction in which the whisker moved into the edge at onset (unit, world; zero if unknown).
  Eigen::Vector3d approach_W = Eigen::Vector3d::Zero();
  Solution solution;  ///< the frame's solve (contact_state equals `state`)
};

class ContactTracker {
 public:
  /// `whisker` must outlive the tracker. Throws std::invalid_argument for invalid options.
  ContactTracker(const Whisker& whisker, const TrackerOptions& options);

  /// A simulated frame: the whisker at `X_WB`, the scene's edges in world coordinates at this frame (the same
  /// edges, in the same order, every frame; they may move). The first frame after construction or reset()
  /// has nothing to cross from and is free. Edge modes only.
  const TrackedFrame& step(const Placement& X_WB, std::span<const EdgeSegment> edges);

  /// A simulated frame against objects (docs/objects.md, "Tracking"), in world coordinates at this frame (the
  /// same objects every frame; they may move). Onset when the rest whisker enters an object since the last frame
  /// (its clearance falls below zero; of several, the one it is deepest in); the approach is the motion of the
  /// rest point deepest in it. Frictionless or Coulomb object mode
  /// per frame; converged and second_contact keep the contact, no_contact releases it, slipped_off and
  /// not_converged push it past; pushed_past -> free once the rest whisker is clear of that object again.
  /// TrackedFrame::edge is the object's index; edge_coordinate stays NaN.
  const TrackedFrame& step(const Placement& X_WB, std::span<const PlacedShape> objects);

  /// A tracked frame: contact when `input.in_contact`. `edge` is the touched edge (required in the edge
  /// modes; in contact-point mode optional, to split the force into normal and edge components).
  const TrackedFrame& step_tracked(const Placement& X_WB, const EdgeSegment* edge, const TrackedInput& input);

  /// Forgets all history (the next frame is a first frame).
  void reset();

  [[nodiscard]] const TrackedFrame& frame() const { return frame_; }
  [[nodiscard]] ContactState state() const { return frame_.state; }
  [[nodiscard]] const TrackerOptions& options() const { return options_; }
  [[nodiscard]] std::size_t solves() const { return solves_; }                ///< solves run so far
  [[nodiscard]] std::size_t failed_solves() const { return failed_solves_; }  ///< of which not_converged

 private:
  void begin_frame();
  void forget_contact();
  void place_rest_nodes(const Placement& X_WB);
  void solve_edge_frame(const Placement& X_WB, const EdgeSegment& e, const std::optional<Eigen::Vector3d>& approach_W,
                        std::optional<double> hint);
  void record_converged(const EdgeSegment* e);
  /// The rest whisker's clearance with object k this frame (only whether and where it is inside matters: links
  /// clear by more than a link's length are skipped), or, where the whisker has not moved
  /// (in the object's frame) by as much as the lower bound of its gap when it was last computed, a positive lower
  /// bound: a whisker far from an object queries it only every so many frames.
  double object_clearance(std::size_t k, const PlacedShape& object, double& arc_length);

  const Whisker& whisker_;
  TrackerOptions options_;
  TrackedFrame frame_;

  bool have_previous_ = false;
  Placement previous_X_;
  std::vector<Eigen::Vector3d> nodes_prev_W_, nodes_now_W_;  // rest nodes, sized once
  std::vector<EdgeSegment> edges_prev_;                      // capacity kept across frames
  std::vector<double> clearance_prev_;                       // objects: the rest whisker's clearance last frame
  /// Objects: the lower bound of the rest whisker's gap where it was last computed, and its nodes then (in the
  /// object's frame) (object_clearance).
  std::vector<double> clearance_bound_;
  std::vector<std::vector<Eigen::Vector3d>> clearance_nodes_O_;

  // History of the current contact.
  int edge_ = -1;
  bool in_tracked_contact_ = false;
  std::optional<LoadState> warm_;
  std::optional<double> hint_;
  std::optional<Eigen::Vector3d> friction_start_W_;
  Eigen::Vector2d approach_E_ = Eigen::Vector2d::Zero();  // simulated: in the edge's frame, follows the edge
  std::optional<Eigen::Vector3d> approach_W_;             // tracked
  double onset_coordinate_ = std::numeric_limits<double>::quiet_NaN();

  std::size_t solves_ = 0, failed_solves_ = 0;
};

}  // namespace vibrissa
