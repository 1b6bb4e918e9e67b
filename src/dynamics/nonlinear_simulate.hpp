#pragma once
// The nonlinear path of dynamics::simulate() (nonlinear_simulate.cpp; include/vibrissa/dynamics/simulate.hpp).
#include "vibrissa/dynamics/simulate.hpp"

namespace vibrissa::dynamics::detail {

TimeSeries simulate_nonlinear(const Whisker& whisker, const LinearModel& model, const Modes& modes,
                              const BaseTrajectory& base, const Eigen::Vector3d& gravity_W,
                              const SimulationOptions& options, const InitialState& initial);

}  // namespace vibrissa::dynamics::detail
