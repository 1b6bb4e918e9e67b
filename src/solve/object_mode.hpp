#pragma once
// The driver of the object modes (object_mode.cpp), shared by the frictional mode.
#include "object_problem.hpp"

namespace vibrissa::detail {

/// Rounds of the two-contact solve in the frictionless object mode (object_solution).
inline constexpr int default_two_contact_rounds = 3;

/// Depth below which another part of the whisker counts as inside the object: a second contact [m].
inline constexpr double second_contact_depth = 1e-9;

struct ObjectOutcome {
  ObjectAttempt attempt;
  double sigma = 1.0;   ///< side of a line core
  bool folded = false;  ///< slipped_off because continuation from touch could not reach the object's place
};

/// Where the rest whisker first touches the object moved back along the deepest point's normal: the offset of
/// the object (B) and the arc length of the touch (a line core: moved onto the nearest point seen along it).
struct Touch {
  Eigen::Vector3d offset_B;
  double arc_length;
};
Touch first_touch(const Whisker& w, const ObjectGeometryB& g, const DeepestPoint& d);
/// A line core within the whisker's reach, seen along it (edge mode's test, edge_problem.hpp), with its radius.
bool core_within_reach(const Whisker& w, const ObjectGeometryB& g);
/// Whether a converged attempt is a contact: pushing, and at the tip only if the whisker's gap falls toward it.
bool valid_contact(const Whisker& w, const ObjectGeometryB& g, const ObjectAttempt& a, double sigma);
/// What a warm start knows before its first attempt: that it is one (its force is near the solution's, so the
/// first attempt is solved to the polish's tolerance at once) and the loaded link's lowest piece at the previous
/// frame's load, where the distance equation starts.
struct WarmAttempt {
  bool warm = false;
  ClearancePiece piece = ClearancePiece::centre;
};
/// One attempt from u0, switching between side and tip where the equations say the contact is at the other, and
/// (a line core) to the axis's other side `sigma` where the force says so.
ObjectAttempt attempt_object(const Whisker& w, const Scales& sc, const ObjectGeometryB& g, const FrictionLaw& law,
                             double& sigma, bool tip, const Eigen::Vector3d& u0, const SolveOptions& options,
                             const WarmAttempt& warm = {});
/// A side contact found by alternating: the force with s held, then s moved to the deflected whisker's point
/// nearest the object; then attempt_object from there (when a direct attempt stalls in the object's creases).
/// A warm start (`warm`) moves s once, to the nearest point on the links about the contact (nearest_about), and
/// starts the last attempt as attempt_object's warm attempts.
ObjectAttempt attempt_by_sliding(const Whisker& w, const Scales& sc, const ObjectGeometryB& g, const FrictionLaw& law,
                                 double& sigma, const Eigen::Vector3d& u0, const SolveOptions& options,
                                 const WarmAttempt& warm = {});
/// A side contact on a shape with creases (a mesh) solved holding one feature at a time (Shape::nearest_on_feature;
/// docs/objects.md, "Solver"): an edge as a peg of radius 0 along its line in the line core's terms (regular where
/// the mesh's own normal turns across the crease's band faster than the force can follow), a face as its plane.
/// Starts with `feature` (else the feature nearest `from`'s contact) and moves to the feature nearest each
/// solution until it is the one held; then polished with the plain queries. not_converged at a vertex, at the
/// tip, or where that does not settle within a few features.
ObjectAttempt attempt_on_features(const Whisker& w, const Scales& sc, const ObjectGeometryB& g, const FrictionLaw& law,
                                  double& sigma, const ObjectAttempt& from, const SolveOptions& options,
                                  const std::optional<SurfacePoint>& feature = std::nullopt);
/// A side contact on a shape with creases found along the whisker: the force held at s (gap and force
/// direction; attempt_side's `pinned`) gives the tangency g'(s) = n . t - r', which rises through zero at the
/// gap's minimum (on a mesh usually by a jump at a crease). A step of a link from `from`'s s, doubled until g'
/// changes sign, brackets the minimum; bisection narrows it; then attempt_on_features at the crease found
/// between the bracket's two contact points.
ObjectAttempt attempt_by_bracketing(const Whisker& w, const Scales& sc, const ObjectGeometryB& g,
                                   const FrictionLaw& law, double& sigma, const ObjectAttempt& from,
                                   const SolveOptions& options);
/// The solve: start (warm, hint, or the rest whisker's deepest point), attempts, continuation from touch.
ObjectOutcome solve_object_contact(const Whisker& w, const Scales& sc, const ObjectGeometryB& g, const FrictionLaw& law,
                                   std::optional<double> hint, const SolveOptions& options, const LoadState* warm);
/// The Solution of an outcome: outputs, contact side, approach, second contact. Where the whisker would be inside
/// the object at a second place, a frictionless outcome solves the two contacts together (two_contact.hpp) up to
/// `two_contact_rounds` times (a single contact found there may enter at the first place again); 0 (the
/// frictional mode): status second_contact.
Solution object_solution(const Whisker& w, const Placement& X_WB, const ObjectContact& object,
                         const ObjectGeometryB& g, const ObjectOutcome& outcome, const SolveOptions& options,
                         const std::optional<Eigen::Vector3d>& approach_W, int two_contact_rounds = 0);

}  // namespace vibrissa::detail
