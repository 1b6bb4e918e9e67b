// Time integration of the linearised chain (include/vibrissa/dynamics/simulate.hpp).
#include "vibrissa/dynamics/simulate.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

#include <Eigen/Cholesky>

#include "vibrissa/core/checks.hpp"
#include "vibrissa/core/limits.hpp"
#include "nonlinear_simulate.hpp"
#include "step_control.hpp"
#include "vibrissa/dynamics/air_drag.hpp"

namespace vibrissa::dynamics {
namespace {

Eigen::Vector3d vee(const Eigen::Matrix3d& m) {  // axial vector of the skew part
  return 0.5 * Eigen::Vector3d(m(2, 1) - m(1, 2), m(0, 2) - m(2, 0), m(1, 0) - m(0, 1));
}

using Input = Eigen::Matrix<double, base_input_size, 1>;

/// Modal state: displacement and rate of every mode.
struct State {
  Eigen::VectorXd eta, rate;
};

}  // namespace

std::string_view to_string(SimulationStatus s) {
  switch (s) {
    case SimulationStatus::completed: return "completed";
    case SimulationStatus::max_steps: return "max_steps";
    case SimulationStatus::step_too_small: return "step_too_small";
  }
  return "unknown";
}

std::string_view to_string(ChainModel m) {
  switch (m) {
    case ChainModel::automatic: return "automatic";
    case ChainModel::linear: return "linear";
    case ChainModel::nonlinear: return "nonlinear";
  }
  return "unknown";
}

BaseTrajectory trajectory_from_placements(std::function<Placement(double)> placement, double h) {
  if (!(std::isfinite(h) && h > 0.0))
    throw std::invalid_argument("trajectory difference step h must be positive [s], got " + format_value(h));
  return [placement = std::move(placement), h](double t) {
    const Placement m2 = placement(t - 2 * h), m1 = placement(t - h), c = placement(t), p1 = placement(t + h),
                    p2 = placement(t + 2 * h);
    BaseMotion out;
    out.R_WB = c.R_WB;
    out.p_W_base = c.p_W_base;
    const double d1 = 1.0 / (12.0 * h), d2 = 1.0 / (12.0 * h * h);
    out.velocity_W = d1 * (-p2.p_W_base + 8.0 * p1.p_W_base - 8.0 * m1.p_W_base + m2.p_W_base);
    out.acceleration_W =
        d2 * (-p2.p_W_base + 16.0 * p1.p_W_base - 30.0 * c.p_W_base + 16.0 * m1.p_W_base - m2.p_W_base);
    const Eigen::Matrix3d Rd = d1 * (-p2.R_WB + 8.0 * p1.R_WB - 8.0 * m1.R_WB + m2.R_WB);
    const Eigen::Matrix3d Rdd = d2 * (-p2.R_WB + 16.0 * p1.R_WB - 30.0 * c.R_WB + 16.0 * m1.R_WB - m2.R_WB);
    // R' = [Omega]x R and R'' = ([alpha]x + [Omega]x^2) R (world axes).
    out.omega_W = vee(Rd * c.R_WB.transpose());
    const Eigen::Matrix3d W = Rdd * c.R_WB.transpose();
    out.alpha_W = vee(W);
    return out;
  };
}

BaseTrajectory fixed_base(const Placement& placement) {
  return [placement](double) {
    BaseMotion m;
    m.R_WB = placement.R_WB;
    m.p_W_base = placement.p_W_base;
    return m;
  };
}

void validate(const SimulationOptions& o) {
  auto positive = [](double v, const char* field, const char* unit) {
    if (!(std::isfinite(v) && v > 0.0))
      throw std::invalid_argument(std::string(field) + " must be positive and finite " + unit + ", got " +
                                  format_value(v));
  };
  positive(o.duration, "duration", "[s]");
  positive(o.output_rate, "output_rate", "[Hz]");
  positive(o.relative_tolerance, "relative_tolerance", "");
  if (!(std::isfinite(o.absolute_tolerance) && o.absolute_tolerance >= 0.0))
    throw std::invalid_argument("absolute_tolerance must be >= 0 and finite [sqrt(J)], got " +
                                format_value(o.absolute_tolerance));
  if (!(std::isfinite(o.max_step) && o.max_step >= 0.0))
    throw std::invalid_argument("max_step must be >= 0 and finite [s], got " + format_value(o.max_step));
  if (o.modes < 0) throw std::invalid_argument("modes must be >= 0 (0: all), got " + std::to_string(o.modes));
  if (o.max_steps < 1) throw std::invalid_argument("max_steps must be >= 1, got " + std::to_string(o.max_steps));
  if (o.duration * o.output_rate + 1.0 > static_cast<double>(limits::max_array_frames))
    throw std::invalid_argument("duration * output_rate must give at most " +
                                std::to_string(limits::max_array_frames) + " frames, got " +
                                format_value(o.duration * o.output_rate + 1.0));
}

TimeSeries simulate(const Whisker& w, const LinearModel& model, const Modes& modes, const BaseTrajectory& base,
                    const Eigen::Vector3d& gravity_W, const SimulationOptions& opt, const InitialState& initial,
                    const ExternalLoad& external) {
  validate(opt);
  const bool nonlinear =
      opt.model == ChainModel::nonlinear || (opt.model == ChainModel::automatic && !opt.objects.empty());
  if (!nonlinear && !opt.objects.empty())
    throw std::invalid_argument("model \"linear\" cannot touch objects (" + std::to_string(opt.objects.size()) +
                                " given): use \"nonlinear\" or \"automatic\"");
  if (nonlinear && external)
    throw std::invalid_argument("air drag (an external load) acts in the linear model only, not yet in the nonlinear "
                                "chain with objects: set dynamics.air_drag false or model \"linear\"");
  if (nonlinear) return detail::simulate_nonlinear(w, model, modes, base, gravity_W, opt, initial);
  const Eigen::Index n = model.size(), m = modes.count();
  if (m != n)
    throw std::invalid_argument("simulate needs all " + std::to_string(n) + " modes of the model, got " +
                                std::to_string(m));
  const Eigen::MatrixXd& Phi = modes.joint_shapes;
  const Eigen::VectorXd k = modes.omega.cwiseProduct(modes.omega);
  const Eigen::VectorXd c = 2.0 * modes.damping_ratio.cwiseProduct(modes.omega);
  const Eigen::MatrixXd P = Phi.transpose() * model.input;  // modal force per unit input
  const Eigen::MatrixXd Mphi = model.mass * Phi;          // eta = Phi^T M q
  auto modal_force = [&](double t) -> Eigen::VectorXd {
    Eigen::VectorXd p = P * base_input(base(t), gravity_W);
    if (external) {
      Eigen::VectorXd Q = Eigen::VectorXd::Zero(n);
      Eigen::Matrix<double, 6, 1> unused = Eigen::Matrix<double, 6, 1>::Zero();
      external(t, Q, unused);
      p.noalias() += Phi.transpose() * Q;
    }
    return p;
  };

  State y{Eigen::VectorXd::Zero(m), Eigen::VectorXd::Zero(m)};
  if (initial.q.size() != 0) {
    if (initial.q.size() != n || (initial.q_dot.size() != 0 && initial.q_dot.size() != n))
      throw std::invalid_argument("initial state must have " + std::to_string(n) + " joint coordinates, got " +
                                  std::to_string(initial.q.size()));
    y.eta = Mphi.transpose() * initial.q;
    if (initial.q_dot.size() != 0) y.rate = Mphi.transpose() * initial.q_dot;
  } else if (!initial.undeformed) {
    const Eigen::VectorXd p0 = modal_force(0.0);
    y.eta = p0.cwiseQuotient(k);
  }
  auto energy_norm2 = [&](const Eigen::VectorXd& eta, const Eigen::VectorXd& rate) {
    return k.dot(eta.cwiseProduct(eta)) + rate.squaredNorm();
  };

  // One trapezoidal step of every mode: (1 + hc/2 + h^2 k/4) v1 = (1 - hc/2 - h^2 k/4) v0 + h (p0 + p1)/2 - h k e0,
  // e1 = e0 + h (v0 + v1) / 2.
  auto step = [&](const State& s, double h, const Eigen::VectorXd& p0, const Eigen::VectorXd& p1) {
    State out{Eigen::VectorXd(m), Eigen::VectorXd(m)};
    for (Eigen::Index i = 0; i < m; ++i) {
      const double a = 0.5 * h * c(i) + 0.25 * h * h * k(i);
      const double v1 = ((1.0 - a) * s.rate(i) + 0.5 * h * (p0(i) + p1(i)) - h * k(i) * s.eta(i)) / (1.0 + a);
      out.eta(i) = s.eta(i) + 0.5 * h * (s.rate(i) + v1);
      out.rate(i) = v1;
    }
    return out;
  };

  TimeSeries ts;
  const long frames = static_cast<long>(std::floor(opt.duration * opt.output_rate * (1.0 + 1e-12))) + 1;
  const std::size_t N = static_cast<std::size_t>(w.links());
  if (opt.record_nodes && static_cast<double>(frames) * static_cast<double>(3 * (N + 1)) >
                              static_cast<double>(limits::max_array_elements))
    throw std::invalid_argument("the node positions of " + std::to_string(frames) + " frames of " +
                                std::to_string(N + 1) + " nodes exceed " + std::to_string(limits::max_array_elements) +
                                " values: lower output_rate or duration, or links");
  ts.q.resize(n, frames);
  auto record = [&](long f, double t, const State& s, const Eigen::VectorXd& p) {
    const BaseMotion b = base(t);
    const Input u = base_input(b, gravity_W);
    const Eigen::VectorXd acc = p - c.cwiseProduct(s.rate) - k.cwiseProduct(s.eta);
    Eigen::Matrix<double, 6, 1> wrench = model.base_from_input * u + model.base_from_acceleration * (Phi * acc);
    if (external) {
      Eigen::VectorXd unused = Eigen::VectorXd::Zero(n);
      external(t, unused, wrench);
    }
    ts.time.push_back(t);
    ts.force_B.push_back(wrench.head<3>());
    ts.moment_B.push_back(wrench.tail<3>());
    ts.force_W.push_back(b.R_WB * wrench.head<3>());
    ts.moment_W.push_back(b.R_WB * wrench.tail<3>());
    const Eigen::VectorXd q = Phi * s.eta;
    ts.q.col(f) = q;
    ts.kinetic_energy.push_back(0.5 * s.rate.squaredNorm());
    ts.elastic_energy.push_back(0.5 * k.dot(s.eta.cwiseProduct(s.eta)));
    const Eigen::Index tip = static_cast<Eigen::Index>(3 * N);
    ts.tip_displacement_B.push_back(model.node_displacement.middleRows<3>(tip) * q);
    const Placement X(b.R_WB, b.p_W_base);
    ts.placements.push_back(X);
    if (opt.record_nodes) {
      const Eigen::VectorXd d = model.node_displacement * q;
      std::vector<Eigen::Vector3d> nodes(N + 1);
      for (std::size_t i = 0; i <= N; ++i)
        nodes[i] = X.to_world(w.rest_nodes_B()[i] + d.segment<3>(static_cast<Eigen::Index>(3 * i)));
      ts.nodes_W.push_back(std::move(nodes));
    }
  };

  Eigen::VectorXd p_t = modal_force(0.0), p_end;
  record(0, 0.0, y, p_t);
  double scale = std::sqrt(energy_norm2(y.eta, y.rate));
  State half;
  detail::integrate_with_step_control(
      opt, frames, ts,
      [&](double t, double h) {
        const Eigen::VectorXd p_half = modal_force(t + 0.5 * h);
        p_end = modal_force(t + h);
        const State full = step(y, h, p_t, p_end);
        half = step(step(y, 0.5 * h, p_t, p_half), 0.5 * h, p_half, p_end);
        const double err = std::sqrt(energy_norm2(half.eta - full.eta, half.rate - full.rate)) / 3.0;
        const double tol = opt.relative_tolerance * std::max(scale, std::sqrt(energy_norm2(half.eta, half.rate))) +
                           opt.absolute_tolerance;
        return detail::StepAttempt{true, err, tol};
      },
      [&](double, double) {
        y = half;
        p_t = p_end;
        scale = std::max(scale, std::sqrt(energy_norm2(y.eta, y.rate)));
      },
      [&](long f, double t_out) { record(f, t_out, y, p_t); });
  return ts;
}

TimeSeries simulate(const Whisker& w, const DynamicsProperties& props, const BaseTrajectory& base,
                    const SimulationOptions& options, const InitialState& initial) {
  const LinearModel model = linear_model(w, props);
  const Modes all = modes(model, w);
  return simulate(w, model, all, base, props.gravity_W, options, initial,
                  props.air_drag ? air_drag_load(w, base, props.air) : ExternalLoad{});
}

}  // namespace vibrissa::dynamics
