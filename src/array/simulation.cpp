#include "vibrissa/array/simulation.hpp"

#include <omp.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <exception>
#include <mutex>
#include <optional>

#include "array_util.hpp"
#include "vibrissa/array/crossing.hpp"
#include "vibrissa/array/error_bound.hpp"
#include "vibrissa/core/pose.hpp"
#include "vibrissa/solve/solvers.hpp"

namespace vibrissa::array {
namespace {

constexpr double kRenderHalfLength = 0.04;  // infinite edges are drawn ±40 mm about their point [m]

// Everything that does not depend on the (pitch, whisker) pair being run, shared read-only by all threads.
struct Prepared {
  std::vector<Whisker> rest;                    // per whisker, frame B at the origin
  std::vector<std::vector<Eigen::Matrix3d>> R_HB;  // [whisker][frame]
  std::vector<std::vector<HeadPose>> head;       // [pitch][frame]
  std::vector<std::vector<std::vector<EdgeSegment>>> edges;  // [pitch][frame][edge]
  std::vector<int> render_index;                 // frame -> index among rendered frames, or -1
};

void put3(std::vector<double>& v, std::size_t i, const Eigen::Vector3d& x) {
  v[3 * i] = x.x();
  v[3 * i + 1] = x.y();
  v[3 * i + 2] = x.z();
}

// The run of one whisker at one head pitch, in time order (warm starts need it).
class PairRun {
 public:
  PairRun(const SimulationConfig& c, const Prepared& prep, ArrayResult& r, std::size_t p, std::size_t w)
      : c_(c), prep_(prep), r_(r), p_(p), w_(w), spec_(c.morphology.whiskers[w]), rest_(prep.rest[w]) {}

  void run() {
    const auto& nodes_B = rest_.rest_nodes_B();
    const auto& arc = rest_.node_arc_lengths();
    const std::size_t n = nodes_B.size();
    std::vector<Eigen::Vector3d> prev(n), now(n);
    for (std::size_t f = 0; f < r_.n_frames; ++f) {
      const HeadPose& H = prep_.head[p_][f];
      const Eigen::Matrix3d R_WB = H.R_WH * prep_.R_HB[w_][f];
      const Eigen::Vector3d p_W_base = H.point_to_world(spec_.p_H_base);
      for (std::size_t i = 0; i < n; ++i) now[i] = p_W_base + R_WB * nodes_B[i];
      const std::size_t k = r_.index(p_, w_, f);
      put3(r_.base_W, k, p_W_base);
      if (f > 0) step(f, prev, now, arc, R_WB, p_W_base);
      r_.state[k] = static_cast<std::int8_t>(state_);
      if (p_ == static_cast<std::size_t>(c_.render_pitch) && prep_.render_index[f] >= 0) render(f, now);
      std::swap(prev, now);
    }
  }

  std::size_t solves = 0, failed = 0;

 private:
  // Earliest crossing among the edges; `only` restricts to one edge, `skip` excludes one.
  std::optional<std::pair<int, Crossing>> earliest_crossing(std::size_t f, const std::vector<Eigen::Vector3d>& prev,
                                                             const std::vector<Eigen::Vector3d>& now,
                                                             const std::vector<double>& arc, int only, int skip,
                                                             bool within_extent) const {
    const auto& ep = prep_.edges[p_][f - 1];
    const auto& en = prep_.edges[p_][f];
    std::optional<std::pair<int, Crossing>> best;
    for (std::size_t e = 0; e < en.size(); ++e) {
      const int ei = static_cast<int>(e);
      if ((only >= 0 && ei != only) || ei == skip) continue;
      if (!may_reach(prev.front(), ep[e]) && !may_reach(now.front(), en[e])) continue;
      if (auto c = find_crossing(prev, now, arc, ep[e], en[e], within_extent); c && (!best || c->tau < best->second.tau))
        best = std::make_pair(ei, *c);
    }
    return best;
  }

