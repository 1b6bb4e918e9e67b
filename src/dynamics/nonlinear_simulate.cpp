// Large-deflection motion of the chain with contacts (docs/dynamics.md, "Large deflection" and "Contact during
// motion"; include/vibrissa/dynamics/simulate.hpp, chain_kinematics.hpp, contact.hpp).
//
// Equations, in the modal coordinates of the rest chain (q = Phi eta, Phi^T M Phi = I, Phi^T K Phi = diag(k)):
//     eta'' + diag(c) eta' + diag(k) eta = Phi^T (G u(t) + Q(q, q', t)),
// Q = sum over contacts of J(q)^T F: the contact forces through the exact kinematics of the deflected chain. The
// joint springs are those of the quasi-static chain (linear_model.hpp: the inverse of each joint's compliance), so
// with the exact kinematics the equilibrium K theta_j = J_r(theta_j)^T m_j (J_r the right Jacobian of SO(3), m_j
// the moment of the distal load in the joint's distal frame) is the quasi-static walk's law
// theta_j = K^-1 (m_j + (K^-1 m_j) x m_j / 2) (core/chain.hpp) to second order in the joint rotation.
// The mass matrix is the rest chain's (the inertia is linearised; the elastic and contact forces are not).
//
// Integrator: TR-BDF2 (Bank et al. 1985) as a three-stage ESDIRK (Hosea & Shampine 1996): a trapezoidal stage to
// t + (2 - sqrt 2) h, then BDF2 to t + h; L-stable, stiffly accurate, order 2, the first stage explicit (the last
// stage's f of the step before). The two implicit stages share the diagonal coefficient d, so their Newton matrices
// are the same: each is solved by Newton's method on the stage's modal rates; the contacts make the Newton matrix
// diag + a rank-3 term per contact (Woodbury). Error control (step_control.hpp) by the embedded third-order
// estimate, filtered through the Newton matrix (stiff components count by their damped response). Where a contact
// flickers: Alexander's two-stage SDIRK (same order, all stages implicit) with step doubling (run()).
#include "nonlinear_simulate.hpp"
#include "step_control.hpp"
#include "surface_contact.hpp"

#include <algorithm>
#include <array>
#include <iterator>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <span>
#include <string>
#include <variant>

#include <Eigen/LU>

#include "vibrissa/core/checks.hpp"
#include "vibrissa/dynamics/chain_kinematics.hpp"
#include "vibrissa/dynamics/skew.hpp"

namespace vibrissa::dynamics::detail {
namespace {

// TR-BDF2 as an ESDIRK (Hosea & Shampine 1996, Appl. Numer. Math. 20:21, eqs. for the "TR-BDF2" tableau): c = (0,
// 2d, 1), rows (0 0 0), (d d 0), (w w d), b = the last row (stiffly accurate), d = 1 - 1/sqrt 2, w = sqrt 2 / 4; the
// embedded third-order weights b^ = ((1 - w) / 3, (3w + 1) / 3, d / 3).
const double d_trbdf2 = 1.0 - 1.0 / std::sqrt(2.0);
const double w_trbdf2 = std::sqrt(2.0) / 4.0;
// Where a contact flickers: Alexander's two-stage SDIRK (gamma = 1 - 1/sqrt 2; L-stable, stiffly accurate,
// order 2), step doubling (see step_sdirk2).
const double gamma_sdirk2 = 1.0 - 1.0 / std::sqrt(2.0);

/// One contact's evaluation at a stage.
struct ContactValue {
  ContactState state = ContactState::none;
  double gap = std::numeric_limits<double>::infinity();
  double arc_length = 0.0;
  double anchor = 0.0;  ///< stick point's coordinate along the line [m]
  double side = 0.0;    ///< +-1: the side of the line the whisker is on; 0: not known
  Eigen::Vector3d anchor_W = Eigen::Vector3d::Zero();  ///< a surface's stick point (world) [m]
  int link = 0;
  Eigen::Vector3d x_B = Eigen::Vector3d::Zero(), force_B = Eigen::Vector3d::Zero();
  Eigen::Vector3d point_W = Eigen::Vector3d::Zero(), force_W = Eigen::Vector3d::Zero();
  Eigen::Matrix3d S_x = Eigen::Matrix3d::Zero(), S_v = Eigen::Matrix3d::Zero();  ///< dF/dx, dF/dx' (B)
};

struct State {
  Eigen::VectorXd eta, rate;
  std::vector<ContactValue> contacts;
  Eigen::VectorXd contact_force;  ///< modal, Phi^T Q
};

/// The obstacles in B at one instant and the base's motion.
struct Frame {
  BaseMotion base;
  Eigen::VectorXd modal_input;
  Eigen::VectorXd static_q;  ///< with a truncated basis: the residual modes' static response R G u(t) (else empty)
};

class Integrator {
 public:
  Integrator(const Whisker& w, const LinearModel& model, const Modes& modes, const BaseTrajectory& base,
             const Eigen::Vector3d& gravity_W, const SimulationOptions& opt)
      : w_(w), model_(model), base_(base), gravity_(gravity_W), opt_(opt) {
    const Eigen::Index all = modes.joint_shapes.cols();
    m_ = opt.modes > 0 ? std::min<Eigen::Index>(opt.modes, all) : all;
    truncated_ = m_ < all;
    Phi_ = modes.joint_shapes.leftCols(m_);
    k_ = modes.omega.head(m_).cwiseProduct(modes.omega.head(m_));
    c_ = 2.0 * modes.damping_ratio.head(m_).cwiseProduct(modes.omega.head(m_));
    P_ = Phi_.transpose() * model.input;
    if (truncated_) {
      // The residual flexibility R = K^-1 - Phi_m k^-1 Phi_m^T (K block diagonal: K^-1 by blocks, O(N m) products)
      // and the residual modes' static response to the base input, R G (3N x 12).
      const Eigen::Index joints = model.size() / 3;
      K_inv_.resize(static_cast<std::size_t>(joints));
      for (Eigen::Index j = 0; j < joints; ++j)
        K_inv_[static_cast<std::size_t>(j)] = model.stiffness.block<3, 3>(3 * j, 3 * j).inverse();
      static_input_ = apply_K_inv(model.input) - Phi_ * (P_.array().colwise() / k_.array()).matrix();
    }
    kn_ = opt.contact.stiffness;
    kt_ = opt.contact.tangential_stiffness > 0.0 ? opt.contact.tangential_stiffness : kn_;
    // Contact slots: the line objects' first (one each, indexed as objects_), then the surfaces' (surface_slots
    // each).
    for (std::size_t k = 0; k < opt.objects.size(); ++k)
      if (const auto* line = std::get_if<LineObstacle>(&opt.objects[k])) {
        LineObstacle u = *line;
        u.direction_W = line->direction_W.normalized();
        objects_.push_back(u);
        object_of_.push_back(k);
      }
    for (std::size_t k = 0; k < opt.objects.size(); ++k)
      if (const auto* surface = std::get_if<SurfaceObstacle>(&opt.objects[k])) {
        surfaces_.push_back(*surface);
        for (std::size_t j = 0; j < surface_slots; ++j) object_of_.push_back(k);
      }
    slots_ = object_of_.size();
  }

