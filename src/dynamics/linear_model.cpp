// Inertia, damping and the linearised equations of motion (include/vibrissa/dynamics/linear_model.hpp).
#include "vibrissa/dynamics/linear_model.hpp"
#include "vibrissa/dynamics/skew.hpp"

#include <array>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/LU>

#include "vibrissa/core/checks.hpp"
#include "vibrissa/core/limits.hpp"

namespace vibrissa::dynamics {
namespace {

Eigen::Index at(std::size_t j) { return static_cast<Eigen::Index>(3 * j); }

/// The base motion u as its three parts (linear_model.hpp, base_input_size).
struct InputParts {
  Eigen::Vector3d a, alpha;
  Eigen::Matrix3d S;  // Omega Omega^T
};

InputParts parts(const Eigen::Matrix<double, base_input_size, 1>& u) {
  InputParts p;
  p.a = u.segment<3>(0);
  p.alpha = u.segment<3>(3);
  p.S << u(6), u(9), u(10), u(9), u(7), u(11), u(10), u(11), u(8);
  return p;
}

/// Inertial load on a link (force at its centroid and couple) of the base motion at rest: -m a_c, and
/// -(I alpha + Omega x I Omega) with Omega x (I Omega) written in S = Omega Omega^T.
void link_load(const LinkInertia& L, const InputParts& u, Eigen::Vector3d& f, Eigen::Vector3d& n) {
  const Eigen::Vector3d& c = L.centroid_B;
  f = -L.mass * (u.a + u.alpha.cross(c) + u.S * c - u.S.trace() * c);
  const Eigen::Matrix3d P = L.inertia_B * u.S;
  const Eigen::Vector3d gyro(P(2, 1) - P(1, 2), P(0, 2) - P(2, 0), P(1, 0) - P(0, 1));
  n = -(L.inertia_B * u.alpha + gyro);
}

}  // namespace

void validate(const DynamicsProperties& p) {
  // Upper bounds far beyond anything physical (every solid is below 2.3e4 kg/m^3; follicle damping ratios are
  // ~0.1-0.3), so that a typing error is refused instead of overflowing the damping or mass matrices (a damping
  // ratio of 1e308 made the integrator run without end).
  constexpr double max_density = 1e5, max_damping = 1e6;
  if (!(p.density > 0.0 && p.density <= max_density))
    throw std::invalid_argument("dynamics.density must lie in (0, 1e5] [kg/m^3], got " + format_value(p.density));
  if (!(p.damping_ratio >= 0.0 && p.damping_ratio <= max_damping))
    throw std::invalid_argument("dynamics.damping_ratio must lie in [0, 1e6], got " + format_value(p.damping_ratio));
  if (p.joint_damping_time && !(*p.joint_damping_time >= 0.0 && *p.joint_damping_time <= max_damping))
    throw std::invalid_argument("dynamics.joint_damping_time must lie in [0, 1e6] [s], got " +
                                format_value(*p.joint_damping_time));
  if (!(std::isfinite(p.air.density) && p.air.density > 0.0))
    throw std::invalid_argument("dynamics.air_density must be positive and finite [kg/m^3], got " +
                                format_value(p.air.density));
  if (!(std::isfinite(p.air.kinematic_viscosity) && p.air.kinematic_viscosity > 0.0))
    throw std::invalid_argument("dynamics.air_kinematic_viscosity must be positive and finite [m^2/s], got " +
                                format_value(p.air.kinematic_viscosity));
  if (!p.gravity_W.allFinite())
    throw std::invalid_argument("dynamics.gravity must be finite [m/s^2], got " + format_value(p.gravity_W));
}

std::vector<LinkInertia> link_inertias(const Whisker& w, double density) {
  // 3-point Gauss-Legendre on [0, 1]: exact to degree 5 (the integrands are of degree <= 4 in the chord).
  const double g = std::sqrt(0.6);
  const std::array<double, 3> xi{0.5 * (1.0 - g), 0.5, 0.5 * (1.0 + g)};
  const std::array<double, 3> wt{5.0 / 18.0, 8.0 / 18.0, 5.0 / 18.0};
  const auto& radius = w.node_radii();
  std::vector<LinkInertia> out(static_cast<std::size_t>(w.links()));
  for (std::size_t i = 0; i < out.size(); ++i) {
    const double l = w.link_lengths()[i], ra = radius[i], rb = radius[i + 1];
    double m = 0.0, first = 0.0, second = 0.0, r4 = 0.0;  // integrals of r^2, r^2 x, r^2 x^2, r^4 over [0, l]
    for (std::size_t q = 0; q < 3; ++q) {
      const double x = xi[q] * l, r = ra + (rb - ra) * xi[q], r2 = r * r;
      m += wt[q] * l * r2;
      first += wt[q] * l * r2 * x;
      second += wt[q] * l * r2 * x * x;
      r4 += wt[q] * l * r2 * r2;
    }
    const double rho_pi = density * std::numbers::pi;
    LinkInertia& L = out[i];
    L.mass = rho_pi * m;
    const double xc = first / m;
    const Eigen::Vector3d e = w.rest_link_frames_B()[i].col(0);
    L.centroid_B = w.rest_nodes_B()[i] + xc * e;
    const double axial = 0.5 * rho_pi * r4;                              // rho pi r^4 / 2 per length
    const double transverse = rho_pi * (0.25 * r4 + second) - L.mass * xc * xc;  // about the centroid
    L.inertia_B = axial * e * e.transpose() + transverse * (Eigen::Matrix3d::Identity() - e * e.transpose());
  }
  return out;
}

Eigen::Matrix<double, base_input_size, 1> base_input(const BaseMotion& m, const Eigen::Vector3d& gravity_W) {
  const Eigen::Matrix3d RT = m.R_WB.transpose();
  const Eigen::Vector3d a = RT * (m.acceleration_W - gravity_W), alpha = RT * m.alpha_W, w = RT * m.omega_W;
  Eigen::Matrix<double, base_input_size, 1> u;
  u << a, alpha, w.x() * w.x(), w.y() * w.y(), w.z() * w.z(), w.x() * w.y(), w.x() * w.z(), w.y() * w.z();
  return u;
}

Eigen::MatrixXd chain_mass_matrix(const std::vector<LinkInertia>& links, const std::vector<Eigen::Vector3d>& p) {
  // Tail sums over links i >= k (j <= k): sum_i m_i skew(c_i - p_j)^T skew(c_i - p_k) + I_i
  // = tr(X) 1 - X + sum I_i with X = sum_i m_i (c_i - p_k)(c_i - p_j)^T.
  const std::size_t N = links.size();
  Eigen::MatrixXd mass = Eigen::MatrixXd::Zero(at(N), at(N));
  double S0 = 0.0;
  Eigen::Vector3d S1 = Eigen::Vector3d::Zero();
  Eigen::Matrix3d T = Eigen::Matrix3d::Zero(), Itail = Eigen::Matrix3d::Zero();
  for (std::size_t k = N; k-- > 0;) {
    const LinkInertia& L = links[k];
    S0 += L.mass;
    S1 += L.mass * L.centroid_B;
    T += L.mass * L.centroid_B * L.centroid_B.transpose();
    Itail += L.inertia_B;
    for (std::size_t j = 0; j <= k; ++j) {
      const Eigen::Matrix3d X = T - S1 * p[j].transpose() - p[k] * S1.transpose() + S0 * p[k] * p[j].transpose();
      const Eigen::Matrix3d B = X.trace() * Eigen::Matrix3d::Identity() - X + Itail;
      mass.block<3, 3>(at(j), at(k)) = B;
      if (j != k) mass.block<3, 3>(at(k), at(j)) = B.transpose();
    }
  }
  return 0.5 * (mass + mass.transpose());
}

LinearModel linear_model(const Whisker& w, const DynamicsProperties& props) {
  validate(props);
  if (w.properties().scheme != Scheme::second_order)
    throw std::invalid_argument(
        "whisker.scheme must be \"second_order\" for dynamics (the paper scheme re-meshes its chain for each "
        "load), got \"paper\"");
  if (w.links() > limits::max_dynamics_links)
    throw std::invalid_argument("whisker.links must be at most " + std::to_string(limits::max_dynamics_links) +
                                " for dynamics (dense 3N x 3N mass matrix and modes), got " + std::to_string(w.links()));
  const std::size_t N = static_cast<std::size_t>(w.links());
  const Eigen::Index n = at(N);
  LinearModel model;
  model.links = link_inertias(w, props.density);
  const auto& links = model.links;
  const auto& p = w.rest_nodes_B();

  // Stiffness: inverse of each joint's compliance to a distal load (eqs. (1)-(3)), follicle spring in series.
  model.stiffness = Eigen::MatrixXd::Zero(n, n);
  for (std::size_t j = 0; j < N; ++j) {
    Eigen::Matrix3d C = w.weighted_joint_compliance_B()[j];
    if (j == 0 && w.base_extra_compliance() > 0.0) {
      const Eigen::Vector3d e = w.rest_link_frames_B()[0].col(0);
      C += w.base_extra_compliance() * (Eigen::Matrix3d::Identity() - e * e.transpose());
    }
    const Eigen::Matrix3d K = C.inverse();
    model.stiffness.block<3, 3>(at(j), at(j)) = 0.5 * (K + K.transpose());
  }

  model.mass = chain_mass_matrix(links, p);

  // Base motion: generalised forces and the follicle's wrench for each unit input.
  model.input.resize(n, base_input_size);
  model.base_from_input.resize(6, base_input_size);
  for (int c = 0; c < base_input_size; ++c) {
    Eigen::Matrix<double, base_input_size, 1> e = Eigen::Matrix<double, base_input_size, 1>::Zero();
    e(c) = 1.0;
    const InputParts u = parts(e);
    Eigen::Vector3d F = Eigen::Vector3d::Zero(), Mo = Eigen::Vector3d::Zero();  // tail sums, moment about B's origin
    for (std::size_t j = N; j-- > 0;) {
      Eigen::Vector3d f, nn;
      link_load(links[j], u, f, nn);
      F += f;
      Mo += links[j].centroid_B.cross(f) + nn;
      model.input.block<3, 1>(at(j), c) = Mo - p[j].cross(F);
    }
    model.base_from_input.block<3, 1>(0, c) = F;
    model.base_from_input.block<3, 1>(3, c) = Mo - p[0].cross(F);
  }
  model.base_from_acceleration.resize(6, n);
  for (std::size_t j = 0; j < N; ++j)
    for (int a = 0; a < 3; ++a) {
      const Eigen::Vector3d axis = Eigen::Vector3d::Unit(a);
      Eigen::Vector3d F = Eigen::Vector3d::Zero(), Mo = Eigen::Vector3d::Zero();
      for (std::size_t i = j; i < N; ++i) {
        const Eigen::Vector3d f = -links[i].mass * axis.cross(links[i].centroid_B - p[j]);
        F += f;
        Mo += (links[i].centroid_B - p[0]).cross(f) - links[i].inertia_B * axis;
      }
      model.base_from_acceleration.block<3, 1>(0, at(j) + a) = F;
      model.base_from_acceleration.block<3, 1>(3, at(j) + a) = Mo;
    }

  // Node displacements: node k moves by sum_{j < k} theta_j x (x_k - p_j).
  model.node_displacement = Eigen::MatrixXd::Zero(at(N + 1), n);
  for (std::size_t k = 1; k <= N; ++k)
    for (std::size_t j = 0; j < k; ++j) model.node_displacement.block<3, 3>(at(k), at(j)) = -skew(p[k] - p[j]);

  if (props.joint_damping_time) {
    model.damping_time = *props.joint_damping_time;
  } else if (props.damping_ratio > 0.0) {
    const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> eig(model.stiffness, model.mass,
                                                                        Eigen::EigenvaluesOnly);
    if (eig.info() != Eigen::Success)
      throw std::runtime_error("dynamics: the eigenvalues of the linearised chain did not converge");
    model.damping_time = 2.0 * props.damping_ratio / std::sqrt(eig.eigenvalues()(0));
  }
  return model;
}

}  // namespace vibrissa::dynamics