  // Cheap rejection: an edge's line farther from the base than the whisker is long cannot be crossed.
  [[nodiscard]] bool may_reach(const Eigen::Vector3d& base_W, const EdgeSegment& e) const {
    const Eigen::Vector3d r = base_W - e.p0;
    const double dist = (r - r.dot(e.direction) * e.direction).norm();
    return dist <= 1.05 * spec_.arc_length;
  }

  void begin_contact(std::size_t f, int edge, const Crossing& c) {
    state_ = ContactState::contact;
    edge_ = edge;
    approach_E_ = c.approach_E;
    hint_ = c.arc_length;
    have_warm_ = false;
    onset_pending_ = true;
    const EdgeSegment& e = prep_.edges[p_][f][static_cast<std::size_t>(edge)];
    last_contact_W_ = e.p0 + c.edge_coordinate * e.direction;
  }

  void step(std::size_t f, const std::vector<Eigen::Vector3d>& prev, const std::vector<Eigen::Vector3d>& now,
            const std::vector<double>& arc, const Eigen::Matrix3d& R_WB, const Eigen::Vector3d& p_W_base) {
    if (state_ == ContactState::free) {
      if (auto hit = earliest_crossing(f, prev, now, arc, -1, -1, true)) begin_contact(f, hit->first, hit->second);
    } else if (state_ == ContactState::pushed_past) {
      // Retraction: the rest whisker crosses back over the line it was pushed past (its extent aside).
      if (earliest_crossing(f, prev, now, arc, edge_, -1, false)) {
        state_ = ContactState::free;
        edge_ = -1;
      } else if (auto hit = earliest_crossing(f, prev, now, arc, -1, edge_, true)) {
        begin_contact(f, hit->first, hit->second);
      }
    }
    if (state_ == ContactState::contact) solve(f, R_WB, p_W_base);
  }

  void solve(std::size_t f, const Eigen::Matrix3d& R_WB, const Eigen::Vector3d& p_W_base) {
    const std::size_t k = r_.index(p_, w_, f);
    const EdgeSegment& e = prep_.edges[p_][f][static_cast<std::size_t>(edge_)];
    const Whisker placed = rest_.placed(pose_from_rotation(R_WB, p_W_base));
    SolveOptions options;
    options.tolerance = c_.tolerance;
    options.max_iterations = c_.max_iterations;
    const bool rendering = p_ == static_cast<std::size_t>(c_.render_pitch) && prep_.render_index[f] >= 0;
    options.compute_shape = rendering;
    const Eigen::Vector3d approach_W = edge_vector_to_world(e, approach_E_);
    const LoadState* warm = have_warm_ ? &warm_ : nullptr;
    const Solution s = c_.mode == ContactMode::edge
                           ? solve_edge(placed, e.line(), hint_, options, warm, approach_W)
                           : solve_frictional_edge(placed, e.line(), c_.mu, last_contact_W_, options, warm, approach_W);
    ++solves;
    r_.solver_status[k] = static_cast<std::int8_t>(s.status);
    r_.edge[k] = static_cast<std::int16_t>(edge_);
    if (s.status == Status::slipped_off) {
      state_ = ContactState::pushed_past;  // Fig. 4a green: the whisker slipped off its tip past the edge
      return;
    }
    if (s.status == Status::no_contact) {
      state_ = ContactState::free;  // released: the edge would have to pull
      edge_ = -1;
      return;
    }
    if (s.status == Status::not_converged) {
      // No frictionless equilibrium near the previous one: past a fold of the edge-mode solution the whisker
      // slides along the edge and snaps free; its rest shape is beyond the edge, so it has pushed past.
      ++failed;
      state_ = ContactState::pushed_past;
      return;
    }
    const double lambda = (s.contact_point - e.p0).dot(e.direction);
    if (!e.contains(lambda)) {
      state_ = ContactState::pushed_past;  // slipped off the end of a finite edge
      return;
    }
    put3(r_.contact_W, k, s.contact_point);
    put3(r_.force_W, k, s.force);
    put3(r_.moment_W, k, s.moment);
    put3(r_.force_B, k, s.whisker_frame.force);
    put3(r_.moment_B, k, s.whisker_frame.moment);
    r_.s_applied[k] = s.arc_length;
    r_.FT[k] = s.whisker_frame.FT;
    r_.MB[k] = s.whisker_frame.MB;
    r_.FD[k] = s.whisker_frame.FD;
    r_.MD[k] = s.whisker_frame.MD;
    r_.normal_force[k] = s.normal_force.value_or(0.0);
    r_.edge_force[k] = s.edge_force.value_or(0.0);
    r_.z_edge[k] = lambda;
    if (onset_pending_) {
      z_onset_ = lambda;
      onset_pending_ = false;
    }
    warm_ = s.state;
    have_warm_ = true;
    hint_ = s.arc_length;
    last_contact_W_ = s.contact_point;
    // eq. (7): error bound on the contact position along the edge for friction coefficient mu.
    r_.z_error[k] = contact_error_bound(lambda - z_onset_, c_.mu, r_.normal_force[k], s.arc_length, spec_.arc_length,
                                       spec_.base_radius, spec_.taper_ratio, spec_.youngs_modulus);
    if (rendering && !s.shape.empty()) deflected_ = s.shape;
  }

