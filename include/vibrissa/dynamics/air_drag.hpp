#pragma once
// Air drag on the links of a whisker whose base moves (issue 27 item 1; docs/dynamics.md, "Air drag").
//
// Each link is a circular cylinder in cross flow: per unit length f = -1/2 rho_air C_d(Re) d |v_n| v_n, with v_n the
// part of the velocity relative to still air normal to the link, d the local diameter and Re = |v_n| d / nu_air.
// C_d(Re) = 1 + 10 Re^(-2/3): White's correlation for a circular cylinder (F. M. White, Fluid Mechanics / Viscous
// Fluid Flow, McGraw-Hill; stated for 1 <= Re <= 2e5; whisking gives Re <= ~4, so it is used below its range:
// at Re = 1 and 0.1 it lies 13 % and 19 % under Lamb's low-Re cylinder drag). The velocity is that of the rigid base motion at the links' rest positions
// (the linear model's forcing, linear_model.hpp): the elastic velocity is left out, so drag forces the whisker
// but does not damp its own vibration (the joint dampers do). Integrated along every link by 3-point
// Gauss-Legendre.
#include <Eigen/Core>

#include "vibrissa/dynamics/simulate.hpp"

namespace vibrissa::dynamics {

/// C_d of a circular cylinder in cross flow at Reynolds number `reynolds` (> 0): 1 + 10 Re^(-2/3) (White).
double cylinder_drag_coefficient(double reynolds);

/// The drag as an external load of simulate(): generalised force (3N) on the joints and the wrench it puts on
/// the follicle (force, then moment about the base point, B axes) at time t, from the base trajectory.
ExternalLoad air_drag_load(const Whisker& whisker, const BaseTrajectory& base, const AirProperties& air);

}  // namespace vibrissa::dynamics
