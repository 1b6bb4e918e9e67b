// Modes about a deflected equilibrium (include/vibrissa/dynamics/deflected_modes.hpp, docs/dynamics.md).
#include "vibrissa/dynamics/deflected_modes.hpp"
#include "vibrissa/dynamics/skew.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <Eigen/QR>

#include "vibrissa/core/checks.hpp"
#include "vibrissa/core/rodrigues.hpp"

namespace vibrissa::dynamics {
namespace {

Eigen::Index at(std::size_t j) { return static_cast<Eigen::Index>(3 * j); }

Eigen::Matrix3d exp_so3(const Eigen::Vector3d& w) {
  double a = 0.0, b = 0.0;
  vibrissa::detail::rodrigues_coefficients(w.squaredNorm(), a, b);
  const Eigen::Matrix3d W = skew(w);
  return Eigen::Matrix3d::Identity() + a * W + b * W * W;
}

/// Rotation vector of a rotation matrix, accurate for small angles (from the skew part, not the trace alone).
Eigen::Vector3d log_so3(const Eigen::Matrix3d& R) {
  const Eigen::Vector3d v = 0.5 * Eigen::Vector3d(R(2, 1) - R(1, 2), R(0, 2) - R(2, 0), R(1, 0) - R(0, 1));
  const double s = v.norm(), c = 0.5 * (R.trace() - 1.0);
  const double t = std::atan2(s, c);
  if (s < 1e-300) return Eigen::Vector3d::Zero();
  return (t / s) * v;
}

/// Left Jacobian of the exponential map: exp(w + dw) = exp(J_l(w) dw) exp(w) to first order.
Eigen::Matrix3d left_jacobian(const Eigen::Vector3d& w) {
  const double t2 = w.squaredNorm();
  double a = 0.0, b = 0.0;
  vibrissa::detail::rodrigues_coefficients(t2, a, b);
  const double c = vibrissa::detail::right_jacobian_coefficient(t2, a);
  const Eigen::Matrix3d W = skew(w);
  return Eigen::Matrix3d::Identity() + b * W + c * W * W;
}

/// The joint law of joint j (chain.hpp: omega = Kw (m + (Kw m) x m / 2), the follicle spring in series at joint
/// 0), its inverse m(omega) and the derivative d omega / d m there.
struct JointLaw {
  Eigen::Matrix3d C, base;  // weighted compliance (rest axes), follicle compliance (bending part)
  JointLaw(const Whisker& w, std::size_t j) : C(w.weighted_joint_compliance_B()[j]), base(Eigen::Matrix3d::Zero()) {
    if (j == 0 && w.base_extra_compliance() > 0.0) {
      const Eigen::Vector3d e = w.rest_link_frames_B()[0].col(0);
      base = w.base_extra_compliance() * (Eigen::Matrix3d::Identity() - e * e.transpose());
    }
  }
  [[nodiscard]] Eigen::Vector3d rotation(const Eigen::Vector3d& m) const {
    return C * (m + 0.5 * (C * m).cross(m)) + base * m;
  }
  [[nodiscard]] Eigen::Matrix3d derivative(const Eigen::Vector3d& m) const {
    return C * (Eigen::Matrix3d::Identity() + 0.5 * (skew(C * m) - skew(m) * C)) + base;
  }
  [[nodiscard]] Eigen::Vector3d moment(const Eigen::Vector3d& omega) const {
    Eigen::Vector3d m = (C + base).inverse() * omega;
    for (int it = 0; it < 30; ++it) {
      const Eigen::Vector3d r = rotation(m) - omega;
      if (r.norm() <= 1e-15 * omega.norm()) break;
      m -= derivative(m).inverse() * r;
    }
    return m;
  }
};

/// The chain at a configuration: proximal and distal rotations of every joint, nodes, the load's point.
struct Chain {
  std::vector<Eigen::Matrix3d> R_pre, R_dist;
  std::vector<Eigen::Vector3d> nodes;
  int k = 0;  // loaded link
  Eigen::Vector3d contact = Eigen::Vector3d::Zero();
  Chain(const Whisker& w, const JointRotations& omega, double s) {
    const std::size_t N = static_cast<std::size_t>(w.links());
    if (omega.size() != N)
      throw std::invalid_argument("joint rotations: expected " + std::to_string(N) + ", got " +
                                  std::to_string(omega.size()));
    R_pre.resize(N);
    R_dist.resize(N);
    nodes.resize(N + 1);
    nodes[0] = w.rest_nodes_B()[0];
    Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
    for (std::size_t j = 0; j < N; ++j) {
      R_pre[j] = R;
      R = R * exp_so3(omega[j]);
      R_dist[j] = R;
      nodes[j + 1] = nodes[j] + R * w.rest_link_vectors_B()[j];
    }
    double h = 0.0;
    w.locate(s, k, h);
    const std::size_t uk = static_cast<std::size_t>(k);
    contact = nodes[uk] + R_dist[uk] * (h * w.rest_link_frames_B()[uk].col(0));
  }
};

void check_arc_length(const Whisker& w, double s) {
  if (!(std::isfinite(s) && s >= 0.0 && s <= w.length()))
    throw std::invalid_argument("load arc_length must lie on the whisker, 0 ... " + format_value(w.length()) +
                                " m, got " + format_value(s));
}

/// d x_contact / d theta (3 x 3N).
Eigen::MatrixXd contact_jacobian(const Chain& c, std::size_t N) {
  Eigen::MatrixXd G = Eigen::MatrixXd::Zero(3, at(N));
  for (std::size_t i = 0; i <= static_cast<std::size_t>(c.k); ++i) G.block<3, 3>(0, at(i)) = -skew(c.contact - c.nodes[i]);
  return G;
}

/// -d residual / d F (3N x 3): the load's moment arms.
Eigen::MatrixXd force_jacobian(const Chain& c, std::size_t N) {
  Eigen::MatrixXd B = Eigen::MatrixXd::Zero(at(N), 3);
  for (std::size_t j = 0; j <= static_cast<std::size_t>(c.k); ++j) B.block<3, 3>(at(j), 0) = skew(c.contact - c.nodes[j]);
  return B;
}

double residual_scale(const Whisker& w, const Chain& c, const Eigen::Vector3d& F) {
  // The load's moment about the base, or (no load) the moment that turns the first joint by 1e-6 rad.
  const double load = (c.contact - c.nodes[0]).cross(F).norm();
  return std::max(load, 1e-6 / w.weighted_joint_compliance_B()[0].norm());
}

}  // namespace

std::string_view to_string(ContactModel m) {
  switch (m) {
    case ContactModel::none: return "none";
    case ContactModel::stick: return "stick";
    case ContactModel::slip: return "slip";
  }
  return "unknown";
}

std::vector<Eigen::Vector3d> chain_nodes_B(const Whisker& w, const JointRotations& omega) {
  return Chain(w, omega, 0.0).nodes;
}

JointRotations apply_increments(const JointRotations& omega, const Eigen::VectorXd& dtheta) {
  JointRotations out(omega.size());
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  for (std::size_t j = 0; j < omega.size(); ++j) {
    const Eigen::Matrix3d Q = exp_so3(omega[j]);
    out[j] = log_so3(exp_so3(R.transpose() * dtheta.segment<3>(at(j))) * Q);
    R = R * Q;
  }
  return out;
}

Eigen::VectorXd equilibrium_residual(const Whisker& w, const JointRotations& omega, const Eigen::Vector3d& F,
                                     double s) {
  check_arc_length(w, s);
  const Chain c(w, omega, s);
  const std::size_t N = omega.size();
  Eigen::VectorXd g(at(N));
  for (std::size_t j = 0; j < N; ++j) {
    Eigen::Vector3d r = c.R_dist[j] * JointLaw(w, j).moment(omega[j]);
    if (j <= static_cast<std::size_t>(c.k)) r -= (c.contact - c.nodes[j]).cross(F);
    g.segment<3>(at(j)) = r;
  }
  return g;
}

Eigen::MatrixXd tangent_stiffness(const Whisker& w, const JointRotations& omega, const Eigen::Vector3d& F, double s,
                                  bool follower) {
  check_arc_length(w, s);
  const Chain c(w, omega, s);
  const std::size_t N = omega.size(), k = static_cast<std::size_t>(c.k);
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(at(N), at(N));
  const Eigen::Matrix3d SF = skew(F);
  for (std::size_t j = 0; j < N; ++j) {
    // Springs: the moment R_dist m turns with every proximal increment; joint j's own increment also changes
    // omega_j by J_l^-1 R_pre^T dtheta.
    const JointLaw law(w, j);
    const Eigen::Vector3d m = law.moment(omega[j]);
    const Eigen::Matrix3d turn = -skew(c.R_dist[j] * m);
    for (std::size_t i = 0; i < j; ++i) K.block<3, 3>(at(j), at(i)) = turn;
    K.block<3, 3>(at(j), at(j)) = turn + c.R_dist[j] * law.derivative(m).inverse() *
                                             left_jacobian(omega[j]).inverse() * c.R_pre[j].transpose();
    if (j > k) continue;
    // Load: L_j = (x_c - p_j) x F. An increment at i <= j turns x_c - p_j; at j < i <= k it moves x_c only;
    // a follower force turns with every increment at i <= k.
    const Eigen::Vector3d r = c.contact - c.nodes[j];
    const Eigen::Matrix3d follow = follower ? Eigen::Matrix3d(-skew(r) * SF) : Eigen::Matrix3d::Zero();
    for (std::size_t i = 0; i <= k; ++i) {
      const Eigen::Vector3d arm = i <= j ? r : Eigen::Vector3d(c.contact - c.nodes[i]);
      K.block<3, 3>(at(j), at(i)) -= SF * skew(arm) + follow;
    }
  }
  return K;
}

HeldEquilibrium held_equilibrium(const Whisker& w, const HeldLoad& load, const JointRotations& start) {
  check_arc_length(w, load.arc_length);
  const std::size_t N = static_cast<std::size_t>(w.links());
  HeldEquilibrium eq;
  eq.omega = start.empty() ? JointRotations(N, Eigen::Vector3d::Zero()) : start;
  eq.force_B = load.force_B;
  const bool contact = load.contact != ContactModel::none;
  const Eigen::Vector3d target = load.contact_point_B.value_or(Chain(w, eq.omega, load.arc_length).contact);
  for (;; ++eq.iterations) {
    const Chain c(w, eq.omega, load.arc_length);
    const Eigen::VectorXd g = equilibrium_residual(w, eq.omega, eq.force_B, load.arc_length);
    const double scale = residual_scale(w, c, eq.force_B);
    const double gap = contact ? (c.contact - target).norm() / w.length() : 0.0;
    eq.residual = std::max(g.lpNorm<Eigen::Infinity>() / scale, gap);
    eq.contact_B = c.contact;
    if (eq.residual <= 1e-10) return eq;
    if (eq.iterations >= 50)
      throw std::runtime_error("held equilibrium: Newton's method did not converge in 50 iterations (relative "
                               "residual " + format_value(eq.residual) + ")");
    const Eigen::MatrixXd K = tangent_stiffness(w, eq.omega, eq.force_B, load.arc_length, load.follower && !contact);
    if (!contact) {
      eq.omega = apply_increments(eq.omega, K.partialPivLu().solve(-g));
      continue;
    }
    // Pinned material point: unknowns (dtheta, dF); the reaction is a dead force.
    const Eigen::Index n = at(N);
    Eigen::MatrixXd A = Eigen::MatrixXd::Zero(n + 3, n + 3);
    A.topLeftCorner(n, n) = K;
    A.topRightCorner(n, 3) = -force_jacobian(c, N);
    A.bottomLeftCorner(3, n) = contact_jacobian(c, N);
    Eigen::VectorXd rhs(n + 3);
    rhs << -g, target - c.contact;
    const Eigen::VectorXd d = A.partialPivLu().solve(rhs);
    eq.omega = apply_increments(eq.omega, d.head(n));
    eq.force_B += d.tail<3>();
  }
}

DeflectedModes deflected_modes(const Whisker& w, const DynamicsProperties& props, const HeldLoad& load,
                               const JointRotations& start, int count) {
  const LinearModel rest = linear_model(w, props);  // validates; beta and the links' mass properties
  const std::size_t N = static_cast<std::size_t>(w.links());
  const Eigen::Index n = at(N);
  DeflectedModes out;
  if (load.contact == ContactModel::slip && !(std::abs(load.normal_B.norm() - 1.0) < 1e-9))
    throw std::invalid_argument("slip contact: normal_B must be a unit vector, got " + format_value(load.normal_B));
  out.equilibrium = held_equilibrium(w, load, start);
  const HeldEquilibrium& eq = out.equilibrium;
  const Chain c(w, eq.omega, load.arc_length);
  const bool contact = load.contact != ContactModel::none;
  const Eigen::MatrixXd K = tangent_stiffness(w, eq.omega, eq.force_B, load.arc_length, load.follower && !contact);
  const Eigen::MatrixXd Ks = tangent_stiffness(w, eq.omega, Eigen::Vector3d::Zero(), load.arc_length, false);

  // Mass of the links where they are: centroids and inertias turned with their links.
  std::vector<LinkInertia> links = rest.links;
  for (std::size_t i = 0; i < N; ++i) {
    links[i].centroid_B = c.nodes[i] + c.R_dist[i] * (rest.links[i].centroid_B - w.rest_nodes_B()[i]);
    links[i].inertia_B = c.R_dist[i] * rest.links[i].inertia_B * c.R_dist[i].transpose();
  }
  const Eigen::MatrixXd M = chain_mass_matrix(links, c.nodes);

  // Constraint: stick holds the contact's material point, slip its motion along the normal. Z spans the rest.
  Eigen::MatrixXd Z = Eigen::MatrixXd::Identity(n, n);
  if (contact) {
    const Eigen::MatrixXd G3 = contact_jacobian(c, N);
    const Eigen::MatrixXd G = load.contact == ContactModel::stick ? G3 : Eigen::MatrixXd(load.normal_B.transpose() * G3);
    // Rank-revealing: a straight whisker's tip cannot move along its axis to first order (a zero row).
    Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(G.transpose());
    qr.setThreshold(1e-12);
    out.constraints = static_cast<int>(qr.rank());
    const Eigen::MatrixXd Q = qr.householderQ();
    Z = Q.rightCols(n - qr.rank());
  }
  const Eigen::MatrixXd Kr = Z.transpose() * K * Z, Mr = Z.transpose() * M * Z;
  out.asymmetry = (Kr - Kr.transpose()).norm() / Kr.norm();
  const Eigen::Index dim = Kr.rows();
  const Eigen::Index m = count <= 0 ? dim : std::min<Eigen::Index>(count, dim);
  Eigen::VectorXd lambda(m);
  Eigen::MatrixXd V(dim, m);
  if (out.asymmetry < 1e-9) {
    const Eigen::MatrixXd Ksym = 0.5 * (Kr + Kr.transpose());
    const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> eig(Ksym, Mr);
    if (eig.info() != Eigen::Success)
      throw std::runtime_error("dynamics: the eigenproblem K_T v = omega^2 M v about the equilibrium did not converge");
    lambda = eig.eigenvalues().head(m);
    V = eig.eigenvectors().leftCols(m);
  } else {
    // Not symmetric (a follower force): M = L L^T, eigenvalues of L^-1 K_T L^-T, real parts.
    const Eigen::LLT<Eigen::MatrixXd> llt(Mr);
    const Eigen::MatrixXd Li = llt.matrixL().solve(Eigen::MatrixXd::Identity(dim, dim));
    const Eigen::EigenSolver<Eigen::MatrixXd> eig(Li * Kr * Li.transpose());
    if (eig.info() != Eigen::Success)
      throw std::runtime_error("dynamics: the eigenproblem K_T v = lambda M v about the equilibrium did not converge");
    std::vector<Eigen::Index> order(static_cast<std::size_t>(dim));
    for (Eigen::Index i = 0; i < dim; ++i) order[static_cast<std::size_t>(i)] = i;
    const Eigen::VectorXcd ev = eig.eigenvalues();
    std::sort(order.begin(), order.end(), [&](Eigen::Index a, Eigen::Index b) { return ev(a).real() < ev(b).real(); });
    for (Eigen::Index i = 0; i < m; ++i) {
      const Eigen::Index o = order[static_cast<std::size_t>(i)];
      lambda(i) = ev(o).real();
      out.largest_imaginary = std::max(out.largest_imaginary, std::abs(ev(o).imag()) / std::abs(ev(o)));
      Eigen::VectorXd v = Li.transpose() * eig.eigenvectors().col(o).real();
      v /= std::sqrt(v.dot(Mr * v));
      V.col(i) = v;
    }
  }
  Modes& md = out.modes;
  md.damping_time = rest.damping_time;
  md.omega = lambda.cwiseMax(0.0).cwiseSqrt();
  md.frequency_hz = md.omega / (2.0 * std::numbers::pi);
  md.joint_shapes = Z * V;
  md.damping_ratio.resize(m);
  md.damped_frequency_hz.resize(m);
  md.torsion_fraction.resize(m);
  for (Eigen::Index i = 0; i < m; ++i) {
    // Joint dampers C = beta K_s (the springs' tangent): modal damping v^T C v / (2 omega) for v^T M v = 1.
    const Eigen::VectorXd v = md.joint_shapes.col(i);
    const double spring = v.dot(Ks * v);
    const double z = md.omega(i) > 0.0 ? 0.5 * rest.damping_time * spring / md.omega(i) : 0.0;
    md.damping_ratio(i) = z;
    md.damped_frequency_hz(i) = z < 1.0 ? md.frequency_hz(i) * std::sqrt(1.0 - z * z) : 0.0;
    double twist = 0.0;
    for (std::size_t j = 0; j < N; ++j) {
      const Eigen::Vector3d moment = Ks.block<3, 3>(at(j), at(j)) * v.segment<3>(at(j));
      Eigen::Vector3d t = c.R_dist[j] * w.rest_link_frames_B()[j].col(0);
      if (j > 0) t = (t + c.R_dist[j - 1] * w.rest_link_frames_B()[j - 1].col(0)).normalized();
      const double tm = t.dot(moment);
      twist += 0.5 * tm * tm * w.joint_weight()[j] * w.torsion_compliance()[j];
    }
    md.torsion_fraction(i) = spring > 0.0 ? std::clamp(twist / (0.5 * spring), 0.0, 1.0) : 0.0;
  }
  // Node displacements of the deflected chain: node k moves by sum_{j < k} theta_j x (x_k - p_j).
  Eigen::MatrixXd D = Eigen::MatrixXd::Zero(at(N + 1), n);
  for (std::size_t kk = 1; kk <= N; ++kk)
    for (std::size_t j = 0; j < kk; ++j) D.block<3, 3>(at(kk), at(j)) = -skew(c.nodes[kk] - c.nodes[j]);
  md.node_shapes = D * md.joint_shapes;
  detail::orient_and_scale_shapes(md);
  return out;
}

}  // namespace vibrissa::dynamics