  Frame frame(double t) const {
    Frame f;
    f.base = base_(t);
    const Eigen::Matrix<double, base_input_size, 1> u = base_input(f.base, gravity_);
    f.modal_input = P_ * u;
    if (truncated_) f.static_q = static_input_ * u;
    return f;
  }

  /// K^-1 X, block by block.
  Eigen::MatrixXd apply_K_inv(const Eigen::MatrixXd& X) const {
    Eigen::MatrixXd out(X.rows(), X.cols());
    for (std::size_t j = 0; j < K_inv_.size(); ++j)
      out.middleRows<3>(3 * static_cast<Eigen::Index>(j)).noalias() =
          K_inv_[j] * X.middleRows<3>(3 * static_cast<Eigen::Index>(j));
    return out;
  }

  /// The joint coordinates of a state: Phi_m eta, and with a truncated basis the residual modes' static response
  /// to the base input and the contact forces, R (G u + sum J^T F) (docs/dynamics.md, "Modal truncation").
  const Eigen::VectorXd& joint_coordinates(const Frame& f, const State& s) {
    q_.noalias() = Phi_ * s.eta;
    if (!truncated_) return q_;
    q_ += f.static_q;
    chain_kinematics(w_, q_, kin_);
    Eigen::VectorXd Q = Eigen::VectorXd::Zero(q_.size());
    for (const ContactValue& cv : s.contacts)
      if (cv.state != ContactState::none) add_generalized_force(kin_, cv.link, cv.x_B, cv.force_B, Q);
    q_ += apply_K_inv(Q) - Phi_ * (Phi_.transpose() * Q).cwiseQuotient(k_);
    return q_;
  }

  double energy_norm(const Eigen::VectorXd& eta, const Eigen::VectorXd& rate) const {
    return std::sqrt(k_.dot(eta.cwiseProduct(eta)) + rate.squaredNorm());
  }

