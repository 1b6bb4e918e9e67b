#include "vibrissa/array/simulation.hpp"

#include <omp.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <exception>
#include <limits>
#include <mutex>
#include <optional>

#include "array_util.hpp"
#include "vibrissa/contact/tracker.hpp"
#include "vibrissa/array/error_bound.hpp"
#include "vibrissa/solve/solvers.hpp"
#include "vibrissa/dynamics/air_drag.hpp"
#include "vibrissa/dynamics/simulate.hpp"
#include "vibrissa/solve/whisker_frame_signals.hpp"

namespace vibrissa::array {
namespace {

constexpr double kRenderHalfLength = 0.04;  // infinite edges are drawn ±40 mm about their point [m]

// Everything that does not depend on the (pitch, whisker) pair being run, shared read-only by all threads.
struct Prepared {
  std::vector<Whisker> rest;                    // per whisker, frame B at the origin
  std::vector<std::vector<Eigen::Matrix3d>> R_HB;  // [whisker][frame]
  std::vector<std::vector<HeadPose>> head;       // [pitch][frame]
  std::vector<std::vector<std::vector<EdgeSegment>>> edges;  // [pitch][frame][edge]
  std::vector<std::vector<std::vector<PlacedShape>>> shapes;  // [pitch][frame][object] (scenes of surfaces)
  bool surfaces = false;
  std::vector<int> render_index;                 // frame -> index among rendered frames, or -1
  std::vector<std::vector<dynamics::Obstacle>> obstacles;  // [pitch][edge] (--dynamics: contact during motion)
};

void put3(std::vector<double>& v, std::size_t i, const Eigen::Vector3d& x) {
  v[3 * i] = x.x();
  v[3 * i + 1] = x.y();
  v[3 * i + 2] = x.z();
}

// The run of one whisker at one head pitch, in time order (contact history needs it): the rest whisker is
// placed at each frame and the ContactTracker (contact/tracker.hpp) decides onset, solve, push-past and release.
class PairRun {
 public:
  PairRun(const SimulationConfig& c, const Prepared& prep, ArrayResult& r, std::size_t p, std::size_t w)
      : c_(c), prep_(prep), r_(r), p_(p), w_(w), spec_(c.morphology.whiskers[w]), rest_(prep.rest[w]),
        tracker_(rest_, tracker_options(c)) {}

  static TrackerOptions tracker_options(const SimulationConfig& c) {
    TrackerOptions o;
    o.mode = c.mode;
    o.mu = c.mu;
    o.solve.tolerance = c.tolerance;
    o.solve.max_iterations = c.max_iterations;
    o.solve.compute_shape = false;
    o.thickness = c.thickness;
    return o;
  }

  void run() {
    const bool render_run = p_ == static_cast<std::size_t>(c_.render_pitch);
    for (std::size_t f = 0; f < r_.n_frames; ++f) {
      const HeadPose& H = prep_.head[p_][f];
      const Placement X(H.R_WH * prep_.R_HB[w_][f], H.point_to_world(spec_.p_H_base));
      const std::size_t k = r_.index(p_, w_, f);
      put3(r_.base_W, k, X.p_W_base);
      const TrackedFrame& fr =
          prep_.surfaces ? tracker_.step(X, prep_.shapes[p_][f]) : tracker_.step(X, prep_.edges[p_][f]);
      r_.state[k] = static_cast<std::int8_t>(fr.state);
      if (fr.solved) {
        r_.solver_status[k] = static_cast<std::int8_t>(fr.solution.status);
        r_.edge[k] = static_cast<std::int16_t>(fr.edge);
      }
      if (fr.state == ContactState::contact) record(k, fr);
      if (render_run && prep_.render_index[f] >= 0) render(f, X, fr);
    }
  }

  [[nodiscard]] std::size_t solves() const { return tracker_.solves(); }
  [[nodiscard]] std::size_t failed() const { return tracker_.failed_solves(); }

