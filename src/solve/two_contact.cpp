// The two-contact equilibrium (docs/objects.md, "Two contacts"): two side contacts, frictionless, solved
// together by Newton's method on six unknowns (each contact's force normal to the whisker and its arc length),
// each contact's equations those of the single side contact (object_problem.hpp): gap on the loaded link's lowest
// piece zero, tangency n . t = r', force along the normal. On a creased shape each contact holds one feature
// (Shape::nearest_on_feature: an edge as its line, a face as its plane), so the equations are smooth, and moves
// to the feature nearest its solution until that is the held one (as attempt_on_features).
#include "two_contact.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Dense>

#include "object_mode.hpp"
#include "vibrissa/core/chain.hpp"
#include "vibrissa/objects/clearance.hpp"

namespace vibrissa::detail {

TwoLoadKinematics deflect_two_loads(const Whisker& w, const std::array<LoadState, 2>& loads, Eigen::Vector3d* omega_out) {
  const auto& K_B = w.joint_compliance_B();
  const auto& weight = w.joint_weight();
  const auto& link_B = w.rest_link_vectors_B();
  const auto& R_link = w.rest_link_frames_B();
  const double base_extra = w.base_extra_compliance();
  // Each load in rest axes at its link (chain.hpp, deflect): r from the node below it, F, and the load frame's axes.
  std::array<int, 2> k{};
  std::array<double, 2> h{};
  std::array<Eigen::Vector3d, 2> r, F, t, y;
  for (std::size_t i = 0; i < 2; ++i) {
    double h0;
    w.locate(loads[i].arc_length, k[i], h0);
    const auto uk = static_cast<std::size_t>(k[i]);
    h[i] = loads[i].arc_length - w.node_arc_lengths()[uk];
    const Eigen::Vector3d& kappa = w.load_frame_curvature()[uk];
    const double offset = h[i] - 0.5 * w.link_lengths()[uk];
    const Eigen::Vector3d psi = offset * kappa;
    const Eigen::Matrix3d RE =
        R_link[uk] * (psi.norm() > 0.0 ? Eigen::AngleAxisd(psi.norm(), psi.normalized()).toRotationMatrix()
                                       : Eigen::Matrix3d::Identity());
    r[i] = h[i] * R_link[uk].col(0);
    F[i] = RE * Eigen::Vector3d(loads[i].force_x, loads[i].force_y, loads[i].force_z);
    t[i] = RE.col(0);
    y[i] = RE.col(1);
  }
  const int top = std::max(k[0], k[1]);
  if (omega_out)
    for (int j = top + 1; j < w.links(); ++j) omega_out[j].setZero();
  for (int j = top; j >= 0; --j) {
    const auto u = static_cast<std::size_t>(j);
    Eigen::Vector3d M = Eigen::Vector3d::Zero(), m = Eigen::Vector3d::Zero();
    for (std::size_t i = 0; i < 2; ++i) {
      if (k[i] < j) continue;
      const Eigen::Vector3d mi = r[i].cross(F[i]);
      // The loaded joint's weight (trapezoid over [s_k, s]); every joint below it the full weight.
      const double wi = k[i] == j ? w.loaded_joint_weight_base(j) + w.loaded_joint_weight_slope() * h[i] : weight[u];
      M += wi * mi;
      m += mi;
    }
    const Eigen::Vector3d P = K_B[u] * M;
    Eigen::Vector3d omega = P + K_B[u] * P.cross(0.5 * M);
    if (j == 0 && base_extra > 0.0) {  // the follicle spring in series (chain.hpp)
      const Eigen::Vector3d e = R_link[0].col(0);
      omega += base_extra * (m - m.dot(e) * e);
    }
    if (omega_out) omega_out[j] = R_link[u].transpose() * omega;
    const double angle = omega.norm();
    const Eigen::Matrix3d Q =
        angle > 0.0 ? Eigen::AngleAxisd(angle, omega / angle).toRotationMatrix() : Eigen::Matrix3d::Identity();
    for (std::size_t i = 0; i < 2; ++i) {
      if (k[i] < j) continue;
      r[i] = Q * r[i] + (j > 0 ? link_B[u - 1] : Eigen::Vector3d::Zero());
      F[i] = Q * F[i];
      t[i] = Q * t[i];
      y[i] = Q * y[i];
    }
  }
  TwoLoadKinematics out;
  out.p_B = r;
  out.F_B = F;
  out.t_B = t;
  out.y_B = y;
  return out;
}

namespace {

using Vector6 = Eigen::Matrix<double, 6, 1>;
using Matrix6 = Eigen::Matrix<double, 6, 6>;

/// Newton rounds with the features and pieces held; features and pieces moved between rounds.
constexpr int feature_rounds = 8;
constexpr int newton_iterations = 30;
/// Points per link at which the first contact's far side is searched for a lower gap.
constexpr int beyond_samples = 32;

struct Held {
  std::array<ObjectGeometryB, 2> g;
  std::array<ClearancePiece, 2> piece{ClearancePiece::centre, ClearancePiece::centre};
};

std::array<LoadState, 2> loads_of(const Whisker& w, const Scales& sc, const ObjectGeometryB& g, const Vector6& x) {
  std::array<LoadState, 2> loads;
  for (std::size_t i = 0; i < 2; ++i) {
    const double s = std::clamp(sc.length * x[static_cast<Eigen::Index>(3 * i + 2)], 1e-9 * sc.length, sc.length);
    loads[i] = side_load_state(w, g, sc.force * x[static_cast<Eigen::Index>(3 * i)],
                               sc.force * x[static_cast<Eigen::Index>(3 * i + 1)], s);
  }
  return loads;
}

Vector6 residual(const Whisker& w, const Scales& sc, const Held& held, const Vector6& x) {
  const std::array<LoadState, 2> loads = loads_of(w, sc, held.g[0], x);
  const TwoLoadKinematics k = deflect_two_loads(w, loads);
  Vector6 R;
  for (std::size_t i = 0; i < 2; ++i) {
    const ObjectGeometryB& g = held.g[i];
    const double s = loads[i].arc_length;
    const SurfacePoint q = g.query(k.p_B[i]);
    double slope = 0.0;
    const double r = g.thickness ? whisker_radius_at(w, s, slope) : 0.0;
    const double gap = held.piece[i] == ClearancePiece::centre
                           ? q.signed_distance - r
                           : piece_gap_at(held.piece[i], w, g, s, k.p_B[i], k.t_B[i], k.y_B[i]);
    const Eigen::Vector3d b = q.normal.cross(k.t_B[i]).normalized();
    const auto o = static_cast<Eigen::Index>(3 * i);
    R[o] = gap / sc.length;
    R[o + 1] = q.normal.dot(k.t_B[i]) - slope;
    R[o + 2] = k.F_B[i].dot(b) / sc.force;
  }
  return R;
}

/// Newton's method with central-difference Jacobians and a halving line search on the max-norm.
bool newton(const Whisker& w, const Scales& sc, const Held& held, Vector6& x, double tolerance, int& iterations,
            double& final_residual) {
  Vector6 R = residual(w, sc, held, x);
  double r_max = R.cwiseAbs().maxCoeff(), r_norm = R.norm();
  for (int it = 0; it < newton_iterations; ++it) {
    if (!std::isfinite(r_max)) return false;
    if (r_max <= tolerance) {
      final_residual = r_max;
      return true;
    }
    ++iterations;
    Matrix6 J;  // forward differences (a failure path: six walks, not twelve; Newton converges linearly at worst)
    for (Eigen::Index c = 0; c < 6; ++c) {
      const double step = 1e-7 * std::max(std::abs(x[c]), c % 3 == 2 ? 0.1 : 1e-2);
      Vector6 xp = x;
      xp[c] += step;
      J.col(c) = (residual(w, sc, held, xp) - R) / step;
    }
    const Vector6 dx = J.fullPivLu().solve(-R);
    if (!dx.allFinite()) return false;
    double lambda = 1.0;
    bool moved = false;
    for (int half = 0; half < 30; ++half, lambda *= 0.5) {
      Vector6 xn = x + lambda * dx;
      for (Eigen::Index i : {2, 5}) xn[i] = std::clamp(xn[i], 1e-9, 1.0);
      const Vector6 Rn = residual(w, sc, held, xn);
      const double rn = Rn.norm();
      if (std::isfinite(rn) && rn < r_norm) {
        x = xn;
        R = Rn;
        r_norm = rn;
        r_max = Rn.cwiseAbs().maxCoeff();
        moved = true;
        break;
      }
    }
    if (!moved) break;
  }
  final_residual = r_max;
  return r_max <= tolerance;
}

/// The feature a contact at c_B holds on a creased shape (its nearest), else none.
ObjectGeometryB holding(const ObjectGeometryB& g, const Eigen::Vector3d& c_B) {
  ObjectGeometryB h = g;
  h.last_deflected.reset();
  h.held_feature = -1;
  if (g.shape->needs_thickness()) h.held_feature = g.query(c_B).feature_id;
  return h;
}

}  // namespace

TwoContacts solve_two_contacts(const Whisker& w, const Scales& sc, const ObjectGeometryB& g, const ObjectAttempt& first,
                               double s_second, const SolveOptions& options) {
  TwoContacts out;
  if (w.properties().scheme == Scheme::paper || first.tip || g.core_B || first.status != Status::converged)
    return out;
  const double L = sc.length;
  Vector6 x;
  x << first.state.force_y / sc.force, first.state.force_z / sc.force, first.state.arc_length / L, 0.0, 0.0,
      std::clamp(s_second, 1e-3 * L, L * (1.0 - 1e-6)) / L;
  // Where the first contact's gap is a maximum along the whisker (a whisker curving toward a flat facet touches
  // where its gap is lowest on either side: the creases), it starts at the lowest point on its far side.
  if (g.shape->needs_thickness()) {
    std::vector<Eigen::Vector3d> omega(static_cast<std::size_t>(w.links())), nodes;
    deflect_two_loads(w, loads_of(w, sc, g, x), omega.data());
    deflected_nodes_B(w, omega.data(), nodes);
    const double s1 = first.state.arc_length, away = s_second > s1 ? -1.0 : 1.0, link = L / w.links();
    double best_s = s1, best_gap = std::numeric_limits<double>::infinity();
    for (int i = 0; i <= 3 * beyond_samples; ++i) {
      const double s = std::clamp(s1 + away * i * link / beyond_samples, 1e-3 * L, L * (1.0 - 1e-6));
      int k;
      double h;
      w.locate(s, k, h);
      const auto uk = static_cast<std::size_t>(std::clamp(k, 0, w.links() - 1));
      const double f = std::clamp(h / w.link_lengths()[uk], 0.0, 1.0);
      const Eigen::Vector3d c = (1.0 - f) * nodes[uk] + f * nodes[uk + 1];
      double slope = 0.0;
      const double gap = g.query(c).signed_distance - (g.thickness ? whisker_radius_at(w, s, slope) : 0.0);
      if (gap < best_gap) {
        best_gap = gap;
        best_s = s;
      }
    }
    if (best_gap < -second_contact_depth) x[2] = best_s / L;
  }
  Held held;
  {
    const TwoLoadKinematics k = deflect_two_loads(w, loads_of(w, sc, g, x));
    for (std::size_t i = 0; i < 2; ++i) held.g[i] = holding(g, k.p_B[i]);
  }
  const double tolerance = options.tolerance / L;
  for (int round = 0; round < feature_rounds; ++round) {
    double res = 0.0;
    const Vector6 x_start = x;
    if (!newton(w, sc, held, x, tolerance, out.iterations, res) && g.shape->needs_thickness()) {
      // Stalled: the features nearest where it stalled held instead, from the round's start.
      const TwoLoadKinematics k = deflect_two_loads(w, loads_of(w, sc, g, x));
      bool moved = false;
      for (std::size_t i = 0; i < 2; ++i) {
        const std::int64_t nearest = g.query(k.p_B[i]).feature_id;
        moved = moved || nearest != held.g[i].held_feature;
        held.g[i].held_feature = nearest;
      }
      x = x_start;
      if (moved && newton(w, sc, held, x, tolerance, out.iterations, res)) res = std::max(res, 0.0);
      else res = -1.0;
    }
    if (res < 0.0 || res > tolerance) return out;
    out.residual = res * L;
    // Pieces and features at the solution: where another is lower or nearer, hold it and solve again.
    const std::array<LoadState, 2> loads = loads_of(w, sc, g, x);
    const TwoLoadKinematics k = deflect_two_loads(w, loads);
    bool changed = false;
    for (std::size_t i = 0; i < 2; ++i) {
      if (g.shape->needs_thickness()) {
        const SurfacePoint on = held.g[i].query(k.p_B[i]), nearest = g.query(k.p_B[i]);
        const bool same = std::abs(on.signed_distance - nearest.signed_distance) <= 1e-15 * L &&
                          (on.normal - nearest.normal).norm() <= 1e-12;
        if (!same) {
          held.g[i].held_feature = nearest.feature_id;
          changed = true;
        }
      }
      if (contact_pieces_apply(w, g)) {
        double slope = 0.0;
        const double gap_c = held.g[i].query(k.p_B[i]).signed_distance -
                             (g.thickness ? whisker_radius_at(w, loads[i].arc_length, slope) : 0.0);
        ClearancePiece best = ClearancePiece::centre;
        double lowest = gap_c;
        for (ClearancePiece p : {ClearancePiece::start_node, ClearancePiece::end_node, ClearancePiece::chord}) {
          const double gp = piece_gap_at(p, w, held.g[i], loads[i].arc_length, k.p_B[i], k.t_B[i], k.y_B[i]);
          if (gp < lowest - 1e-15 * L) {
            lowest = gp;
            best = p;
          }
        }
        if (best != held.piece[i]) {
          held.piece[i] = best;
          changed = true;
        }
      }
    }
    if (changed) continue;
    // Both pushing? Where one would pull, the single contact at the other place.
    for (std::size_t i = 0; i < 2; ++i) {
      const SurfacePoint q = g.query(k.p_B[i]);
      if (k.F_B[i].dot(q.normal) < 0.0) {
        const std::size_t other = 1 - i;
        const auto o = static_cast<Eigen::Index>(3 * other);
        double sigma = 1.0;
        ObjectAttempt a = attempt_object(w, sc, g, FrictionLaw{}, sigma, false, Eigen::Vector3d(x[o], x[o + 1], x[o + 2]),
                                         options);
        if (a.status == Status::not_converged && g.shape->needs_thickness()) {
          ObjectAttempt from = a;
          from.status = Status::converged;
          from.lm.u = Eigen::Vector3d(x[o], x[o + 1], x[o + 2]);
          from.state = loads[other];
          a = attempt_on_features(w, sc, g, FrictionLaw{}, sigma, from, options, g.query(k.p_B[other]));
        }
        out.iterations += a.lm.iterations;
        if (a.status != Status::converged || !valid_contact(w, g, a, sigma)) return out;
        out.single = static_cast<int>(other);
        out.single_attempt = a;
        out.solved = true;
        return out;
      }
    }
    // Nowhere else inside.
    std::vector<Eigen::Vector3d> omega(static_cast<std::size_t>(w.links()));
    deflect_two_loads(w, loads, omega.data());
    deflected_nodes_B(w, omega.data(), out.nodes_B);
    const std::vector<double> none;
    const PlacedShape placed{g.shape, ObjectPose{g.R_BO, g.p_BO + g.offset_B}};
    const Clearance c = clearance(placed, out.nodes_B, w.node_arc_lengths(), g.thickness ? w.node_radii() : none,
                                  -second_contact_depth);
    if (c.gap < -second_contact_depth) return out;
    for (std::size_t i = 0; i < 2; ++i) {
      const SurfacePoint q = g.query(k.p_B[i]);
      out.loads[i] = loads[i];
      out.point_B[i] = q.closest;
      out.normal_B[i] = q.normal;
      out.feature[i] = q.feature;
    }
    out.solved = true;
    return out;
  }
  return out;
}

}  // namespace vibrissa::detail
