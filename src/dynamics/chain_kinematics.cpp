// Exact kinematics of the chain in joint coordinates (include/vibrissa/dynamics/chain_kinematics.hpp).
#include "vibrissa/dynamics/chain_kinematics.hpp"
#include "vibrissa/dynamics/skew.hpp"

#include <cmath>

namespace vibrissa::dynamics {
namespace {

/// a = sin t / t, b = (1 - cos t) / t^2, c = (t - sin t) / t^3, smooth at t = 0: Taylor series below t = 0.1,
/// where the first omitted terms (t^10 / 11!, t^10 / 12!, t^10 / 13!) are below 3e-18.
void coefficients(double t2, double& a, double& b, double& c) {
  if (t2 < 1e-2) {
    a = 1.0 - t2 / 6.0 * (1.0 - t2 / 20.0 * (1.0 - t2 / 42.0 * (1.0 - t2 / 72.0)));
    b = 0.5 * (1.0 - t2 / 12.0 * (1.0 - t2 / 30.0 * (1.0 - t2 / 56.0 * (1.0 - t2 / 90.0))));
    c = (1.0 - t2 / 20.0 * (1.0 - t2 / 42.0 * (1.0 - t2 / 72.0 * (1.0 - t2 / 110.0)))) / 6.0;
    return;
  }
  const double t = std::sqrt(t2), s = std::sin(t);
  a = s / t;
  b = (1.0 - std::cos(t)) / t2;
  c = (t - s) / (t2 * t);
}

}  // namespace

Eigen::Matrix3d rotation_from_vector(const Eigen::Vector3d& theta) {
  double a, b, c;
  coefficients(theta.squaredNorm(), a, b, c);
  const Eigen::Matrix3d K = skew(theta);
  return Eigen::Matrix3d::Identity() + a * K + b * K * K;
}

Eigen::Matrix3d left_jacobian(const Eigen::Vector3d& theta) {
  double a, b, c;
  coefficients(theta.squaredNorm(), a, b, c);
  const Eigen::Matrix3d K = skew(theta);
  return Eigen::Matrix3d::Identity() + b * K + c * K * K;
}

void chain_kinematics(const Whisker& w, const Eigen::VectorXd& q, ChainKinematics& out) {
  const std::size_t N = static_cast<std::size_t>(w.links());
  out.nodes_B.resize(N + 1);
  out.joint_axes_B.resize(N);
  const auto& link = w.rest_link_vectors_B();
  out.nodes_B[0] = w.rest_nodes_B()[0];
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();  // R_{j-1}
  for (std::size_t j = 0; j < N; ++j) {
    const Eigen::Vector3d theta = q.segment<3>(static_cast<Eigen::Index>(3 * j));
    double a, b, c;
    coefficients(theta.squaredNorm(), a, b, c);
    const Eigen::Matrix3d K = skew(theta), K2 = K * K;
    out.joint_axes_B[j] = R * (Eigen::Matrix3d::Identity() + b * K + c * K2);
    R = R * (Eigen::Matrix3d::Identity() + a * K + b * K2);
    out.nodes_B[j + 1] = out.nodes_B[j] + R * link[j];
  }
}

void add_generalized_force(const ChainKinematics& k, int link, const Eigen::Vector3d& x_B, const Eigen::Vector3d& F_B,
                           Eigen::Ref<Eigen::VectorXd> Q) {
  for (int j = 0; j <= link; ++j) {
    const std::size_t u = static_cast<std::size_t>(j);
    Q.segment<3>(3 * j) += k.joint_axes_B[u].transpose() * (x_B - k.nodes_B[u]).cross(F_B);
  }
}

Eigen::MatrixXd point_jacobian(const ChainKinematics& k, int link, const Eigen::Vector3d& x_B) {
  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(3, static_cast<Eigen::Index>(3 * k.joint_axes_B.size()));
  for (int j = 0; j <= link; ++j) {
    const std::size_t u = static_cast<std::size_t>(j);
    J.block<3, 3>(0, 3 * j) = -skew(x_B - k.nodes_B[u]) * k.joint_axes_B[u];
  }
  return J;
}

}  // namespace vibrissa::dynamics