 private:
  void record(std::size_t k, const TrackedFrame& fr) {
    const Solution& s = fr.solution;
    put3(r_.contact_W, k, s.contact_point_W);
    put3(r_.force_W, k, s.force_W);
    put3(r_.moment_W, k, s.moment_W);
    put3(r_.force_B, k, s.whisker_frame.force);
    put3(r_.moment_B, k, s.whisker_frame.moment);
    r_.s_applied[k] = s.arc_length;
    r_.FT[k] = s.whisker_frame.FT;
    r_.MB[k] = s.whisker_frame.MB;
    r_.FD[k] = s.whisker_frame.FD;
    r_.MD[k] = s.whisker_frame.MD;
    r_.normal_force[k] = s.normal_force.value_or(0.0);
    r_.edge_force[k] = s.surface ? s.surface->friction_force : s.edge_force.value_or(0.0);
    r_.z_edge[k] = fr.edge_coordinate;
    // eq. (7): error bound on the contact position along the edge for friction coefficient mu.
    r_.z_error[k] = contact_error_bound(fr.edge_coordinate - fr.onset_edge_coordinate, c_.mu, r_.normal_force[k],
                                       s.arc_length, spec_.arc_length, spec_.base_radius, spec_.taper_ratio,
                                       spec_.youngs_modulus);
  }

  // Rest and deflected shapes of a rendered frame (the deflected shape recomputed from the solved state).
  void render(std::size_t f, const Placement& X, const TrackedFrame& fr) {
    const std::size_t ri = static_cast<std::size_t>(prep_.render_index[f]);
    const auto& nodes_B = rest_.rest_nodes_B();
    const std::size_t n = nodes_B.size();
    std::vector<Eigen::Vector3d> bent;
    if (fr.state == ContactState::contact) {
      if (fr.solution.second_contact) bent = fr.solution.shape_W;  // two contacts: not the state's load alone
      else deflected_shape(rest_, X, fr.solution.state, bent);
    }
    for (std::size_t i = 0; i < n; ++i) {
      const std::size_t at = ((ri * r_.n_whiskers + w_) * n + i) * 3;
      const Eigen::Vector3d rest = X.to_world(nodes_B[i]);
      const Eigen::Vector3d& d = bent.size() == n ? bent[i] : rest;
      for (int a = 0; a < 3; ++a) {
        r_.rest_shapes[at + static_cast<std::size_t>(a)] = static_cast<float>(rest[a]);
        r_.deflected_shapes[at + static_cast<std::size_t>(a)] = static_cast<float>(d[a]);
      }
    }
  }