  /// Contacts at (eta, rate); `previous`: the contact states and anchors at the start of the step.
  void evaluate_contacts(const Frame& f, const Eigen::VectorXd& eta, const Eigen::VectorXd& rate,
                         const std::vector<ContactValue>& previous, std::vector<ContactValue>& out,
                         Eigen::VectorXd& modal_force, std::vector<Eigen::MatrixXd>* U,
                         const std::vector<ContactState>* frozen = nullptr) {
    q_.noalias() = Phi_ * eta;
    if (truncated_) q_ += f.static_q;
    chain_kinematics(w_, q_, kin_);
    deep_crossing_ = false;
    // Newton's held surface contacts stay near the links of the iteration before (`out` holds it).
    hold_link_.assign(slots_, -1);
    if (frozen && out.size() == slots_)
      for (std::size_t k = objects_.size(); k < slots_; ++k)
        if ((*frozen)[k] != ContactState::none) hold_link_[k] = out[k].link;
    out.assign(slots_, ContactValue{});
    modal_force.setZero(m_);
    if (U) U->assign(slots_, Eigen::MatrixXd());
    if (!surfaces_.empty()) evaluate_surfaces(f, rate, previous, out, modal_force, U, frozen);
    const Eigen::Matrix3d& R = f.base.R_WB;
    const auto& radii = w_.node_radii();
    const auto& arc = w_.node_arc_lengths();
    for (std::size_t o = 0; o < objects_.size(); ++o) {
      const LineObstacle& ob = objects_[o];
      const Eigen::Vector3d c_B = R.transpose() * (ob.point_W - f.base.p_W_base);
      const Eigen::Vector3d e_B = R.transpose() * ob.direction_W;
      ContactValue& cv = out[o];
      // Nearest approach of the centre line (segment by segment) to the line, minus the radii.
      double best = std::numeric_limits<double>::infinity(), best_u_raw = 0.0;
      std::size_t best_i = 0;
      Eigen::Vector3d best_r = Eigen::Vector3d::Zero(), best_t = Eigen::Vector3d::UnitX();
      const std::size_t last_link = kin_.nodes_B.size() - 2;
      for (std::size_t i = 0; i + 1 < kin_.nodes_B.size(); ++i) {
        const Eigen::Vector3d p = kin_.nodes_B[i], d = kin_.nodes_B[i + 1] - p, w0 = p - c_B;
        const double a = d.squaredNorm(), b = d.dot(e_B), denom = a - b * b;
        const double u_raw = denom > 1e-12 * a ? (b * e_B.dot(w0) - d.dot(w0)) / denom : 0.5;
        const double u = std::clamp(u_raw, 0.0, 1.0);
        const Eigen::Vector3d x = p + u * d;
        const Eigen::Vector3d r = x - c_B - e_B.dot(x - c_B) * e_B;
        const double reach = ob.radius + (ob.thickness ? radii[i] + u * (radii[i + 1] - radii[i]) : 0.0);
        const double gap = r.norm() - reach;
        if (gap < best) {
          best = gap;
          best_u_raw = u_raw;
          best_i = i;
          best_r = r;
          best_t = d;
          cv.gap = gap;
          cv.link = static_cast<int>(i);
          cv.arc_length = arc[i] + u * (arc[i + 1] - arc[i]);
          cv.x_B = x;
        }
      }
      // Which side of the line the whisker is on: the sign of r . (t x e) where the nearest point lies on the
      // whisker (where the centre line can cross the line), carried from step to step, so that a centre line
      // pushed across an edge (radius 0) within one step counts as a penetration, not as the other side. Beyond
      // the whisker's ends (the nearest point is the base or the tip, clamped) the side is forgotten and read
      // again later. A node between two links is on the whisker: a contact passing from one link to the next
      // keeps its side.
      const double side = best_r.dot(best_t.cross(e_B)) >= 0.0 ? 1.0 : -1.0;
      const bool interior = !(best_i == 0 && best_u_raw <= 0.0) && !(best_i == last_link && best_u_raw >= 1.0);
      const double side_before = previous[o].side;
      cv.side = interior ? (side_before != 0.0 ? side_before : side) : 0.0;
      // The side only means something near the line: a flip of the sign farther than kMaxCrossing (0.1 mm: a
      // penalty force of 1 N with the default k_n, far above a whisker's) from it is the nearest point moving
      // along a curved whisker, and the side is read again; but if the whisker was that near at the step's start,
      // the step carried it through the line, and the step is refused (the step control shrinks it until the
      // penalty has caught the whisker, or, at the tip, until the contact has slid off it).
      constexpr double kMaxCrossing = 1e-4;
      const bool flipped = interior && side_before != 0.0 && side != side_before;
      const double reach_here = best_r.norm() - cv.gap;
      const bool near = best_r.norm() <= reach_here + kMaxCrossing;
      const bool crossed = flipped && near;
      if (flipped && !near) {
        if (previous[o].gap < kMaxCrossing) deep_crossing_ = true;
        cv.side = side;
      }
      const double dist = best_r.norm();
      if (crossed) cv.gap = -dist - (dist - cv.gap);  // -(distance) - reach
      cv.point_W = f.base.p_W_base + R * cv.x_B;
      const ContactValue& before = previous[o];
      cv.anchor = before.anchor;
      // Newton's later iterations keep the contact set (and the stick/slip branch) of the earlier ones: the
      // switches are not smooth, and near grazing or the cone's edge the iteration would cycle. The stage's final
      // evaluation decides them again.
      const bool frozen_on = frozen && (*frozen)[o] != ContactState::none;
      if (frozen && !frozen_on) continue;
      if (cv.gap >= 0.0 && !frozen_on) continue;
      // In contact: normal n (from the line to the whisker), tangent e (along the line).
      const Eigen::Vector3d rel = cv.x_B - c_B;
      Eigen::Vector3d n = dist > 0.0 ? Eigen::Vector3d(best_r / dist) : Eigen::Vector3d(best_t.cross(e_B).normalized());
      if (crossed) n = -n;
      NormalForce nf = normal_force(f, cv, n, rate, frozen_on);
      Eigen::MatrixXd& Ui = nf.Ui;
      const Eigen::Vector3d& v_B = nf.v_B;
      const Eigen::Matrix3d& C = nf.C;
      const double fn = nf.fn;
      const double lambda = e_B.dot(rel);
      if (before.state == ContactState::none) cv.anchor = lambda;  // touches: sticks where it touched
      const double mu = ob.friction_coefficient;
      double ft = 0.0;
      Eigen::Vector3d b = e_B;  // the friction force's direction (below)
      if (fn > 0.0 || frozen_on) {
        const Eigen::Vector3d &dfn_dx = nf.dfn_dx, &dfn_dv = nf.dfn_dv;
        cv.S_x = n * dfn_dx.transpose();
        cv.S_v = n * dfn_dv.transpose();
        // Elastic-plastic friction, with the quasi-static frictional edge's law (spec §3.1; solve_frictional_edge):
        // the whisker slides freely along its own length, so the friction force lies across it, along
        // b = e_perp / |e_perp| (e_perp: the line's direction without its part along the whisker's tangent t);
        // the stick spring holds the crossing's coordinate lambda along the line at the anchor (a whisker
        // displacement delta across it moves lambda by b . delta / c, c = |e_perp|: spring -k_t c (lambda - anchor)
        // along b), and Coulomb bounds the force's part along the line by mu times its part normal to the line:
        // |F . e| <= mu |F - (F . e) e|, with F = f_n n + f_t b: |f_t| <= mu f_n / sqrt(c^2 - mu^2 (1 - c^2)) (no
        // bound when the line is within atan(mu) of the whisker's tangent). A damper on the stick spring
        // (critical for the effective mass along b, as the normal one) adds to the force, which stays inside the
        // cone; the spring's force alone decides stick or slip (so that the state does not chatter).
        // (b is also made normal to n, which at a node between two links is not exactly normal to the chord, so
        // that c = b . e makes the cone exact.)
        const Eigen::Vector3d t_hat = best_t.normalized();
        Eigen::Vector3d e_perp = e_B - e_B.dot(t_hat) * t_hat;
        e_perp -= e_perp.dot(n) * n;
        const bool frictional = mu > 0.0 && e_perp.norm() > 1e-9;
        if (frictional) b = e_perp.normalized();
        const double c_line = frictional ? b.dot(e_B) : 0.0;
        const double cone = c_line * c_line - mu * mu * (1.0 - c_line * c_line);
        const double ratio = cone > 0.0 ? mu / std::sqrt(cone) : std::numeric_limits<double>::infinity();
        const double limit = ratio * fn;
        const double ct = critical_damping(kt_, Ui, C, b);
        const double spring = -kt_ * c_line * (lambda - cv.anchor), damper = -ct * b.dot(v_B);
        const ContactState keep = frozen ? (*frozen)[o] : ContactState::none;
        const bool stick = keep != ContactState::none ? keep == ContactState::stick && frictional
                                                      : frictional && std::abs(spring) <= limit;
        if (stick) {
          cv.state = ContactState::stick;
          ft = spring + damper;
          cv.S_x -= kt_ * b * b.transpose();
          if (keep != ContactState::none) {
            cv.S_v -= ct * b * b.transpose();
          } else if (std::abs(ft) > limit) {
            ft = ft > 0.0 ? limit : -limit;
          } else {
            cv.S_v -= ct * b * b.transpose();
          }
        } else if (frictional) {
          cv.state = ContactState::slip;
          const double sign = spring >= 0.0 ? 1.0 : -1.0;
          ft = sign * limit;
          cv.anchor = lambda + ft / (kt_ * c_line);  // the stick point slides along with the contact
          cv.S_x += (sign * ratio) * b * dfn_dx.transpose();
          cv.S_v += (sign * ratio) * b * dfn_dv.transpose();
        } else {
          cv.state = ContactState::slip;
          cv.anchor = lambda;
        }
      } else {
        // Inside, but the damper pulls harder than the spring pushes: no force. Still touching (the state follows
        // the gap, so that events are touch and release of the surfaces, not of the force).
        cv.anchor = lambda;
        cv.state = before.state != ContactState::none ? before.state : ContactState::slip;
        continue;
      }
      cv.force_B = fn * n + ft * b;
      give_way(f, C, n, cv);
      cv.force_W = R * cv.force_B;
      modal_force.noalias() += Ui * cv.force_B;
      if (U) (*U)[o] = std::move(Ui);
    }
  }

  /// The damping coefficient of a contact spring k along the unit direction d (normal, or a friction direction):
  /// `damping_ratio` times critical for the whisker's effective mass there, 1 / m_eff = d^T J M^-1 J^T d = |Ui d|^2,
  /// for the spring in series with the residual compliance d^T C d (the series law scales the force by
  /// 1 / (1 + k d^T C d), so the damper is taken that much larger; C is zero with all modes).
  double critical_damping(double k, const Eigen::MatrixXd& Ui, const Eigen::Matrix3d& C,
                          const Eigen::Vector3d& d) const {
    const double series = 1.0 + k * std::max(0.0, d.dot(C * d));
    return 2.0 * opt_.contact.damping_ratio * std::sqrt(k / series / std::max((Ui * d).squaredNorm(), 1e-300)) *
           series;
  }

