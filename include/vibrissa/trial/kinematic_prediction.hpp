#pragma once
// Fig. 2f (spec §2.3, §3.2): the contact height predicted from whisking kinematics alone. The undeflected
// whisker, placed at the frame's pose, is projected along the camera's line of sight onto a plane parallel to
// the peg; the height at which the projected whisker crosses the projected peg is the prediction.
#include <Eigen/Core>

#include "vibrissa/core/whisker.hpp"
#include "vibrissa/solve/options.hpp"

namespace vibrissa::trial {

/// Height along the edge [m] (as height_along_edge) where the projection of the rest whisker crosses the
/// projected edge, first crossing from the base; NaN if it does not cross. `view_W` is the line of sight
/// (need not be unit; its component along the edge is ignored).
double kinematic_contact_height(const Whisker& whisker, const Placement& X_WB, const Edge& edge,
                                const Eigen::Vector3d& view_W);

/// Front-on line of sight for a peg seen from a whisker base at `base_W`: normal to the edge and to the
/// horizontal base-to-edge direction, so the projection plane contains the peg and the whisker's length.
Eigen::Vector3d front_view_direction(const Edge& edge, const Eigen::Vector3d& base_W);

}  // namespace vibrissa::trial