  const SimulationConfig& c_;
  const Prepared& prep_;
  ArrayResult& r_;
  std::size_t p_, w_;
  const WhiskerSpec& spec_;
  const Whisker& rest_;
  ContactTracker tracker_;
};

// The scene's edges (edges_in_world order) as contacts during motion (dynamics/contact.hpp) for one head pitch:
// infinite edges and pegs (the integrator's line objects), or the surfaces, fixed in the world, friction mu in the
// frictional edge mode. Objects that move with a moving head and finite edges (prisms) are refused, naming the
// object.
std::vector<dynamics::Obstacle> dynamics_obstacles(const SimulationConfig& c, const Prepared& prep,
                                                       std::size_t p) {
  const double mu = c.mode == ContactMode::frictional_edge ? c.mu : 0.0;
  if (prep.surfaces) {
    // Surfaces (dynamics/contact.hpp's SurfaceObstacle), with the solver's thickness, fixed in the world.
    std::vector<dynamics::Obstacle> out;
    const std::vector<PlacedShape>& first = prep.shapes[p].front();
    for (std::size_t k = 0; k < first.size(); ++k) {
      for (const std::vector<PlacedShape>& later : prep.shapes[p])
        if (later[k].X_WO.p_WO != first[k].X_WO.p_WO || later[k].X_WO.R_WO != first[k].X_WO.R_WO)
          throw std::invalid_argument("objects: --dynamics needs objects fixed in the world; objects[" +
                                      std::to_string(k) + "] (" + c.objects[k].kind + ") moves with the head");
      out.push_back(dynamics::obstacle(c.objects[k].shape, first[k].X_WO, c.thickness, mu));
    }
    return out;
  }
  const std::vector<EdgeSegment>& first = prep.edges[p].front();
  std::vector<dynamics::Obstacle> out;
  for (std::size_t e = 0; e < first.size(); ++e) {
    if (first[e].finite())
      throw std::invalid_argument("objects: --dynamics touches infinite edges and pegs; edge " + std::to_string(e) +
                                  " is " + fmt(first[e].length * 1e3) + " mm long (a finite edge, a prism's or a "
                                  "peg's with a height)");
    for (const std::vector<EdgeSegment>& later : prep.edges[p])
      if (later[e].p0 != first[e].p0 || later[e].direction != first[e].direction)
        throw std::invalid_argument("objects: --dynamics needs objects fixed in the world; edge " + std::to_string(e) +
                                    " moves with the head");
    out.push_back(dynamics::line_obstacle(first[e].line(), mu));
  }
  return out;
}

// The run of one whisker at one head pitch through the dynamics integrator, with the scene's edges as contacts
// during motion: its base follows the head and whisking kinematics; frames are the integrator's outputs at the
// config's (equally spaced) times.
void run_dynamics(const SimulationConfig& c, const Prepared& prep, ArrayResult& r, std::size_t p, std::size_t w,
                  std::size_t& steps, std::size_t& rejected) {
  const WhiskerSpec& spec = c.morphology.whiskers[w];
  const Whisker& rest = prep.rest[w];
  const double t0 = c.times.front(), pitch = c.pitches[p];
  auto placement = [&c, &spec, t0, pitch](double t) {
    const HeadPose H = c.head.at(t0 + t, pitch);
    const WhiskerAngles a = angles_at(spec, c.whisking, t0 + t);
    return Placement(H.R_WH * R_HB(spec.side, a.theta, a.phi, a.zeta), H.point_to_world(spec.p_H_base));
  };
  const dynamics::BaseTrajectory base = dynamics::trajectory_from_placements(placement);
  const dynamics::DynamicsProperties& props = *c.dynamics;
  dynamics::SimulationOptions o;
  o.output_rate = static_cast<double>(c.times.size() - 1) / (c.times.back() - t0);
  o.duration = c.times.back() - t0;
  const bool render_run = p == static_cast<std::size_t>(c.render_pitch);
  o.record_nodes = render_run && !c.render_frames.empty();
  o.objects = prep.obstacles[p];
  o.modes = props.modes;
  const dynamics::LinearModel model = dynamics::linear_model(rest, props);
  const dynamics::Modes all = dynamics::modes(model, rest);
  const dynamics::TimeSeries ts = dynamics::simulate(
      rest, model, all, base, props.gravity_W, o, {},
      props.air_drag ? dynamics::air_drag_load(rest, base, props.air) : dynamics::ExternalLoad{});
  if (ts.status != dynamics::SimulationStatus::completed || ts.time.size() != r.n_frames)
    throw std::runtime_error("dynamics of whisker " + spec.label() + " stopped early: " +
                             std::string(dynamics::to_string(ts.status)));
  steps += static_cast<std::size_t>(ts.steps);
  rejected += static_cast<std::size_t>(ts.rejected_steps);
  r.contact_events[p * r.n_whiskers + w] = ts.events;
  for (std::size_t f = 0; f < r.n_frames; ++f) {
    const std::size_t k = r.index(p, w, f);
    put3(r.base_W, k, ts.placements[f].p_W_base);
    const Eigen::Vector3d& F = ts.force_B[f];
    const Eigen::Vector3d& M = ts.moment_B[f];
    put3(r.force_B, k, F);
    put3(r.moment_B, k, M);
    put3(r.force_W, k, ts.force_W[f]);
    put3(r.moment_W, k, ts.moment_W[f]);
    put3(r.tip_displacement_B, k, ts.tip_displacement_B[f]);
    // The contact of the frame: the touching edge with the largest force (the array records one per frame).
    int touching = -1;
    for (std::size_t j = 0; j < ts.contacts.size(); ++j)
      if (ts.contacts[j].state[f] != dynamics::ContactState::none &&
          (touching < 0 || ts.contacts[j].force_W[f].norm() >
                               ts.contacts[static_cast<std::size_t>(touching)].force_W[f].norm()))
        touching = static_cast<int>(j);
    if (touching >= 0 && prep.surfaces) {
      // A surface: normal_force F . n (n the surface's normal at the contact), edge_force the friction force's
      // magnitude in the tangent plane, z_edge NaN.
      const std::size_t j = static_cast<std::size_t>(touching);
      const Eigen::Vector3d& Fc = ts.contacts[j].force_W[f];
      const Eigen::Vector3d n = prep.shapes[p][f][j].nearest_W(ts.contacts[j].point_W[f]).normal;
      r.state[k] = static_cast<std::int8_t>(ContactState::contact);
      r.edge[k] = static_cast<std::int16_t>(j);
      r.s_applied[k] = ts.contacts[j].arc_length[f];
      put3(r.contact_W, k, ts.contacts[j].point_W[f]);
      r.normal_force[k] = Fc.dot(n);
      r.edge_force[k] = (Fc - r.normal_force[k] * n).norm();
      r.z_edge[k] = std::numeric_limits<double>::quiet_NaN();
    } else if (touching >= 0) {
      const std::size_t e_index = static_cast<std::size_t>(touching);
      const EdgeSegment& e = prep.edges[p][f][e_index];
      const Eigen::Vector3d& Fc = ts.contacts[e_index].force_W[f];
      r.state[k] = static_cast<std::int8_t>(ContactState::contact);
      r.edge[k] = static_cast<std::int16_t>(e_index);
      r.s_applied[k] = ts.contacts[e_index].arc_length[f];
      put3(r.contact_W, k, ts.contacts[e_index].point_W[f]);
      r.edge_force[k] = Fc.dot(e.direction);
      r.normal_force[k] = (Fc - r.edge_force[k] * e.direction).norm();
      r.z_edge[k] = e.coordinate(ts.contacts[e_index].point_W[f]);
    }
    const WhiskerFrameSignals sig = whisker_frame_signals(F, M);
    r.FT[k] = sig.FT;
    r.MB[k] = sig.MB;
    r.FD[k] = sig.FD;
    r.MD[k] = sig.MD;
    if (render_run && prep.render_index[f] >= 0) {
      const std::size_t ri = static_cast<std::size_t>(prep.render_index[f]);
      const auto& nodes_B = rest.rest_nodes_B();
      for (std::size_t i = 0; i < nodes_B.size(); ++i) {
        const std::size_t at = ((ri * r.n_whiskers + w) * nodes_B.size() + i) * 3;
        const Eigen::Vector3d x_rest = ts.placements[f].to_world(nodes_B[i]);
        for (int a = 0; a < 3; ++a) {
          r.rest_shapes[at + static_cast<std::size_t>(a)] = static_cast<float>(x_rest[a]);
          r.deflected_shapes[at + static_cast<std::size_t>(a)] = static_cast<float>(ts.nodes_W[f][i][a]);
        }
      }
    }
  }
}

Prepared prepare(const SimulationConfig& c, ArrayResult& r) {
  Prepared prep;
  const std::size_t W = c.morphology.whiskers.size(), F = c.times.size(), P = c.pitches.size();
  prep.rest.reserve(W);
  prep.R_HB.resize(W);
  for (std::size_t w = 0; w < W; ++w) {
    const WhiskerSpec& s = c.morphology.whiskers[w];
    prep.rest.push_back(make_rest_whisker(s, c.links));
    prep.R_HB[w].resize(F);
    for (std::size_t f = 0; f < F; ++f) {
      const WhiskerAngles a = angles_at(s, c.whisking, c.times[f]);
      prep.R_HB[w][f] = R_HB(s.side, a.theta, a.phi, a.zeta);
      r.theta[w * F + f] = a.theta;
      r.phi[w * F + f] = a.phi;
      r.zeta[w * F + f] = a.zeta;
    }
  }
  prep.head.resize(P);
  prep.edges.resize(P);
  prep.shapes.resize(P);
  prep.surfaces = scene_of_surfaces(c.objects);
  for (std::size_t p = 0; p < P; ++p) {
    for (std::size_t f = 0; f < F; ++f) {
      prep.head[p].push_back(c.head.at(c.times[f], c.pitches[p]));
      prep.edges[p].push_back(edges_in_world(c.objects, prep.head[p].back()));
      prep.shapes[p].push_back(shapes_in_world(c.objects, prep.head[p].back()));
    }
  }
  prep.render_index.assign(F, -1);
  for (std::size_t i = 0; i < c.render_frames.size(); ++i)
    prep.render_index[static_cast<std::size_t>(c.render_frames[i])] = static_cast<int>(i);
  if (c.dynamics)
    for (std::size_t p = 0; p < P; ++p) prep.obstacles.push_back(dynamics_obstacles(c, prep, p));
  return prep;
}

}  // namespace

std::vector<double> uniform_times(double start, double end, int frames) {
  if (!std::isfinite(start) || !std::isfinite(end) || !(end > start))
    fail("time: end_s must be later than start_s, got start " + fmt(start) + " s, end " + fmt(end) + " s");
  if (frames < 2) fail("time.frames must be >= 2, got " + std::to_string(frames));
  require_at_most(static_cast<std::size_t>(frames), limits::max_array_frames, "time.frames");
  std::vector<double> t(static_cast<std::size_t>(frames));
  for (int k = 0; k < frames; ++k) t[static_cast<std::size_t>(k)] = start + (end - start) * k / (frames - 1);
  return t;
}

void validate(const SimulationConfig& c) {
  if (c.morphology.whiskers.empty()) fail("morphology: no whiskers selected");
  for (const WhiskerSpec& s : c.morphology.whiskers) validate(s);
  validate(c.whisking.protraction, "whisking");
  for (const auto& [name, p] : c.whisking.per_whisker) {
    bool known = false;
    for (const WhiskerSpec& s : c.morphology.whiskers) known = known || s.name == name || s.label() == name;
    if (!known) fail("whisking.per_whisker: unknown whisker '" + name + "'");
    validate(p, "whisking.per_whisker." + name);
  }
  validate(c.head, "head");
  if (c.pitches.empty()) fail("head.pitches_deg must hold at least one pitch");
  for (std::size_t i = 0; i < c.pitches.size(); ++i)
    if (!(std::abs(to_deg(c.pitches[i])) <= 180.0 + 1e-9))  // an angle: 1e300 deg is a typo, not a pose
      fail("head.pitches_deg[" + std::to_string(i) + "] must lie in [-180, 180], got " + fmt(to_deg(c.pitches[i])));
  if (c.objects.empty()) fail("objects: the scene has no objects");
  if (c.times.size() < 2) fail("time.frames must be >= 2, got " + std::to_string(c.times.size()));
  for (std::size_t i = 0; i < c.times.size(); ++i) {
    if (!std::isfinite(c.times[i])) fail("time[" + std::to_string(i) + "] must be finite");
    if (i > 0 && !(c.times[i] > c.times[i - 1])) fail("time must increase strictly at frame " + std::to_string(i));
  }
  if (c.dynamics) {
    dynamics::validate(*c.dynamics);
    const double dt = (c.times.back() - c.times.front()) / static_cast<double>(c.times.size() - 1);
    for (std::size_t i = 1; i < c.times.size(); ++i)
      if (std::abs(c.times[i] - c.times.front() - dt * static_cast<double>(i)) > 1e-9 * (c.times.back() - c.times.front()))
        fail("time: dynamics needs equally spaced frames (the integrator's output rate), frame " + std::to_string(i) +
             " is at " + fmt(c.times[i]) + " s");
  }
  if (c.mode == ContactMode::contact_point)
    fail("solver.mode must be 'edge' or 'frictional_edge' (an array has no tracked contact points), got 'contact_point'");
  if (!(std::isfinite(c.mu) && c.mu >= 0.0)) fail("solver.mu must be finite and >= 0, got " + fmt(c.mu));
  if (c.links < 2) fail("solver.links must be >= 2, got " + std::to_string(c.links));
  if (!(c.tolerance > 0.0 && c.tolerance <= 1e-3))
    fail("solver.tolerance_m must lie in (0, 0.001], got " + fmt(c.tolerance));
  if (c.max_iterations < 1) fail("solver.max_iterations must be >= 1, got " + std::to_string(c.max_iterations));
  for (int f : c.render_frames)
    if (f < 0 || static_cast<std::size_t>(f) >= c.times.size())
      fail("output.render_frames: frame " + std::to_string(f) + " is outside 0.." + std::to_string(c.times.size() - 1));
  if (c.render_pitch < 0 || static_cast<std::size_t>(c.render_pitch) >= c.pitches.size())
    fail("output.render_pitch must index head.pitches_deg, got " + std::to_string(c.render_pitch));
  if (c.threads < 0 || c.threads > limits::max_threads)
    fail("threads must lie in [0, " + std::to_string(limits::max_threads) + "], got " + std::to_string(c.threads));
  if (c.links > limits::max_links) fail("solver.links must be <= " + std::to_string(limits::max_links) + ", got " + std::to_string(c.links));
  require_at_most(c.times.size(), limits::max_array_frames, "time: number of frames");
  require_at_most(c.objects.size(), limits::max_edges, "objects: number of objects");
  const double whiskers = static_cast<double>(c.morphology.whiskers.size());  // products in double: no overflow
  const double samples = static_cast<double>(c.times.size()) * whiskers * static_cast<double>(c.pitches.size());
  if (samples > static_cast<double>(limits::max_array_samples))
    fail("frames x whiskers x pitches = " + fmt(samples) + " is more than the limit of " +
         std::to_string(limits::max_array_samples) + " samples per run (docs/formats.md, \"Limits\")");
  const double rendered = static_cast<double>(c.render_frames.size()) * whiskers * (c.links + 1.0);
  if (rendered > static_cast<double>(limits::max_array_samples))
    fail("output.render_count x whiskers x (solver.links + 1) = " + fmt(rendered) + " is more than the limit of " +
         std::to_string(limits::max_array_samples) + " rendered nodes per run");
}

ArrayResult simulate_array(const SimulationConfig& c, const RunControl& control) {
  validate(c);
  const auto start = std::chrono::steady_clock::now();
  ArrayResult r;
  r.n_pitches = c.pitches.size();
  r.n_whiskers = c.morphology.whiskers.size();
  r.n_frames = c.times.size();
  r.n_nodes = static_cast<std::size_t>(c.links) + 1;
  r.times = c.times;
  r.pitches = c.pitches;
  for (const WhiskerSpec& s : c.morphology.whiskers) r.labels.push_back(s.label());
  const std::size_t total = r.n_pitches * r.n_whiskers * r.n_frames;
  r.state.assign(total, 0);
  r.solver_status.assign(total, -1);
  r.edge.assign(total, -1);
  // Without contact the loads are zero, and the contact's position and direction do not exist (NaN).
  for (auto* v : {&r.FT, &r.MB, &r.normal_force, &r.edge_force}) v->assign(total, 0.0);
  for (auto* v : {&r.s_applied, &r.FD, &r.MD, &r.z_edge, &r.z_error}) v->assign(total, kNaN);
  for (auto* v : {&r.force_W, &r.moment_W, &r.force_B, &r.moment_B, &r.base_W}) v->assign(3 * total, 0.0);
  r.contact_W.assign(3 * total, kNaN);
  for (auto* v : {&r.theta, &r.phi, &r.zeta}) v->assign(r.n_whiskers * r.n_frames, 0.0);
  r.render_frames = c.render_frames;
  const std::size_t shape_size = c.render_frames.size() * r.n_whiskers * r.n_nodes * 3;
  r.rest_shapes.assign(shape_size, 0.0f);
  r.deflected_shapes.assign(shape_size, 0.0f);

  const Prepared prep = prepare(c, r);
  r.n_edges = prep.edges.front().front().size();
  r.n_objects = prep.shapes.front().front().size();
  for (int f : c.render_frames)
    for (const PlacedShape& o : prep.shapes[static_cast<std::size_t>(c.render_pitch)][static_cast<std::size_t>(f)]) {
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) r.render_object_poses.push_back(static_cast<float>(o.X_WO.R_WO(i, j)));
      for (int i = 0; i < 3; ++i) r.render_object_poses.push_back(static_cast<float>(o.X_WO.p_WO[i]));
    }
  for (int f : c.render_frames) {
    for (const EdgeSegment& e : prep.edges[static_cast<std::size_t>(c.render_pitch)][static_cast<std::size_t>(f)]) {
      const Eigen::Vector3d a = e.finite() ? e.p0 : Eigen::Vector3d(e.p0 - kRenderHalfLength * e.direction);
      const Eigen::Vector3d b = e.finite() ? Eigen::Vector3d(e.p0 + e.length * e.direction)
                                           : Eigen::Vector3d(e.p0 + kRenderHalfLength * e.direction);
      for (int i = 0; i < 3; ++i) r.render_edges.push_back(static_cast<float>(a[i]));
      for (int i = 0; i < 3; ++i) r.render_edges.push_back(static_cast<float>(b[i]));
    }
  }

