#pragma once
// Time integration of the linearised chain with a prescribed base motion (docs/dynamics.md).
//
// Integrator: the trapezoidal rule (implicit, A-stable, second order; for the undamped linear system it
// conserves the elastic + kinetic energy exactly, to rounding) with step-doubling error control: each step
// h is also taken as two steps h/2, the difference / 3 estimates the local error of the two half steps
// (Richardson), which are kept; the error is measured in the energy norm, sqrt(sum_n omega_n^2 de_n^2 +
// de'_n^2) [sqrt(J)], against relative_tolerance times the largest sqrt(2 E) so far plus absolute_tolerance.
// The step is chosen from that estimate (order 2: factor (tol / err)^(1/3)); steps land on output times.
// Because the stiffness-proportional damping keeps the modes uncoupled, the rule is applied mode by mode
// (the trapezoidal rule commutes with the change to modal coordinates, so this is the same solution as in
// the joint coordinates at O(3N) work per step).
#include <functional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "vibrissa/core/pose.hpp"
#include "vibrissa/dynamics/contact.hpp"
#include "vibrissa/dynamics/modes.hpp"

namespace vibrissa::dynamics {

/// Base motion at time t [s].
using BaseTrajectory = std::function<BaseMotion(double)>;

/// A base trajectory from placements over time: velocities and accelerations by 5-point central differences
/// with step `h` [s] (truncation error O(h^4)).
BaseTrajectory trajectory_from_placements(std::function<Placement(double)> placement, double h = 1e-4);

/// A fixed base at `placement`.
BaseTrajectory fixed_base(const Placement& placement);

/// Which equations of motion (docs/dynamics.md): `linear` (the linearised chain above, trapezoidal rule mode by
/// mode); `nonlinear` (the chain's exact kinematics: large rotations of the joints, contact forces through the
/// deflected shape; the same joint springs, dampers and rest mass matrix; L-stable TR-BDF2 with its embedded
/// error estimate, order 2); `automatic`: nonlinear when there are objects, else linear.
enum class ChainModel { automatic, linear, nonlinear };
std::string_view to_string(ChainModel model);

struct SimulationOptions {
  double duration = 1.0;              ///< [s]
  double output_rate = 1000.0;        ///< frames per second [Hz]; frames at k / output_rate, 0 included
  double relative_tolerance = 1e-6;   ///< local error per step, energy norm relative to the largest sqrt(2 E)
  double absolute_tolerance = 1e-14;  ///< [sqrt(J)]
  double max_step = 0.0;              ///< [s]; 0: 1 / output_rate
  long max_steps = 50'000'000;
  bool record_nodes = true;           ///< node positions per frame (3(N+1) doubles a frame)
  ChainModel model = ChainModel::automatic;
  /// Objects the whisker may touch (contact.hpp); they need the nonlinear chain.
  std::vector<Obstacle> objects;
  ContactLaw contact;
  /// Modes integrated by the nonlinear chain (the contact path): the lowest `modes`, the others following their
  /// load statically (residual flexibility; docs/dynamics.md, "Modal truncation"); 0 or >= 3N: all (exact).
  /// The linear chain always integrates all.
  int modes = 0;
};
void validate(const SimulationOptions& options);

/// Initial deflection and rate in joint coordinates (3N each). Empty q: in equilibrium under the load of the
/// base motion at t = 0, q = K^-1 G u(0), at rest relative to the base (so that a motion that starts with an
/// acceleration does not start with a jolt), or undeformed with `undeformed`.
struct InitialState {
  Eigen::VectorXd q, q_dot;
  bool undeformed = false;
};

enum class SimulationStatus { completed, max_steps, step_too_small };
std::string_view to_string(SimulationStatus status);

struct TimeSeries {
  SimulationStatus status = SimulationStatus::completed;
  std::vector<double> time;                          ///< [s]
  /// Wrench the whisker transmits to the follicle (the quasi-static solves' convention: docs/conventions.md),
  /// moment about the base point; B and world axes [N], [N m].
  std::vector<Eigen::Vector3d> force_B, moment_B, force_W, moment_W;
  std::vector<Eigen::Vector3d> tip_displacement_B;   ///< tip minus its rest position, in B [m]
  std::vector<double> kinetic_energy, elastic_energy;  ///< relative to the moving frame B [J]
  Eigen::MatrixXd q;                                  ///< 3N x frames
  std::vector<std::vector<Eigen::Vector3d>> nodes_W;  ///< per frame, N+1 nodes [m] (if record_nodes)
  std::vector<Placement> placements;                  ///< base placement per frame
  ChainModel model = ChainModel::linear;               ///< the equations integrated (never automatic)
  std::vector<ContactChannels> contacts;              ///< one per object, per frame
  std::vector<ContactEvent> events;                   ///< in time order
  double max_penetration = 0.0;                       ///< largest -gap at any accepted step [m]
  long steps = 0, rejected_steps = 0;
  double smallest_step = 0.0, largest_step = 0.0;     ///< accepted steps [s]
};

/// A load on the links besides the base motion (e.g. air drag, air_drag.hpp): at time t, adds its generalised force
/// (3N, joint coordinates) to `force` and the wrench it transmits to the follicle (force, then moment about the
/// base point; B axes) to `wrench_B`. It may depend on time and the base motion, not on the deflection.
using ExternalLoad = std::function<void(double t, Eigen::VectorXd& force, Eigen::Matrix<double, 6, 1>& wrench_B)>;

/// Integrates from t = 0 over options.duration. The frame of each output is computed from the exact state at
/// that time (steps land on output times).
TimeSeries simulate(const Whisker& whisker, const LinearModel& model, const Modes& modes,
                    const BaseTrajectory& base, const Eigen::Vector3d& gravity_W, const SimulationOptions& options,
                    const InitialState& initial = {}, const ExternalLoad& external = {});
/// Builds the model and all its modes, then simulates.
TimeSeries simulate(const Whisker& whisker, const DynamicsProperties& props, const BaseTrajectory& base,
                    const SimulationOptions& options, const InitialState& initial = {});

}  // namespace vibrissa::dynamics
