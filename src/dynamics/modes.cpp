// Natural modes of the linearised chain (include/vibrissa/dynamics/modes.hpp).
#include "vibrissa/dynamics/modes.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include <Eigen/Eigenvalues>

namespace vibrissa::dynamics {

namespace detail {
void orient_and_scale_shapes(Modes& out) {
  const Eigen::Index nodes = out.node_shapes.rows() / 3;
  for (Eigen::Index i = 0; i < out.node_shapes.cols(); ++i) {
    // Fix the sign: the largest node displacement component positive.
    Eigen::Index big = 0;
    out.node_shapes.col(i).cwiseAbs().maxCoeff(&big);
    if (out.node_shapes(big, i) < 0.0) {
      out.node_shapes.col(i) *= -1.0;
      out.joint_shapes.col(i) *= -1.0;
    }
    double largest = 0.0;
    for (Eigen::Index k = 0; k < nodes; ++k) largest = std::max(largest, out.node_shapes.col(i).segment<3>(3 * k).norm());
    if (largest > 0.0) out.node_shapes.col(i) /= largest;
  }
}
}  // namespace detail

Modes modes(const LinearModel& model, const Whisker& w, int count) {
  const int n = model.size();
  const int m = count <= 0 ? n : std::min(count, n);
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> eig(model.stiffness, model.mass);
  if (eig.info() != Eigen::Success)
    throw std::runtime_error("dynamics: the eigenproblem K v = omega^2 M v of the linearised chain did not converge");
  Modes out;
  out.damping_time = model.damping_time;
  out.omega = eig.eigenvalues().head(m).cwiseMax(0.0).cwiseSqrt();
  out.frequency_hz = out.omega / (2.0 * std::numbers::pi);
  out.damping_ratio = 0.5 * model.damping_time * out.omega;
  out.damped_frequency_hz.resize(m);
  for (int i = 0; i < m; ++i) {
    const double z = out.damping_ratio(i);
    out.damped_frequency_hz(i) = z < 1.0 ? out.frequency_hz(i) * std::sqrt(1.0 - z * z) : 0.0;
  }
  out.joint_shapes = eig.eigenvectors().leftCols(m);  // v^T M v = 1 (Eigen's normalisation for A x = l B x)
  out.node_shapes = model.node_displacement * out.joint_shapes;
  detail::orient_and_scale_shapes(out);
  out.torsion_fraction.resize(m);
  const std::size_t N = static_cast<std::size_t>(w.links());
  for (int i = 0; i < m; ++i) {
    // Twist energy: with the joint moment m = K theta, (t . m)^2 w / (G J) / 2 about the joint's mid tangent t.
    double twist = 0.0;
    for (std::size_t j = 0; j < N; ++j) {
      const Eigen::Index r = static_cast<Eigen::Index>(3 * j);
      const Eigen::Vector3d moment = model.stiffness.block<3, 3>(r, r) * out.joint_shapes.col(i).segment<3>(r);
      Eigen::Vector3d t = w.rest_link_frames_B()[j].col(0);
      if (j > 0) t = (t + w.rest_link_frames_B()[j - 1].col(0)).normalized();
      const double tm = t.dot(moment);
      twist += 0.5 * tm * tm * w.joint_weight()[j] * w.torsion_compliance()[j];
    }
    const double total = 0.5 * eig.eigenvalues()(i);  // v^T K v / 2 with v^T M v = 1
    out.torsion_fraction(i) = total > 0.0 ? std::clamp(twist / total, 0.0, 1.0) : 0.0;
  }
  return out;
}

Modes modes(const Whisker& w, const DynamicsProperties& props, int count) {
  return modes(linear_model(w, props), w, count);
}

}  // namespace vibrissa::dynamics
