#pragma once
// Exact kinematics of the chain in joint coordinates (docs/dynamics.md, "Large deflection"): q = (theta_0 ...
// theta_{N-1}), the joint rotation vectors in B's rest axes, composed as the quasi-static walk composes them
// (core/chain.hpp): link i turns by R_i = exp([theta_0]x) ... exp([theta_i]x), node i+1 = node i + R_i l_i (l_i the
// rest link vector in B). A change d theta_j turns every link distal to joint j by the rotation vector
// A_j d theta_j about node j, A_j = R_{j-1} J_l(theta_j) (J_l the left Jacobian of the exponential map of SO(3)),
// so the Jacobian of a point x on link i is dx/dtheta_j = -[x - p_j]x A_j for j <= i, zero beyond.
#include <vector>

#include <Eigen/Core>

#include "vibrissa/core/whisker.hpp"

namespace vibrissa::dynamics {

struct ChainKinematics {
  std::vector<Eigen::Vector3d> nodes_B;       ///< N+1 deflected nodes [m]
  std::vector<Eigen::Matrix3d> joint_axes_B;  ///< A_j, N of them
};

/// Fills `out` for q (size 3N; reuses its storage).
void chain_kinematics(const Whisker& whisker, const Eigen::VectorXd& q, ChainKinematics& out);

/// Left Jacobian of the exponential map: d exp([theta + d]x) = [J_l(theta) d]x exp([theta]x) to first order.
Eigen::Matrix3d left_jacobian(const Eigen::Vector3d& theta);
/// exp([theta]x) (Rodrigues).
Eigen::Matrix3d rotation_from_vector(const Eigen::Vector3d& theta);

/// J^T F: the generalised force (3N) of a force F_B applied at x_B on link `link` (joints beyond it get zero).
void add_generalized_force(const ChainKinematics& k, int link, const Eigen::Vector3d& x_B, const Eigen::Vector3d& F_B,
                           Eigen::Ref<Eigen::VectorXd> Q);
/// The Jacobian J (3 x 3N) of the point x_B on link `link`.
Eigen::MatrixXd point_jacobian(const ChainKinematics& k, int link, const Eigen::Vector3d& x_B);

}  // namespace vibrissa::dynamics