  /// A contact's normal law at its point cv.x_B (on link cv.link, gap cv.gap) with normal n (in B): the penalty
  /// and its damper (docs/dynamics.md, "Contacts"), with what the friction law and give_way need.
  struct NormalForce {
    Eigen::MatrixXd Ui;       ///< Phi^T J^T of the point
    Eigen::Vector3d v_B;      ///< the point's velocity (world, in B axes)
    Eigen::Matrix3d C;        ///< the residual compliance (zero with all modes)
    double fn = 0.0;          ///< the normal force (>= 0 unless the contact set is frozen)
    Eigen::Vector3d dfn_dx;   ///< its derivatives by the point's displacement and velocity
    Eigen::Vector3d dfn_dv;
  };
  NormalForce normal_force(const Frame& f, const ContactValue& cv, const Eigen::Vector3d& n,
                           const Eigen::VectorXd& rate, bool frozen_on) {
    const Eigen::Matrix3d& R = f.base.R_WB;
    NormalForce out;
    out.Ui = modal_projection(cv.link, cv.x_B);
    // The contact point's velocity in B: the base's, plus J q' = (Phi^T J^T)^T eta'.
    out.v_B = R.transpose() * (f.base.velocity_W + f.base.omega_W.cross(R * cv.x_B)) + out.Ui.transpose() * rate;
    // With a truncated basis the residual modes follow the force statically: the contact point gives way by
    // C F, C = J R J^T = sum_j J_j^T K_j^-1 J_j - (Phi_m^T J^T)^T k^-1 (Phi_m^T J^T), in series with the law.
    out.C = residual_compliance(cv.link, out.Ui);
    const double cn = critical_damping(kn_, out.Ui, out.C, n);
    const double gap_rate = n.dot(out.v_B);
    const double fn_raw = -kn_ * cv.gap - cn * gap_rate;
    out.fn = frozen_on ? fn_raw : std::max(0.0, fn_raw);
    const bool damped = frozen_on || (fn_raw > 0.0 && cn * gap_rate != 0.0);
    out.dfn_dx = -kn_ * n;
    out.dfn_dv = damped ? Eigen::Vector3d(-cn * n) : Eigen::Vector3d::Zero();
    return out;
  }

  /// Phi^T J^T of the point x_B on link `link` (the modal projection of a force there); J^T into Jt_ (its rows
  /// for the joints up to the link).
  Eigen::MatrixXd modal_projection(int link, const Eigen::Vector3d& x_B) {
    const Eigen::Index joints = 3 * (link + 1);
    Jt_.resize(joints, 3);
    for (int j = 0; j <= link; ++j) {
      const std::size_t u = static_cast<std::size_t>(j);
      Jt_.middleRows<3>(3 * j) = kin_.joint_axes_B[u].transpose() * skew(x_B - kin_.nodes_B[u]);
    }
    // With the first 3 (link + 1) rows of Phi, mode by mode: the three dot products of a mode's column read it from
    // memory once (three matrix-vector products read Phi three times).
    Eigen::MatrixXd Ui(m_, 3);
    for (Eigen::Index k = 0; k < m_; ++k) {
      const auto col = Phi_.col(k).head(joints);
      Ui(k, 0) = col.dot(Jt_.col(0));
      Ui(k, 1) = col.dot(Jt_.col(1));
      Ui(k, 2) = col.dot(Jt_.col(2));
    }
    return Ui;
  }

  /// With a truncated basis the residual modes follow a contact force statically: the point (on `link`, J^T in Jt_
  /// from modal_projection, Ui = Phi_m^T J^T) gives way by C F, C = J R J^T = sum_j J_j^T K_j^-1 J_j - Ui^T k^-1 Ui.
  /// Zero with all modes.
  Eigen::Matrix3d residual_compliance(int link, const Eigen::MatrixXd& Ui) const {
    Eigen::Matrix3d C = Eigen::Matrix3d::Zero();
    if (!truncated_) return C;
    for (int j = 0; j <= link; ++j) {
      const auto Jj = Jt_.middleRows<3>(3 * j);
      C.noalias() += Jj.transpose() * K_inv_[static_cast<std::size_t>(j)] * Jj;
    }
    C.noalias() -= Ui.transpose() * (Ui.array().colwise() / k_.array()).matrix();
    return C;
  }

  /// The law (force F_0 = cv.force_B, derivatives S_x, S_v) in series with the give C: at x + C F, linear in x
  /// within its branch, F = (I - S_x C)^-1 F_0, and so its derivatives; the contact point and gap become the
  /// given-way ones. Nothing with all modes.
  void give_way(const Frame& f, const Eigen::Matrix3d& C, const Eigen::Vector3d& n, ContactValue& cv) const {
    if (!truncated_) return;
    const Eigen::Matrix3d A = (Eigen::Matrix3d::Identity() - cv.S_x * C).inverse();
    cv.force_B = A * cv.force_B;
    cv.S_x = A * cv.S_x;
    cv.S_v = A * cv.S_v;
    const Eigen::Vector3d give = C * cv.force_B;
    cv.x_B += give;
    cv.gap += n.dot(give);
    cv.point_W = f.base.p_W_base + f.base.R_WB * cv.x_B;
  }

