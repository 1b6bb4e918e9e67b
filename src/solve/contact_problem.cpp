#include "contact_problem.hpp"

#include "vibrissa/solve/solvers.hpp"
#include "vibrissa/solve/whisker_frame_signals.hpp"

#include <cmath>
#include <numbers>
#include <vector>

namespace vibrissa::detail {

LMBounds contact_bounds() {
  LMBounds b;
  b.lower[2] = 1e-9;
  b.upper[2] = 1.5;
  return b;
}

Eigen::Vector3d unknowns_from_state(const LoadState& s, const Scales& sc) {
  return {s.force_y / sc.force, s.force_z / sc.force, s.arc_length / sc.length};
}

LoadState state_from_unknowns(const Eigen::Vector3d& u, const Scales& sc) {
  const Eigen::Vector3d load = sc.load(u);  // the numbers the walk was given (a record's key)
  LoadState s;
  s.force_y = load[0];
  s.force_z = load[1];
  s.arc_length = load[2];
  return s;
}

void normal_basis(const Eigen::Vector3d& d, Eigen::Vector3d& e1, Eigen::Vector3d& e2) {
  const Eigen::Vector3d helper = std::abs(d.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  e1 = (helper - helper.dot(d) * d).normalized();
  e2 = d.cross(e1);
}

namespace {
/// Per-thread scratch of fill_solution: joint rotations and deflected nodes, grown once per thread.
struct Workspace {
  std::vector<Eigen::Vector3d> omega, nodes_B;
};
Workspace& workspace() {
  thread_local Workspace ws;
  return ws;
}

/// Deflected nodes in B into ws.nodes_B.
void shape_B(const Whisker& w, const LoadState& state, Workspace& ws) {
  const V3<double> F_L(state.force_x, state.force_y, state.force_z);
  const V3<double> C_L(state.couple_x, state.couple_y, state.couple_z);
  if (w.properties().scheme == Scheme::paper) {
    published_nodes_B(w, F_L, C_L, state.arc_length, ws.nodes_B);
    return;
  }
  ws.omega.resize(static_cast<std::size_t>(w.links()));
  deflect<double>(w, F_L, C_L, state.arc_length, ws.omega.data());
  deflected_nodes_B(w, ws.omega.data(), ws.nodes_B);
}
}  // namespace

double force_angle(const Whisker& w, const Placement& X, const LoadState& state) {
  if (w.properties().scheme != Scheme::paper) return std::atan2(state.force_z, state.force_y);
  const double zeta = std::atan2(-state.force_z, -state.force_y) - published_angle_offset(w, X.R_WB, state.arc_length);
  return std::remainder(zeta, 2.0 * std::numbers::pi);
}

void set_force_angle(const Whisker& w, const Placement& X, double force, double angle, LoadState& state) {
  state.force_x = 0.0;
  if (w.properties().scheme != Scheme::paper) {
    state.force_y = force * std::cos(angle);
    state.force_z = force * std::sin(angle);
    return;
  }
  const double a = angle + published_angle_offset(w, X.R_WB, state.arc_length);
  state.force_y = -force * std::cos(a);
  state.force_z = -force * std::sin(a);
}

void fill_solution(const Whisker& w, const Placement& X, const LoadState& state, const SolveOptions& options,
                   const std::optional<Eigen::Vector3d>& edge_direction_W, Solution& out,
                   const ContactEvaluations* evaluated, const ContactKinematics<double>* kinematics) {
  Workspace& ws = workspace();
  auto& omega = ws.omega;
  const bool walk_for_shape = options.compute_shape && w.properties().scheme != Scheme::paper;
  std::optional<ContactKinematics<double>> known;
  if (evaluated && !walk_for_shape) known = evaluated->at(state);
  if (kinematics && !walk_for_shape) known = *kinematics;
  if (!known) {
    if (walk_for_shape) omega.resize(static_cast<std::size_t>(w.links()));
    const V3<double> F_L(state.force_x, state.force_y, state.force_z);
    const V3<double> C_L(state.couple_x, state.couple_y, state.couple_z);
    known = deflect<double>(w, F_L, C_L, state.arc_length, walk_for_shape ? omega.data() : nullptr);
  }
  const ContactKinematics<double>& c = *known;
  const Eigen::Vector3d p_B = to_eigen(c.p_contact_B), F_B = to_eigen(c.force_B);
  Eigen::Vector3d M_B = p_B.cross(F_B);
  if (state.couple_x != 0.0 || state.couple_y != 0.0 || state.couple_z != 0.0) M_B += to_eigen(c.couple_B);
  out.state = state;
  if (evaluated && state.sensitivity.whisker == 0)
    out.state.sensitivity = evaluated->sensitivity_at(w, state);
  out.arc_length = state.arc_length;
  out.force_magnitude = F_B.norm();
  out.angle = force_angle(w, X, state);
  out.contact_point_W = X.to_world(p_B);
  out.force_W = X.R_WB * F_B;
  out.moment_W = X.R_WB * M_B;
  out.whisker_frame = whisker_frame_signals(F_B, M_B);
  if (edge_direction_W) {
    const Eigen::Vector3d d = edge_direction_W->normalized();
    out.edge_force = out.force_W.dot(d);
    out.normal_force = (out.force_W - *out.edge_force * d).norm();
  }
  out.shape_W.clear();
  if (options.compute_shape) {
    if (w.properties().scheme == Scheme::paper) shape_B(w, state, ws);
    else deflected_nodes_B(w, omega.data(), ws.nodes_B);  // the joint rotations of the walk above
    out.shape_W.reserve(ws.nodes_B.size());
    for (const auto& p : ws.nodes_B) out.shape_W.push_back(X.to_world(p));
  }
}

}  // namespace vibrissa::detail

namespace vibrissa {
void deflected_shape(const Whisker& w, const Placement& X, const LoadState& state, std::vector<Eigen::Vector3d>& nodes_W) {
  detail::Workspace& ws = detail::workspace();
  detail::shape_B(w, state, ws);
  nodes_W.resize(ws.nodes_B.size());
  for (std::size_t i = 0; i < ws.nodes_B.size(); ++i) nodes_W[i] = X.to_world(ws.nodes_B[i]);
}
}  // namespace vibrissa

namespace vibrissa::detail {

void set_status(Solution& out, Status status, std::string_view message) {
  out.status = status;
  out.message = message;
  switch (status) {
    case Status::converged:
    case Status::second_contact:
    case Status::underdetermined: out.contact_state = ContactState::contact; break;
    case Status::slipped_off: out.contact_state = ContactState::pushed_past; break;
    case Status::no_contact:
    case Status::not_converged: out.contact_state = ContactState::free; break;
  }
}

Solution unloaded_solution(const Whisker& w, const Placement& X, Status status, std::string_view message,
                           const SolveOptions& options) {
  Solution out;
  LoadState rest;
  rest.arc_length = 0.0;
  fill_solution(w, X, rest, options, std::nullopt, out);
  out.contact_point_W = X.p_W_base;
  set_status(out, status, message);
  return out;
}

double arc_length_at_distance(const Whisker& w, double distance, const Eigen::Vector3d& along) {
  const auto& nodes = w.rest_nodes_B();
  const auto& arc = w.node_arc_lengths();
  auto from_base = [&](const Eigen::Vector3d& p) { return (p - p.dot(along) * along).norm(); };
  for (std::size_t i = 1; i < nodes.size(); ++i) {
    const double d1 = from_base(nodes[i]);
    if (d1 >= distance) {
      const double d0 = from_base(nodes[i - 1]);
      const double f = (distance - d0) / std::max(d1 - d0, 1e-300);
      return arc[i - 1] + std::clamp(f, 0.0, 1.0) * (arc[i] - arc[i - 1]);
    }
  }
  return w.length();
}

double cantilever_compliance(const Whisker& w, double s) {
  const auto& arc = w.node_arc_lengths();
  const auto& cb = w.bending_compliance();
  const auto& weight = w.joint_weight();
  double c = w.base_extra_compliance() * s * s;
  for (std::size_t j = 0; j < cb.size() && arc[j] < s; ++j) c += weight[j] * cb[j] * (s - arc[j]) * (s - arc[j]);
  return c;
}

std::optional<Eigen::Vector3d> cantilever_start(const Whisker& w, const Scales& sc, const Eigen::Vector3d& target_B,
                                                const Eigen::Vector3d& along) {
  auto across = [&](const Eigen::Vector3d& p) { return p - p.dot(along) * along; };
  const double s = arc_length_at_distance(w, across(target_B).norm(), along);
  const Eigen::Vector3d p = w.rest_point_B(s);
  const double turn = std::atan2(across(p).cross(across(target_B)).norm(), across(p).dot(across(target_B)));
  if (!(turn <= max_cantilever_turn)) return std::nullopt;
  const Eigen::Vector3d displacement_B = across(target_B - p);
  const double c = cantilever_compliance(w, s);
  if (!(c > 0.0)) return Eigen::Vector3d(0.0, 0.0, s / sc.length);
  const Eigen::Vector3d F_B = displacement_B / (c * sc.force);
  if (w.properties().scheme == Scheme::paper) {  // its unknowns are components in Elastica3D's load frame
    const Axes<double> frame = published_rest_load_frame(w, s);
    return Eigen::Vector3d(F_B.dot(to_eigen(frame.y)), F_B.dot(to_eigen(frame.z)), s / sc.length);
  }
  int k;
  double h;
  w.locate(s, k, h);
  const Eigen::Matrix3d& R = w.rest_link_frames_B()[static_cast<std::size_t>(k)];  // tangent, normal, binormal
  return Eigen::Vector3d(F_B.dot(R.col(1)), F_B.dot(R.col(2)), s / sc.length);
}

}  // namespace vibrissa::detail