  void render(std::size_t f, const std::vector<Eigen::Vector3d>& now) {
    const std::size_t ri = static_cast<std::size_t>(prep_.render_index[f]);
    const std::size_t n = now.size();
    const bool bent = state_ == ContactState::contact && deflected_.size() == n;
    for (std::size_t i = 0; i < n; ++i) {
      const std::size_t at = ((ri * r_.n_whiskers + w_) * n + i) * 3;
      const Eigen::Vector3d& d = bent ? deflected_[i] : now[i];
      for (int a = 0; a < 3; ++a) {
        r_.rest_shapes[at + static_cast<std::size_t>(a)] = static_cast<float>(now[i][a]);
        r_.deflected_shapes[at + static_cast<std::size_t>(a)] = static_cast<float>(d[a]);
      }
    }
    deflected_.clear();
  }

  const SimulationConfig& c_;
  const Prepared& prep_;
  ArrayResult& r_;
  std::size_t p_, w_;
  const WhiskerSpec& spec_;
  const Whisker& rest_;

  ContactState state_ = ContactState::free;
  int edge_ = -1;
  Eigen::Vector2d approach_E_ = Eigen::Vector2d::Zero();
  double hint_ = 0.0;
  LoadState warm_;
  bool have_warm_ = false;
  bool onset_pending_ = false;
  double z_onset_ = 0.0;
  Eigen::Vector3d last_contact_W_ = Eigen::Vector3d::Zero();
  std::vector<Eigen::Vector3d> deflected_;
};

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
  for (std::size_t p = 0; p < P; ++p) {
    for (std::size_t f = 0; f < F; ++f) {
      prep.head[p].push_back(c.head.at(c.times[f], c.pitches[p]));
      prep.edges[p].push_back(edges_in_world(c.objects, prep.head[p].back()));
    }
  }
  prep.render_index.assign(F, -1);
  for (std::size_t i = 0; i < c.render_frames.size(); ++i)
    prep.render_index[static_cast<std::size_t>(c.render_frames[i])] = static_cast<int>(i);
  return prep;
}

}  // namespace

std::string_view to_string(ContactState s) {
  switch (s) {
    case ContactState::free: return "free";
    case ContactState::contact: return "contact";
    case ContactState::pushed_past: return "pushed_past";
  }
  return "free";
}

std::string_view to_string(ContactMode m) { return m == ContactMode::edge ? "edge" : "frictional_edge"; }

ContactMode contact_mode_from_string(std::string_view name, const char* field) {
  if (name == "edge") return ContactMode::edge;
  if (name == "frictional_edge") return ContactMode::frictional_edge;
  fail(std::string(field) + " must be 'edge' or 'frictional_edge', got '" + std::string(name) + "'");
}