  /// The surfaces' contacts (slots objects_.size() ...; see evaluate_contacts): the points found by
  /// surface_contacts, the line's penalty and damping along the surface's normal n, and the frictional object
  /// mode's friction (docs/objects.md, "Friction"): across the whisker along b = n x t / |n x t| (the whisker slides
  /// freely along itself), in the whole tangent plane at the tip (or where the whisker is along n), with the line's
  /// elastic-plastic stick spring holding the contact at its anchor (a point in the world) and the Coulomb bound
  /// |F_t| <= mu F_n.
  void evaluate_surfaces(const Frame& f, const Eigen::VectorXd& rate, const std::vector<ContactValue>& previous,
                         std::vector<ContactValue>& out, Eigen::VectorXd& modal_force, std::vector<Eigen::MatrixXd>* U,
                         const std::vector<ContactState>* frozen) {
    const Eigen::Matrix3d& R = f.base.R_WB;
    const std::size_t n_nodes = kin_.nodes_B.size(), last_link = n_nodes - 2;
    nodes_W_.resize(n_nodes);
    for (std::size_t i = 0; i < n_nodes; ++i) nodes_W_[i] = f.base.p_W_base + R * kin_.nodes_B[i];
    std::array<double, surface_slots> before_arc{};
    std::array<int, surface_slots> hold{};
    std::array<SurfaceCandidate, surface_slots> found{};
    SurfaceCandidate nearest;
    for (std::size_t s = 0; s < surfaces_.size(); ++s) {
      const SurfaceObstacle& ob = surfaces_[s];
      const std::size_t first = objects_.size() + s * surface_slots;
      for (std::size_t j = 0; j < surface_slots; ++j) {
        const ContactValue& p = previous[first + j];
        before_arc[j] = p.state != ContactState::none ? p.arc_length : std::numeric_limits<double>::quiet_NaN();
        hold[j] = hold_link_[first + j];
      }
      const std::span<const double> radii =
          ob.thickness ? std::span<const double>(w_.node_radii()) : std::span<const double>();
      surface_contacts(PlacedShape{ob.shape.get(), ob.X_WO}, nodes_W_, w_.node_arc_lengths(), radii, before_arc, hold,
                       found, nearest);
      for (std::size_t j = 0; j < surface_slots; ++j) {
        const std::size_t o = first + j;
        ContactValue& cv = out[o];
        const ContactValue& before = previous[o];
        const SurfaceCandidate& c = found[j].found ? found[j] : nearest;
        cv.gap = c.gap;
        cv.link = c.link;
        cv.arc_length = c.arc_length;
        cv.point_W = c.point_W;
        cv.x_B = R.transpose() * (c.point_W - f.base.p_W_base);
        cv.anchor_W = before.anchor_W;
        const bool frozen_on = frozen && (*frozen)[o] != ContactState::none;
        if (!found[j].found || (frozen && !frozen_on)) continue;
        if (cv.gap >= 0.0 && !frozen_on) continue;
        const Eigen::Vector3d n = R.transpose() * c.surface.normal;
        NormalForce nf = normal_force(f, cv, n, rate, frozen_on);  // as the line's
        Eigen::MatrixXd& Ui = nf.Ui;
        const Eigen::Vector3d& v_B = nf.v_B;
        const Eigen::Matrix3d& C = nf.C;
        const double fn = nf.fn;
        if (before.state == ContactState::none) cv.anchor_W = cv.point_W;  // touches: sticks where it touched
        if (!(fn > 0.0 || frozen_on)) {
          // Inside, but the damper pulls harder than the spring pushes: no force, still touching (as the line's).
          cv.anchor_W = cv.point_W;
          cv.state = before.state != ContactState::none ? before.state : ContactState::slip;
          continue;
        }
        const Eigen::Vector3d &dfn_dx = nf.dfn_dx, &dfn_dv = nf.dfn_dv;
        cv.S_x = n * dfn_dx.transpose();
        cv.S_v = n * dfn_dv.transpose();
        // Friction's directions T (B): b = n x t across the whisker on its side; the tangent plane at the tip.
        const Eigen::Vector3d t_hat = (kin_.nodes_B[c.link + 1] - kin_.nodes_B[c.link]).normalized();
        const Eigen::Vector3d b = n.cross(t_hat);
        const bool tip = static_cast<std::size_t>(c.link) == last_link && c.tau >= 1.0 - 1e-12;
        Eigen::Matrix<double, 3, Eigen::Dynamic> T;
        if (tip || b.norm() < 1e-6) {
          const Eigen::Vector3d e1 = n.unitOrthogonal();
          T.resize(3, 2);
          T << e1, n.cross(e1);
        } else {
          T = b.normalized();
        }
        const double mu = surfaces_[s].friction_coefficient;
        Eigen::Vector3d ft_B = Eigen::Vector3d::Zero();
        if (mu > 0.0) {
          const double limit = mu * std::max(fn, 0.0);
          const Eigen::Vector3d anchor_B = R.transpose() * (cv.anchor_W - f.base.p_W_base);
          const Eigen::VectorXd spring = -kt_ * (T.transpose() * (cv.x_B - anchor_B));
          Eigen::VectorXd ct(T.cols()), damper(T.cols());
          for (Eigen::Index k = 0; k < T.cols(); ++k) {
            ct(k) = critical_damping(kt_, Ui, C, T.col(k));
            damper(k) = -ct(k) * T.col(k).dot(v_B);
          }
          const ContactState keep = frozen ? (*frozen)[o] : ContactState::none;
          const bool stick = keep != ContactState::none ? keep == ContactState::stick : spring.norm() <= limit;
          if (stick) {
            cv.state = ContactState::stick;
            Eigen::VectorXd ft = spring + damper;
            cv.S_x -= kt_ * T * T.transpose();
            if (keep == ContactState::none && ft.norm() > limit) {
              ft *= limit / ft.norm();
            } else {
              cv.S_v -= T * ct.asDiagonal() * T.transpose();
            }
            ft_B = T * ft;
          } else {
            cv.state = ContactState::slip;
            const double norm = spring.norm();
            const Eigen::VectorXd dir = norm > 0.0 ? Eigen::VectorXd(spring / norm) : Eigen::VectorXd::Zero(T.cols());
            ft_B = T * (mu * fn * dir);
            // The stick point slides along with the contact.
            cv.anchor_W = cv.point_W + R * (ft_B / kt_);
            cv.S_x += mu * (T * dir) * dfn_dx.transpose();
            cv.S_v += mu * (T * dir) * dfn_dv.transpose();
            // In the tangent plane (the tip) the slip's direction turns with x: d dir / dx = -k_t (I - dir dir^T) T^T
            // / |spring|.
            if (norm > 0.0 && T.cols() == 2)
              cv.S_x -= (mu * fn * kt_ / norm) * T *
                        (Eigen::Matrix2d::Identity() - Eigen::Vector2d(dir) * Eigen::Vector2d(dir).transpose()) *
                        T.transpose();
          }
        } else {
          cv.state = ContactState::slip;
          cv.anchor_W = cv.point_W;
        }
        cv.force_B = fn * n + ft_B;
        give_way(f, C, n, cv);
        cv.force_W = R * cv.force_B;
        modal_force.noalias() += Ui * cv.force_B;
        if (U) (*U)[o] = std::move(Ui);
      }
    }
  }

  /// Solves N x = r with N = D - sum U g (g S_x + S_v) U^T, the stage's Newton matrix (D = 1 + g c + g^2 k) at the
  /// contacts `contacts` whose projections Phi^T J^T are in `U` (empty: not pushing): Woodbury with them stacked.
  Eigen::VectorXd solve_newton(const Eigen::VectorXd& D, double g, const std::vector<ContactValue>& contacts,
                               const std::vector<Eigen::MatrixXd>& U, const Eigen::VectorXd& r) const {
    std::vector<std::size_t> active;
    for (std::size_t o = 0; o < U.size(); ++o)
      if (U[o].size() != 0) active.push_back(o);
    const Eigen::VectorXd Dinv_r = r.cwiseQuotient(D);
    if (active.empty()) return Dinv_r;
    const Eigen::Index p = 3 * static_cast<Eigen::Index>(active.size());
    Eigen::MatrixXd Us(m_, p);
    Eigen::MatrixXd S = Eigen::MatrixXd::Zero(p, p);
    for (std::size_t a = 0; a < active.size(); ++a) {
      const ContactValue& cv = contacts[active[a]];
      const Eigen::Index i = 3 * static_cast<Eigen::Index>(a);
      Us.middleCols<3>(i) = U[active[a]];
      S.block<3, 3>(i, i) = -g * (g * cv.S_x + cv.S_v);  // S' of (D + U S' U^T)
    }
    const Eigen::MatrixXd DinvU = Us.array().colwise() / D.array();
    const Eigen::MatrixXd core = Eigen::MatrixXd::Identity(p, p) + Us.transpose() * DinvU * S;
    return Dinv_r - DinvU * (S * core.partialPivLu().solve(Us.transpose() * Dinv_r));
  }

