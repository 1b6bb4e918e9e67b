#pragma once
// Where a deflected whisker meets a surface during motion (include/vibrissa/dynamics/contact.hpp; docs/dynamics.md,
// "Contact during motion"): per link of the centre line the nearest approach to the surface (the shape's own query,
// objects/clearance.hpp's link_minimum), the places where the whisker is inside it (runs of links with a negative
// gap: each run is one contact point, at its deepest link), and which contact slot each place continues. The
// integrator (nonlinear_simulate.cpp) puts the penalty and friction forces on them.
#include <limits>
#include <span>

#include <Eigen/Core>

#include "vibrissa/objects/shape.hpp"

namespace vibrissa::dynamics::detail {

/// One contact point of the whisker on a surface.
struct SurfaceCandidate {
  bool found = false;
  int link = 0;                                          ///< the link it lies on
  double tau = 0.0;                                      ///< where along the link (0: its base-side node)
  double gap = std::numeric_limits<double>::infinity();  ///< [m], < 0: inside
  double arc_length = 0.0;                               ///< [m]
  Eigen::Vector3d point_W = Eigen::Vector3d::Zero();     ///< on the centre line [m]
  SurfacePoint surface;                                  ///< the shape's query there (world frame)
};

/// The contact points of the polyline `nodes_W` (arc lengths `arc`, radii `radii`, empty: the centre line) inside
/// `object`, into `slots`: a slot in contact before (`previous_arc` finite) takes the point nearest its arc length,
/// new points the free slots, deepest first (more points than slots: the shallowest are left out). `hold_link`
/// (>= 0 for a slot): the slot keeps a point near that link even where the whisker is outside (Newton's later
/// iterations hold the contact set). `nearest`: the smallest gap of the whole whisker (links farther than 1 mm
/// from the shape's bounds by their lower bound only).
void surface_contacts(const PlacedShape& object, std::span<const Eigen::Vector3d> nodes_W,
                      std::span<const double> arc, std::span<const double> radii,
                      std::span<const double> previous_arc, std::span<const int> hold_link,
                      std::span<SurfaceCandidate> slots, SurfaceCandidate& nearest);

}  // namespace vibrissa::dynamics::detail