std::vector<double> uniform_times(double start, double end, int frames) {
  if (!std::isfinite(start) || !std::isfinite(end) || !(end > start))
    fail("time: end_s must be later than start_s, got start " + fmt(start) + " s, end " + fmt(end) + " s");
  if (frames < 2) fail("time.frames must be >= 2, got " + std::to_string(frames));
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
    if (!std::isfinite(c.pitches[i]))
      fail("head.pitches_deg[" + std::to_string(i) + "] must be finite, got " + fmt(to_deg(c.pitches[i])));
  if (c.objects.empty()) fail("objects: the scene has no objects");
  if (c.times.size() < 2) fail("time.frames must be >= 2, got " + std::to_string(c.times.size()));
  for (std::size_t i = 0; i < c.times.size(); ++i) {
    if (!std::isfinite(c.times[i])) fail("time[" + std::to_string(i) + "] must be finite");
    if (i > 0 && !(c.times[i] > c.times[i - 1])) fail("time must increase strictly at frame " + std::to_string(i));
  }
  if (!(std::isfinite(c.mu) && c.mu >= 0.0)) fail("solver.mu must be finite and >= 0, got " + fmt(c.mu));
  if (c.links < 2) fail("solver.links must be >= 2, got " + std::to_string(c.links));
  if (!(std::isfinite(c.tolerance) && c.tolerance > 0.0))
    fail("solver.tolerance must be positive, got " + fmt(c.tolerance));
  if (c.max_iterations < 1) fail("solver.max_iterations must be >= 1, got " + std::to_string(c.max_iterations));
  for (int f : c.render_frames)
    if (f < 0 || static_cast<std::size_t>(f) >= c.times.size())
      fail("output.render_frames: frame " + std::to_string(f) + " is outside 0.." + std::to_string(c.times.size() - 1));
  if (c.render_pitch < 0 || static_cast<std::size_t>(c.render_pitch) >= c.pitches.size())
    fail("output.render_pitch must index head.pitches_deg, got " + std::to_string(c.render_pitch));
  if (c.threads < 0) fail("threads must be >= 0, got " + std::to_string(c.threads));
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
  for (auto* v : {&r.s_applied, &r.FT, &r.MB, &r.FD, &r.MD, &r.normal_force, &r.edge_force, &r.z_edge, &r.z_error})
    v->assign(total, 0.0);
  for (auto* v : {&r.contact_W, &r.force_W, &r.moment_W, &r.force_B, &r.moment_B, &r.base_W}) v->assign(3 * total, 0.0);
  for (auto* v : {&r.theta, &r.phi, &r.zeta}) v->assign(r.n_whiskers * r.n_frames, 0.0);
  r.render_frames = c.render_frames;
  const std::size_t shape_size = c.render_frames.size() * r.n_whiskers * r.n_nodes * 3;
  r.rest_shapes.assign(shape_size, 0.0f);
  r.deflected_shapes.assign(shape_size, 0.0f);

  const Prepared prep = prepare(c, r);
  r.n_edges = prep.edges.front().front().size();
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
  std::size_t solves = 0, failed = 0;
  std::exception_ptr error;
  std::mutex error_mutex;
  const int threads = c.threads > 0 ? c.threads : omp_get_max_threads();
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads) reduction(+ : solves, failed)
  for (long pair = 0; pair < pairs; ++pair) {
    try {
      counter.check();
      const std::size_t pi = static_cast<std::size_t>(pair) / r.n_whiskers;
      const std::size_t wi = static_cast<std::size_t>(pair) % r.n_whiskers;
      PairRun run(c, prep, r, pi, wi);
      run.run();
      solves += run.solves;
      failed += run.failed;
      counter.advance(r.n_frames);
    } catch (...) {
      const std::lock_guard<std::mutex> lock(error_mutex);
      if (!error) error = std::current_exception();
    }
  }
  if (error) std::rethrow_exception(error);
  r.solves = solves;
  r.failed_solves = failed;
  r.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return r;
}

}  // namespace vibrissa::array