  /// Solves the stage Y = A + g f(t, Y) for its rates. Returns false when Newton's method does not converge.
  /// `guess`: a modal contact force to start Newton's method from (the last one known). `U_out`: the contacts'
  /// Phi^T J^T at the solution (for solve_newton).
  bool stage(const Frame& f, double g, const Eigen::VectorXd& A_eta, const Eigen::VectorXd& A_rate,
             const std::vector<ContactValue>& previous, const Eigen::VectorXd& guess, double tol, State& out,
             std::vector<Eigen::MatrixXd>* U_out = nullptr) {
    const Eigen::VectorXd D = Eigen::VectorXd::Ones(m_) + g * c_ + (g * g) * k_;
    const Eigen::VectorXd b0 = A_rate + g * (f.modal_input - k_.cwiseProduct(A_eta));
    Eigen::VectorXd Y = (b0 + g * guess).cwiseQuotient(D);
    std::vector<Eigen::MatrixXd> U;
    std::vector<ContactState> frozen;
    for (int it = 0; it < 25; ++it) {
      out.eta = A_eta + g * Y;
      evaluate_contacts(f, out.eta, Y, previous, out.contacts, out.contact_force, &U, it >= 3 ? &frozen : nullptr);
      if (it == 2) {
        frozen.clear();
        for (const ContactValue& cv : out.contacts) frozen.push_back(cv.state);
      }
      out.rate = Y;
      const Eigen::VectorXd r = D.cwiseProduct(Y) - b0 - g * out.contact_force;
      const bool any = std::any_of(U.begin(), U.end(), [](const Eigen::MatrixXd& u) { return u.size() != 0; });
      if (!any && it == 0 && out.contact_force.isZero(0.0) && guess.isZero(0.0)) {
        if (U_out) *U_out = U;
        return !deep_crossing_;  // no contact: exact
      }
      const Eigen::VectorXd delta = -solve_newton(D, g, out.contacts, U, r);
      const double step = std::sqrt(k_.dot((g * delta).cwiseProduct(g * delta)) + delta.squaredNorm());
      if (step <= 1e-3 * tol && it < 3) {
        // Y solves the stage to within the correction's size (1e-3 of the tolerance), and this evaluation decided
        // the contact set afresh (not frozen): Y is the solution, with this evaluation (no further one).
        if (U_out) *U_out = std::move(U);
        return !deep_crossing_;
      }
      Y += delta;
      if (step <= 1e-3 * tol) {
        out.eta = A_eta + g * Y;
        out.rate = Y;
        evaluate_contacts(f, out.eta, Y, previous, out.contacts, out.contact_force, U_out);
        return !deep_crossing_;
      }
    }
    return false;
  }

  /// One step of Alexander's SDIRK2 of length h from (t, y) (a contact flickers: see run()).
  bool step_sdirk2(double t, double h, const State& y, double tol, State& out) {
    const double g = gamma_sdirk2 * h;
    State Y1;
    if (!stage(frame(t + g), g, y.eta, y.rate, y.contacts, y.contact_force, tol, Y1)) return false;
    // f(Y1) = (Y1 - y) / g; stage 2: Y2 = y + (1 - gamma) h f(Y1) + g f(t + h, Y2).
    const double w = (1.0 - gamma_sdirk2) / gamma_sdirk2;
    const Eigen::VectorXd A_eta = y.eta + w * (Y1.eta - y.eta), A_rate = y.rate + w * (Y1.rate - y.rate);
    return stage(frame(t + h), g, A_eta, A_rate, y.contacts, Y1.contact_force, tol, out);
  }

  /// One TR-BDF2 step of length h from (t, y) into `out`; `err`: the embedded estimate of its local error (energy
  /// norm). Returns false when a stage's Newton iteration does not converge.
  bool step(double t, double h, const State& y, double tol, State& out, double& err) {
    if (!step_from(t, h, y, y.contact_force, tol, out, err)) return false;
    // A contact that begins within the step: its damper's force jumps from zero at the touch (F_n = c_n |g'| at
    // g = 0), a jump of f that the explicit first stage would see at the step's end only (and the error estimate
    // would shrink the step around it without end). The step is taken again with f at its start from the contact
    // law continued across g = 0 (the contacts of the step's end held on), as the implicit stages see it.
    std::vector<ContactState> held(slots_, ContactState::none);
    bool touched = false;
    for (std::size_t o = 0; o < slots_; ++o) {
      const ContactState before = y.contacts[o].state, after = out.contacts[o].state;
      touched = touched || (before == ContactState::none && after != ContactState::none);
      held[o] = before != ContactState::none ? before : after;
    }
    if (!touched) return true;
    std::vector<ContactValue> start;
    Eigen::VectorXd start_force;
    evaluate_contacts(frame(t), y.eta, y.rate, y.contacts, start, start_force, nullptr, &held);
    return step_from(t, h, y, start_force, tol, out, err);
  }

  /// The step from (t, y) with `start_force` the modal contact force in f at its start.
  bool step_from(double t, double h, const State& y, const Eigen::VectorXd& start_force, double tol, State& out,
                 double& err) {
    const double g = d_trbdf2 * h;
    // f at the step's start from its state (first same as last: the contact force of the last stage's final
    // evaluation).
    const Eigen::VectorXd f1_eta = y.rate;
    const Eigen::VectorXd f1_rate = frame(t).modal_input + start_force - c_.cwiseProduct(y.rate) -
                                    k_.cwiseProduct(y.eta);
    // Stage 2 (the trapezoidal rule to t + 2 d h): Y2 = y + g f1 + g f(Y2).
    const Eigen::VectorXd A2_eta = y.eta + g * f1_eta, A2_rate = y.rate + g * f1_rate;
    State Y2;
    if (!stage(frame(t + 2.0 * g), g, A2_eta, A2_rate, y.contacts, start_force, tol, Y2)) return false;
    const Eigen::VectorXd f2_eta = (Y2.eta - A2_eta) / g, f2_rate = (Y2.rate - A2_rate) / g;
    // Stage 3 (BDF2 to t + h): Y3 = y + w h (f1 + f2) + g f(Y3).
    const Eigen::VectorXd A3_eta = y.eta + (w_trbdf2 * h) * (f1_eta + f2_eta);
    const Eigen::VectorXd A3_rate = y.rate + (w_trbdf2 * h) * (f1_rate + f2_rate);
    std::vector<Eigen::MatrixXd> U;
    if (!stage(frame(t + h), g, A3_eta, A3_rate, y.contacts, Y2.contact_force, tol, out, &U)) return false;
    // h (b^ - b) . f, with b^ - b = ((1 - 4w) / 3, 1 / 3, -2d / 3) and f3 = (Y3 - A3) / g ...
    const double e1 = h * (1.0 - 4.0 * w_trbdf2) / 3.0, e2 = h / 3.0, e3 = -2.0 * d_trbdf2 * h / 3.0 / g;
    const Eigen::VectorXd e_eta = e1 * f1_eta + e2 * f2_eta + e3 * (out.eta - A3_eta);
    const Eigen::VectorXd e_rate = e1 * f1_rate + e2 * f2_rate + e3 * (out.rate - A3_rate);
    // ... filtered by (I - g df/dy)^-1 (Hosea & Shampine 1996; Shampine's estimate for stiff problems), so that the
    // stiff components (the penalty, the distal modes) count by their damped response, not by their raw rates.
    // With eta = e_eta + g x_rate, the rate rows read N x_rate = e_rate - g k e_eta + g U S_x U^T e_eta.
    Eigen::VectorXd rhs = e_rate - g * k_.cwiseProduct(e_eta);
    for (std::size_t o = 0; o < U.size(); ++o)
      if (U[o].size() != 0) rhs.noalias() += g * (U[o] * (out.contacts[o].S_x * (U[o].transpose() * e_eta)));
    const Eigen::VectorXd D = Eigen::VectorXd::Ones(m_) + g * c_ + (g * g) * k_;
    const Eigen::VectorXd x_rate = solve_newton(D, g, out.contacts, U, rhs);
    err = energy_norm(e_eta + g * x_rate, x_rate);
    return true;
  }

