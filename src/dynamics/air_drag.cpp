// Air drag on the links (include/vibrissa/dynamics/air_drag.hpp).
#include "vibrissa/dynamics/air_drag.hpp"

#include <array>
#include <cmath>
#include <memory>
#include <stdexcept>
#include <vector>

#include "vibrissa/core/checks.hpp"

namespace vibrissa::dynamics {

double cylinder_drag_coefficient(double re) {
  if (!(std::isfinite(re) && re > 0.0))
    throw std::invalid_argument("Reynolds number must be positive and finite, got " + format_value(re));
  return 1.0 + 10.0 / std::cbrt(re * re);
}

namespace {

/// One quadrature point of a link: rest position in B, tangent, diameter, weight x length.
struct DragPoint {
  Eigen::Vector3d x, e;
  double diameter = 0.0, length = 0.0;
  std::size_t link = 0;
};

}  // namespace

ExternalLoad air_drag_load(const Whisker& w, const BaseTrajectory& base, const AirProperties& air) {
  DynamicsProperties check;
  check.air = air;
  validate(check);
  const double g = std::sqrt(0.6);
  const std::array<double, 3> xi{0.5 * (1.0 - g), 0.5, 0.5 * (1.0 + g)};
  const std::array<double, 3> wt{5.0 / 18.0, 8.0 / 18.0, 5.0 / 18.0};
  const std::size_t N = static_cast<std::size_t>(w.links());
  auto points = std::make_shared<std::vector<DragPoint>>();
  for (std::size_t i = 0; i < N; ++i)
    for (std::size_t q = 0; q < 3; ++q) {
      const double l = w.link_lengths()[i];
      const double r = w.node_radii()[i] + (w.node_radii()[i + 1] - w.node_radii()[i]) * xi[q];
      const Eigen::Vector3d e = w.rest_link_frames_B()[i].col(0);
      points->push_back({w.rest_nodes_B()[i] + xi[q] * l * e, e, 2.0 * r, wt[q] * l, i});
    }
  const std::vector<Eigen::Vector3d> nodes = w.rest_nodes_B();
  return [points, nodes, base, air, N](double t, Eigen::VectorXd& Q, Eigen::Matrix<double, 6, 1>& wrench) {
    const BaseMotion b = base(t);
    const Eigen::Matrix3d RT = b.R_WB.transpose();
    const Eigen::Vector3d v0 = RT * b.velocity_W, om = RT * b.omega_W;
    std::vector<Eigen::Vector3d> F(N, Eigen::Vector3d::Zero()), Mo(N, Eigen::Vector3d::Zero());
    for (const DragPoint& p : *points) {
      const Eigen::Vector3d v = v0 + om.cross(p.x);
      const Eigen::Vector3d vn = v - v.dot(p.e) * p.e;
      const double speed = vn.norm();
      if (!(speed > 0.0)) continue;
      const double cd = cylinder_drag_coefficient(speed * p.diameter / air.kinematic_viscosity);
      const Eigen::Vector3d f = (-0.5 * air.density * cd * p.diameter * speed * p.length) * vn;
      F[p.link] += f;
      Mo[p.link] += p.x.cross(f);
    }
    // Tail sums: joint j carries the drag of every link i >= j, about node j.
    Eigen::Vector3d tailF = Eigen::Vector3d::Zero(), tailM = Eigen::Vector3d::Zero();
    for (std::size_t j = N; j-- > 0;) {
      tailF += F[j];
      tailM += Mo[j];
      Q.segment<3>(static_cast<Eigen::Index>(3 * j)) += tailM - nodes[j].cross(tailF);
    }
    wrench.head<3>() += tailF;
    wrench.tail<3>() += tailM - nodes[0].cross(tailF);
  };
}

}  // namespace vibrissa::dynamics
