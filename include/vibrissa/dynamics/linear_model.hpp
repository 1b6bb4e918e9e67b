#pragma once
// Inertia, damping and the linearised equations of motion of the chain (docs/dynamics.md).
//
// The generalised coordinates are the joint rotation vectors theta_j of the second-order scheme's chain (3 per
// joint, components in B's axes, zero at rest), the same joints and springs as the quasi-static model
// (core/chain.hpp): joint j at node j turns every link distal to it. About the rest shape, in the whisker
// frame B that moves with the base,
//     M q'' + C q' + K q = G u(t),
// where K is block diagonal, K_j = (w_j K_j^B)^-1 (the inverse of the joint compliance of eqs. (1)-(3), with
// the follicle spring in series at joint 0), M the mass matrix of the rigid frustum links, C = beta K the
// joint viscous dampers (stiffness-proportional, so every mode keeps its own damping ratio
// zeta_n = beta omega_n / 2), and u(t) the base motion: the acceleration of the base point minus gravity, the
// angular acceleration and the outer product of the angular velocity, all in B. The base motion enters
// exactly at the rest positions; products of the deflection with the base motion (Coriolis, centrifugal
// stiffening of the deflection) and the geometric nonlinearity of large deflections are left out.
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "vibrissa/core/whisker.hpp"

namespace vibrissa::dynamics {

/// Air around a whisker (air_drag.hpp).
struct AirProperties {
  double density = 1.204;                 ///< [kg/m^3], dry air at 20 degC and 101.325 kPa
  double kinematic_viscosity = 1.516e-5;  ///< [m^2/s], dry air at 20 degC (dynamic 1.825e-5 Pa s / density)
};

/// Material and damping of a whisker in motion. Defaults: docs/dynamics.md, "Parameters".
struct DynamicsProperties {
  /// Density [kg/m^3]: keratin, about 1.3 g/cm^3 (the value used for whisker dynamics in the literature;
  /// docs/dynamics.md).
  double density = 1300.0;
  /// Damping ratio of the first mode: isolated rat whiskers clamped at the base ring down with damping ratios
  /// 0.11-0.17 (Hartmann et al. 2003, J. Neurosci. 23:6510); the default is their midpoint. The joint
  /// dampers are c_j = beta k_j with beta = 2 zeta_1 / omega_1.
  double damping_ratio = 0.14;
  /// The damper time constant beta [s] (joint damping coefficient per unit joint stiffness) instead of
  /// damping_ratio: zeta_n = beta omega_n / 2.
  std::optional<double> joint_damping_time;
  /// Gravity in the world frame [m/s^2]; zero by default (whiskers are light: docs/dynamics.md).
  Eigen::Vector3d gravity_W = Eigen::Vector3d::Zero();
  /// Quadratic air drag on the links (air_drag.hpp); off by default (docs/dynamics.md, "Air drag": it changes the
  /// base signals of whisking in air by a few per cent, and it is evaluated at the rigid base motion's velocity).
  bool air_drag = false;
  AirProperties air;
  /// Modes the nonlinear chain (contact) integrates, the rest static (SimulationOptions::modes; 0: all). Read as
  /// dynamics.modes ("all" or a count) and handed to the simulation by the case and array readers.
  int modes = 0;
};

/// Throws std::invalid_argument naming the field and value for a non-positive density (whisker or air), a
/// non-positive air viscosity, a negative or
/// non-finite damping ratio or damper time, or a non-finite gravity.
void validate(const DynamicsProperties& props);

/// Mass properties of one rigid link (a frustum between its nodes' radii along its chord).
struct LinkInertia {
  double mass = 0.0;                                            ///< [kg]
  Eigen::Vector3d centroid_B = Eigen::Vector3d::Zero();         ///< [m]
  Eigen::Matrix3d inertia_B = Eigen::Matrix3d::Zero();          ///< about the centroid, B axes [kg m^2]
};

/// Mass, centroid and rotational inertia of every link of the whisker at rest (exact for the frustum:
/// 3-point Gauss-Legendre quadrature of polynomials of degree <= 4 along the chord).
std::vector<LinkInertia> link_inertias(const Whisker& whisker, double density);

/// Mass matrix (3N x 3N) of rigid links in spatial joint increments (joint j turns every link distal to it about
/// node j): links with mass properties `links` (centroids and inertias in B) and nodes `nodes_B` (N+1). The
/// kinetic energy of the links under x' = sum_{j<=i} theta_j' x (x - p_j), assembled in O(N^2) from tail sums.
Eigen::MatrixXd chain_mass_matrix(const std::vector<LinkInertia>& links, const std::vector<Eigen::Vector3d>& nodes_B);

/// Size of u(t): acceleration of the base minus gravity (3), angular acceleration (3), the six independent
/// entries of Omega Omega^T (xx, yy, zz, xy, xz, yz), all in B, SI.
inline constexpr int base_input_size = 12;

/// The rigid motion of the base at one instant, world frame.
struct BaseMotion {
  Eigen::Matrix3d R_WB = Eigen::Matrix3d::Identity();
  Eigen::Vector3d p_W_base = Eigen::Vector3d::Zero();        ///< [m]
  Eigen::Vector3d velocity_W = Eigen::Vector3d::Zero();      ///< of the base point [m/s]
  Eigen::Vector3d acceleration_W = Eigen::Vector3d::Zero();  ///< of the base point [m/s^2]
  Eigen::Vector3d omega_W = Eigen::Vector3d::Zero();         ///< angular velocity [rad/s]
  Eigen::Vector3d alpha_W = Eigen::Vector3d::Zero();         ///< angular acceleration [rad/s^2]
};

/// u(t) of a base motion with gravity (see base_input_size).
Eigen::Matrix<double, base_input_size, 1> base_input(const BaseMotion& motion, const Eigen::Vector3d& gravity_W);

/// The linearised chain: q = (theta_0, ..., theta_{N-1}), 3N coordinates.
struct LinearModel {
  Eigen::MatrixXd mass;        ///< M, 3N x 3N, symmetric positive definite [kg m^2]
  Eigen::MatrixXd stiffness;   ///< K, block diagonal [N m / rad]
  double damping_time = 0.0;   ///< beta [s]: C = beta K
  Eigen::MatrixXd input;       ///< G, 3N x 12: generalised force of the base motion u (see base_input_size)
  /// Wrench the whisker transmits to the follicle (force, then moment about the base point; B axes) is
  /// base_from_input u + base_from_acceleration q'' (6 x 12 and 6 x 3N): Sum m (g - a) and its moment, minus
  /// the links' rate of angular momentum.
  Eigen::MatrixXd base_from_input, base_from_acceleration;
  /// Displacement of every node in B for q: node_displacement * q (3(N+1) x 3N, node-major).
  Eigen::MatrixXd node_displacement;
  std::vector<LinkInertia> links;
  [[nodiscard]] int size() const { return static_cast<int>(mass.rows()); }
};

/// Builds the model (second-order scheme only: the paper scheme's chain is re-meshed for each load and has no
/// fixed joints). Throws std::invalid_argument for the paper scheme or invalid properties. With
/// damping_ratio, beta = 2 zeta_1 / omega_1 needs the first natural frequency: it is computed here.
LinearModel linear_model(const Whisker& whisker, const DynamicsProperties& props);

}  // namespace vibrissa::dynamics