  TimeSeries run(const InitialState& initial) {
    TimeSeries ts;
    ts.model = ChainModel::nonlinear;
    const Eigen::Index n = model_.size();
    State y;
    y.eta = Eigen::VectorXd::Zero(m_);
    y.rate = Eigen::VectorXd::Zero(m_);
    const Eigen::MatrixXd Mphi = model_.mass * Phi_;
    if (initial.q.size() != 0) {
      if (initial.q.size() != n || (initial.q_dot.size() != 0 && initial.q_dot.size() != n))
        throw std::invalid_argument("initial state must have " + std::to_string(n) + " joint coordinates, got " +
                                    std::to_string(initial.q.size()));
      y.eta = Mphi.transpose() * initial.q;
      if (initial.q_dot.size() != 0) y.rate = Mphi.transpose() * initial.q_dot;
    } else if (!initial.undeformed) {
      y.eta = frame(0.0).modal_input.cwiseQuotient(k_);
    }
    {
      const std::vector<ContactValue> none(slots_);
      evaluate_contacts(frame(0.0), y.eta, y.rate, none, y.contacts, y.contact_force, nullptr);
      for (std::size_t o = 0; o < slots_; ++o)
        if (y.contacts[o].state != ContactState::none)
          ts.events.push_back(event(0.0, ContactEventType::touch, o, y.contacts[o]));
    }
    const long frames = static_cast<long>(std::floor(opt_.duration * opt_.output_rate * (1.0 + 1e-12))) + 1;
    ts.q.resize(n, frames);
    ts.contacts.assign(opt_.objects.size(), ContactChannels{});
    record(ts, 0, 0.0, y);

    double scale = energy_norm(y.eta, y.rate);
    // TR-BDF2 with its embedded estimate. A contact that flickers (six touches, releases, slip onsets or sticks
    // within a millisecond: a frictionless contact grazing the short, light links near the tip, where TR-BDF2's
    // trapezoidal stage leaves an alternating response in that very stiff contact; a frictional one at a slip ->
    // stick transition, where the elastic-plastic state decided on the explicit first stage's side flips back and
    // forth) switches to SDIRK2 with step doubling (each step also taken as two halves, which are kept; their
    // difference / 3 estimates their error), which passes it as one transition, until no object has been touched
    // for a millisecond (bench_dynamics' peg: 3,509 events with TR-BDF2 alone, 21 with SDIRK2; docs/dynamics.md,
    // "Integrator").
    bool sdirk2 = false, step_sdirk2_used = false;
    constexpr std::size_t flicker_events = 6;
    constexpr double flicker_window = 1e-3;  // [s]
    double last_touched = 0.0;
    State next, full, mid;
    integrate_with_step_control(
        opt_, frames, ts,
        [&](double t, double h) {
          const double tol =
              opt_.relative_tolerance * std::max(scale, energy_norm(y.eta, y.rate)) + opt_.absolute_tolerance;
          double err = 0.0;
          step_sdirk2_used = sdirk2;
          if (sdirk2) {
            if (!(step_sdirk2(t, h, y, tol, full) && step_sdirk2(t, 0.5 * h, y, tol, mid) &&
                  step_sdirk2(t + 0.5 * h, 0.5 * h, mid, tol, next)))
              return StepAttempt{false, 0.0, tol};
            return StepAttempt{true, energy_norm(next.eta - full.eta, next.rate - full.rate) / 3.0, tol};
          }
          if (!step(t, h, y, tol, next, err)) return StepAttempt{false, 0.0, tol};
          return StepAttempt{true, err, tol};
        },
        [&](double t, double h) {
          if (step_sdirk2_used) {
            note_events(ts, t, 0.5 * h, y, mid);
            note_events(ts, t + 0.5 * h, 0.5 * h, mid, next);
          } else {
            note_events(ts, t, h, y, next);
            const std::size_t e = transitions_.size();
            if (e >= flicker_events && transitions_[e - 1] - transitions_[e - flicker_events] < flicker_window)
              sdirk2 = true;
          }
          if (std::any_of(next.contacts.begin(), next.contacts.end(),
                          [](const ContactValue& c) { return c.state != ContactState::none; }))
            last_touched = t + h;
          else if (sdirk2 && t + h - last_touched > flicker_window)
            sdirk2 = false;
          y = next;
          scale = std::max(scale, energy_norm(y.eta, y.rate));
        },
        [&](long f, double t_out) { record(ts, f, t_out, y); });
    return ts;
  }

 private:
  ContactEvent event(double t, ContactEventType type, std::size_t slot, const ContactValue& cv) const {
    return ContactEvent{t, type, static_cast<int>(object_of_[slot]), cv.arc_length, cv.point_W, cv.force_W};
  }

