#pragma once
// The `vibrissa modes` and `vibrissa dynamics` cases and their outputs (docs/dynamics.md, docs/formats.md).
#include <filesystem>
#include <optional>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "vibrissa/array/kinematics.hpp"
#include "vibrissa/dynamics/deflected_modes.hpp"
#include "vibrissa/dynamics/simulate.hpp"
#include "vibrissa/io/case_json.hpp"
#include "vibrissa/io/labelled_data.hpp"

namespace vibrissa::io {

/// Whisking of one whisker about its pose (array/kinematics.hpp): theta = theta_pose + dtheta(t),
/// phi = phi_pose + k_phi dtheta(t), zeta = zeta_pose + k_zeta dtheta(t), base point fixed.
struct Whisking {
  array::Protraction protraction;
  double k_phi = 0.0, k_zeta = 0.0;  ///< [rad/rad]
};

/// The base motion of a whisker whisking about `pose` (velocities and accelerations by
/// dynamics::trajectory_from_placements).
dynamics::BaseTrajectory whisking_trajectory(const Pose& pose, const Whisking& whisking);

struct DynamicsCase {
  explicit DynamicsCase(Whisker w) : whisker(std::move(w)) {}
  Whisker whisker;
  dynamics::DynamicsProperties properties;
  std::optional<Whisking> whisking;       ///< none: the base stays at the whisker's pose
  /// Start in equilibrium under this force [N] (B axes, fixed direction) at `force_arc_length` (default: the
  /// tip), released at t = 0: a whisker let go by a peg or a finger.
  std::optional<Eigen::Vector3d> tip_force_B;
  std::optional<double> force_arc_length;
  dynamics::SimulationOptions options;
  int mode_count = 10;                    ///< modes listed (`vibrissa modes`, summary.json)
  /// `vibrissa modes`: the modes about the equilibrium under this load (the "load" of `vibrissa solve`) instead
  /// of about the rest shape; `hold` overrides how a contact holds (stick / slip; docs/dynamics.md).
  std::optional<Load> load;
  std::optional<dynamics::ContactModel> hold;
};

/// The "dynamics" object of a case (or of an array config): density, damping_ratio | joint_damping_time, gravity,
/// air_drag, air_density, air_kinematic_viscosity; errors name the field and value.
dynamics::DynamicsProperties dynamics_properties_from_json(const nlohmann::json& d);

/// Contact events as summary.json lists them (`vibrissa dynamics`, `vibrissa array --dynamics`): time [s], type,
/// object, arc_length [m], point_W [m], force_W [N].
nlohmann::json contact_events_json(const std::vector<dynamics::ContactEvent>& events);

/// Reads {"whisker": {...as in solve...}, "dynamics": {...}, "whisking": {...}, "initial": {...}, "duration",
/// "output_rate", "relative_tolerance", "absolute_tolerance", "modes"}; errors name the field and value.
DynamicsCase dynamics_case_from_json(const nlohmann::json& j);
/// The same for a whisker built elsewhere (Python): every key but "whisker".
DynamicsCase dynamics_case_from_json(const nlohmann::json& j, const Whisker& whisker);

/// The base trajectory of a case.
dynamics::BaseTrajectory base_trajectory(const DynamicsCase& c);
/// The case's air drag as simulate()'s external load (empty when dynamics.air_drag is off).
dynamics::ExternalLoad external_load(const DynamicsCase& c);
/// The initial state of a case (empty: equilibrium under the base motion at t = 0).
dynamics::InitialState initial_state(const DynamicsCase& c, const dynamics::LinearModel& model);

/// The modes of a case: about the rest shape, or (with a load) about the equilibrium under it, found by the
/// quasi-static solve of the load (as `vibrissa solve`) and refined on the dynamic chain.
struct CaseModes {
  dynamics::Modes modes;
  std::optional<dynamics::DeflectedModes> deflected;
  dynamics::HeldLoad held;
  Solution solution;  ///< the quasi-static solve (with a load)
};
/// Throws std::runtime_error naming the status when the load's quasi-static solve fails, and
/// std::invalid_argument for the inverse (base_wrench) mode, which has no load to hold.
CaseModes case_modes(const DynamicsCase& c, int count);
/// "equilibrium" of the modes' JSON: the load, contact model, constraints, Newton's residual, K_T's asymmetry.
nlohmann::json equilibrium_to_json(const CaseModes& m, const Whisker& whisker);

/// `vibrissa modes` result: frequencies, damped frequencies, damping ratios, torsion fractions, node shapes.
nlohmann::json modes_to_json(const dynamics::Modes& modes, const Whisker& whisker, const DynamicsCase& c);

/// The labelled table of a time series (dynamics.h5; docs/formats.md).
LabelledData dynamics_data(const dynamics::TimeSeries& ts);
/// summary.json of a run: status, steps, peak base signals, the lowest modes.
nlohmann::json dynamics_summary(const dynamics::TimeSeries& ts, const dynamics::Modes& modes, const DynamicsCase& c);
/// Writes dynamics.csv, dynamics.h5 and summary.json into `dir` as one set (output_folder.hpp).
void write_dynamics_outputs(const dynamics::TimeSeries& ts, const nlohmann::json& summary,
                            const std::filesystem::path& dir);

}  // namespace vibrissa::io
