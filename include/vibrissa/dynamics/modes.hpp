#pragma once
// Natural vibration modes of the chain about its rest shape (docs/dynamics.md): K v = omega^2 M v with the
// linearised model (linear_model.hpp), mass-normalised (v^T M v = 1). With the stiffness-proportional joint
// dampers every mode keeps its shape and has the damping ratio zeta_n = beta omega_n / 2.
#include <vector>

#include <Eigen/Core>

#include "vibrissa/dynamics/linear_model.hpp"

namespace vibrissa::dynamics {

struct Modes {
  Eigen::VectorXd omega;          ///< undamped natural angular frequencies, ascending [rad/s]
  Eigen::VectorXd frequency_hz;   ///< omega / 2 pi [Hz]
  Eigen::VectorXd damped_frequency_hz;  ///< omega sqrt(1 - zeta^2) / 2 pi (0 when overdamped) [Hz]
  Eigen::VectorXd damping_ratio;  ///< zeta_n = beta omega_n / 2
  /// Fraction of each mode's elastic energy in twist about the link axes (near 0: bending, near 1: torsion).
  Eigen::VectorXd torsion_fraction;
  Eigen::MatrixXd joint_shapes;   ///< 3N x m joint rotations, v^T M v = 1
  /// 3(N+1) x m node displacements in B (node-major), each column scaled to a largest node displacement of 1.
  Eigen::MatrixXd node_shapes;
  double damping_time = 0.0;      ///< beta [s]
  [[nodiscard]] int count() const { return static_cast<int>(omega.size()); }
};

namespace detail {
/// Signs (largest node displacement component positive, joint shapes alike) and node shapes scaled to a largest
/// node displacement of 1.
void orient_and_scale_shapes(Modes& modes);
}  // namespace detail

/// The `count` lowest modes (all 3N when count <= 0 or larger than 3N).
Modes modes(const LinearModel& model, const Whisker& whisker, int count = 0);
Modes modes(const Whisker& whisker, const DynamicsProperties& props, int count = 0);

}  // namespace vibrissa::dynamics