  void note_events(TimeSeries& ts, double t0, double h, const State& a, const State& b) {
    for (std::size_t o = 0; o < slots_; ++o) {
      const ContactValue &p = a.contacts[o], &c = b.contacts[o];
      ts.max_penetration = std::max(ts.max_penetration, -c.gap);
      const bool was = p.state != ContactState::none, is = c.state != ContactState::none;
      // A touch or a release: where the gap crosses zero, linearly within the step.
      auto crossing = [&] {
        const double d = p.gap - c.gap;
        return d != 0.0 ? t0 + h * std::clamp(p.gap / d, 0.0, 1.0) : t0 + h;
      };
      if (!was && is) {
        const double t = crossing();
        transitions_.push_back(t);
        // Events are contact episodes: a release shorter than release_merge_time is not reported, the contact
        // goes on (the per-frame contact state keeps the separation). Such releases come from the contact passing
        // the nodes between links as it slides off (1-100 us each, every 0.1-0.4 ms in the array against the
        // peg), grazing within a few 1e-11 m near the tip (ns), and bounces at a touch (~10 us).
        const auto last = std::find_if(ts.events.rbegin(), ts.events.rend(),
                                       [&](const ContactEvent& e) { return e.object == static_cast<int>(object_of_[o]); });
        if (last != ts.events.rend() && last->type == ContactEventType::release && t - last->time < release_merge_time)
          ts.events.erase(std::next(last).base());
        else
          ts.events.push_back(event(t, ContactEventType::touch, o, c));
      } else if (was && !is) {
        transitions_.push_back(crossing());
        ts.events.push_back(event(crossing(), ContactEventType::release, o, p));
      }
      if (friction_coefficient(opt_.objects[object_of_[o]]) > 0.0 && is) {
        if (c.state == ContactState::slip && p.state != ContactState::slip) {
          transitions_.push_back(t0 + h);
          ts.events.push_back(event(t0 + h, ContactEventType::slip, o, c));
        } else if (c.state == ContactState::stick && p.state == ContactState::slip) {
          transitions_.push_back(t0 + h);
          ts.events.push_back(event(t0 + h, ContactEventType::stick, o, c));
        }
      }
    }
  }

  void record(TimeSeries& ts, long f, double t, const State& s) {
    const Frame fr = frame(t);
    const BaseMotion& b = fr.base;
    const Eigen::Matrix<double, base_input_size, 1> u = base_input(b, gravity_);
    const Eigen::VectorXd acc = fr.modal_input + s.contact_force - c_.cwiseProduct(s.rate) - k_.cwiseProduct(s.eta);
    Eigen::Matrix<double, 6, 1> wrench = model_.base_from_input * u + model_.base_from_acceleration * (Phi_ * acc);
    for (const ContactValue& cv : s.contacts) {
      wrench.head<3>() += cv.force_B;
      wrench.tail<3>() += (cv.x_B - w_.rest_nodes_B()[0]).cross(cv.force_B);
    }
    ts.time.push_back(t);
    ts.force_B.push_back(wrench.head<3>());
    ts.moment_B.push_back(wrench.tail<3>());
    ts.force_W.push_back(b.R_WB * wrench.head<3>());
    ts.moment_W.push_back(b.R_WB * wrench.tail<3>());
    ts.q.col(f) = joint_coordinates(fr, s);
    chain_kinematics(w_, q_, kin_);
    ts.kinetic_energy.push_back(0.5 * s.rate.squaredNorm());
    double elastic = 0.5 * k_.dot(s.eta.cwiseProduct(s.eta));
    if (truncated_) {  // the static part is K-orthogonal to the modes kept
      const Eigen::VectorXd q_static = q_ - Phi_ * s.eta;
      elastic += 0.5 * q_static.dot(model_.stiffness * q_static);
    }
    ts.elastic_energy.push_back(elastic);
    const std::size_t N = kin_.nodes_B.size() - 1;
    ts.tip_displacement_B.push_back(kin_.nodes_B[N] - w_.rest_nodes_B()[N]);
    const Placement X(b.R_WB, b.p_W_base);
    ts.placements.push_back(X);
    if (opt_.record_nodes) {
      std::vector<Eigen::Vector3d> nodes(N + 1);
      for (std::size_t i = 0; i <= N; ++i) nodes[i] = X.to_world(kin_.nodes_B[i]);
      ts.nodes_W.push_back(std::move(nodes));
    }
    // Per object: its deepest slot's state, gap and point, and the force of all its slots.
    for (std::size_t k = 0; k < ts.contacts.size(); ++k) {
      const ContactValue* deepest = nullptr;
      Eigen::Vector3d force_W = Eigen::Vector3d::Zero();
      for (std::size_t o = 0; o < s.contacts.size(); ++o) {
        if (object_of_[o] != k) continue;
        const ContactValue& cv = s.contacts[o];
        force_W += cv.force_W;
        const bool on = cv.state != ContactState::none;
        if (!deepest || (on && deepest->state == ContactState::none) ||
            (on == (deepest->state != ContactState::none) && cv.gap < deepest->gap))
          deepest = &cv;
      }
      ContactChannels& ch = ts.contacts[k];
      ch.state.push_back(deepest->state);
      ch.arc_length.push_back(deepest->arc_length);
      ch.gap.push_back(deepest->gap);
      ch.point_W.push_back(deepest->point_W);
      ch.force_W.push_back(force_W);
    }
  }

  const Whisker& w_;
  const LinearModel& model_;
  Eigen::MatrixXd Phi_;  ///< the modes integrated (the lowest m_ of the model's)
  const BaseTrajectory& base_;
  Eigen::Vector3d gravity_;
  const SimulationOptions& opt_;
  Eigen::VectorXd k_, c_;
  Eigen::MatrixXd P_;
  Eigen::Index m_ = 0;
  bool truncated_ = false;               ///< fewer modes than coordinates: static correction (R below)
  std::vector<Eigen::Matrix3d> K_inv_;   ///< the joints' compliances (truncated basis only)
  Eigen::MatrixXd static_input_;         ///< R G (truncated basis only)
  double kn_ = 0.0, kt_ = 0.0;
  bool deep_crossing_ = false;  ///< the last evaluation found a line crossed deeper than kMaxCrossing
  std::vector<LineObstacle> objects_;           ///< the line objects (the first slots)
  std::vector<SurfaceObstacle> surfaces_;       ///< the surfaces (surface_slots slots each, after the lines')
  static constexpr std::size_t surface_slots = 2;  ///< contact points per surface
  std::vector<std::size_t> object_of_;          ///< slot -> index into SimulationOptions::objects
  std::size_t slots_ = 0;
  std::vector<int> hold_link_;                  ///< per slot: the link a held surface contact stays near (-1: none)
  std::vector<Eigen::Vector3d> nodes_W_;
  std::vector<double> transitions_;  ///< times of every touch and release, reported or not (the flicker switch)
  static constexpr double release_merge_time = 1e-4;  // [s]
  Eigen::VectorXd q_;
  Eigen::Matrix<double, Eigen::Dynamic, 3> Jt_;
  ChainKinematics kin_;
};

}  // namespace

TimeSeries simulate_nonlinear(const Whisker& w, const LinearModel& model, const Modes& modes,
                              const BaseTrajectory& base, const Eigen::Vector3d& gravity_W,
                              const SimulationOptions& options, const InitialState& initial) {
  validate(options.contact);
  for (const Obstacle& o : options.objects) validate(o);
  if (modes.count() != model.size())
    throw std::invalid_argument("simulate needs all " + std::to_string(model.size()) + " modes of the model, got " +
                                std::to_string(modes.count()));
  Integrator integrator(w, model, modes, base, gravity_W, options);
  return integrator.run(initial);
}

}  // namespace vibrissa::dynamics::detail