  const long pairs = static_cast<long>(r.n_pitches * r.n_whiskers);
  ProgressCounter counter(control, total);
  std::size_t solves = 0, failed = 0, steps = 0, rejected = 0;
  if (c.dynamics) {
    r.tip_displacement_B.assign(3 * total, 0.0);
    r.contact_events.assign(r.n_pitches * r.n_whiskers, {});
  }
  std::exception_ptr error;
  std::mutex error_mutex;
  const int threads = c.threads > 0 ? c.threads : omp_get_max_threads();
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads) reduction(+ : solves, failed, steps, rejected)
  for (long pair = 0; pair < pairs; ++pair) {
    try {
      counter.check();
      const std::size_t pi = static_cast<std::size_t>(pair) / r.n_whiskers;
      const std::size_t wi = static_cast<std::size_t>(pair) % r.n_whiskers;
      if (c.dynamics) {
        run_dynamics(c, prep, r, pi, wi, steps, rejected);
        counter.advance(r.n_frames);
        continue;
      }
      PairRun run(c, prep, r, pi, wi);
      run.run();
      solves += run.solves();
      failed += run.failed();
      counter.advance(r.n_frames);
    } catch (...) {
      const std::lock_guard<std::mutex> lock(error_mutex);
      if (!error) error = std::current_exception();
    }
  }
  if (error) std::rethrow_exception(error);
  r.solves = solves;
  r.failed_solves = failed;
  r.dynamics_steps = steps;
  r.dynamics_rejected_steps = rejected;
  r.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return r;
}

}  // namespace vibrissa::array
