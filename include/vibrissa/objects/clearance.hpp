#pragma once
// How far a whisker is from an object (docs/objects.md, "Clearance and first touch"): its links are straight
// segments whose radius varies linearly from node to node (cone frusta; with no radii, the centre line), and
// the gap of a point is the object's signed distance minus the radius there. Used to find where a placed rest
// whisker first meets an object (contact onset), and to check a deflected whisker nowhere enters it.
#include <limits>
#include <span>

#include <Eigen/Core>

#include "vibrissa/objects/shape.hpp"

namespace vibrissa {

struct Clearance {
  double gap = std::numeric_limits<double>::infinity();  ///< smallest gap found [m] (< 0: inside the object)
  double arc_length = 0.0;                                ///< where along the whisker [m]
  Eigen::Vector3d point_W = Eigen::Vector3d::Zero();      ///< the centre-line point there
  Eigen::Vector3d normal_W = Eigen::Vector3d::UnitZ();    ///< the object's normal there
  /// No point of the polyline has a smaller gap [m], whatever the shape (from the gaps and bounds of the nodes and
  /// the gap's Lipschitz constant along each link): how far it may move before it can enter the object.
  double lower_bound = -std::numeric_limits<double>::infinity();
};

/// The smallest gap found along one link from a_W to b_W (radii r_a, r_b at its ends; 0 for the centre line),
/// given the queries at its ends: where the gap's slope n . (b - a) - (r_b - r_a) turns from negative to positive
/// along it, its minimum inside by regula falsi on the slope (exact for convex shapes; a local minimum on a mesh),
/// else the smaller end. `stop_below`: returns at the first point found with a gap below it.
struct LinkGap {
  double tau = 0.0;                                       ///< where along the link (0: a, 1: b)
  double gap = std::numeric_limits<double>::infinity();   ///< [m]
  SurfacePoint surface;                                   ///< the query there (world frame)
};
LinkGap link_minimum(const PlacedShape& object, const Eigen::Vector3d& a_W, const Eigen::Vector3d& b_W, double r_a,
                     double r_b, const SurfacePoint& q_a, const SurfacePoint& q_b,
                     double stop_below = -std::numeric_limits<double>::infinity());

/// The smallest gap of the polyline `nodes_W` (arc lengths `arc`, radii `radii` or none) to the placed shape, if
/// it is below `threshold`: links that cannot come below it are skipped (the signed distance changes no faster
/// than the distance moved, so a node's gap bounds its neighbourhood; the shape's bounds bound the rest); on each
/// remaining link the minimum is found from its ends' gaps and slopes (exact for convex shapes; the nearest
/// local minimum on a mesh). Result gap = +infinity if nothing is below the threshold.
/// `first_below`: returns at the first point found below the threshold (whether there is one, not the smallest;
/// lower_bound then -infinity).
Clearance clearance(const PlacedShape& object, std::span<const Eigen::Vector3d> nodes_W, std::span<const double> arc,
                    std::span<const double> radii, double threshold = std::numeric_limits<double>::infinity(),
                    bool first_below = false);

}  // namespace vibrissa
