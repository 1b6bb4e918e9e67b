#include "vibrissa/trial/pipeline.hpp"

#include <exception>
#include <limits>
#include <mutex>

#include "vibrissa/solve/solvers.hpp"
#include "vibrissa/trial/contact_geometry.hpp"
#include "vibrissa/trial/kinematic_prediction.hpp"
#include "vibrissa/trial/shape_error.hpp"

namespace vibrissa::trial {

const char* to_string(Mode mode) {
  switch (mode) {
    case Mode::contact_point: return "contact_point";
    case Mode::edge: return "edge";
    case Mode::frictional_edge: return "frictional_edge";
  }
  return "?";
}

namespace {

Pose pose_at(const Trial& t, std::size_t i) {
  Pose p;
  p.p_W_base = t.base_W[i];
  p.theta = t.theta[i];
  p.phi = t.phi[i];
  p.zeta = t.zeta[i];
  return p;
}

void record(const Whisker& w, const Solution& s, const Edge& edge, const std::vector<Eigen::Vector3d>* tracked,
            ModeFrame& m) {
  m.solved = true;
  m.status = s.status;
  m.iterations = s.iterations;
  if (s.status != Status::converged) return;
  const Eigen::Vector3d d = edge.direction.normalized();
  m.contact_W = s.contact_point;
  m.s_applied = s.arc_length;
  m.force_W = s.force;
  m.moment_W = s.moment;
  m.signals_B = s.whisker_frame;
  m.friction_force = s.edge_force ? *s.edge_force : s.force.dot(d);
  m.normal_force = s.normal_force ? *s.normal_force : (s.force - s.force.dot(d) * d).norm();
  m.height = height_along_edge(edge, s.contact_point);
  if (tracked && !tracked->empty() && !s.shape.empty())
    m.shape_error = mean_shape_error(s.shape, w.node_arc_lengths(), s.arc_length, *tracked);
}

/// The edge a period touches: nearest to the tracked contact points, else to the rest whisker at onset.
int choose_edge(const Trial& t, const ContactPeriod& p, const Whisker& w_onset) {
  const auto& edges = t.meta.edges;
  if (edges.size() == 1) return 0;
  int best = 0;
  double best_d = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < edges.size(); ++k) {
    double dist = 0.0;
    if (t.has_contact_point()) {
      const Eigen::Vector3d dir = edges[k].direction.normalized();
      for (std::size_t i = p.first; i <= p.last; ++i) {
        const Eigen::Vector3d r = t.contact_W[i] - edges[k].point;
        dist += (r - r.dot(dir) * dir).norm();
      }
    } else {
      dist = nearest_rest_point(w_onset, edges[k]).distance;
    }
    if (dist < best_d) {
      best_d = dist;
      best = static_cast<int>(k);
    }
  }
  return best;
}

}  // namespace

PipelineResult run_pipeline(const Trial& trial, const PipelineOptions& opt, const RunControl& control) {
  PipelineResult res;
  res.pre = preprocess(trial, opt.preprocess);
  const Trial& t = res.pre.trial;
  const std::size_t n = t.frames();
  res.has_contact_point_mode = opt.contact_point_mode && t.has_contact_point();
  res.has_edge_mode = opt.edge_mode;
  res.has_frictional_mode = opt.mu.has_value();
  res.mu = opt.mu;
  if (opt.mu && !(std::isfinite(*opt.mu) && *opt.mu >= 0.0))
    throw std::invalid_argument("friction coefficient mu must be finite and >= 0, got " + std::to_string(*opt.mu));

  Eigen::Vector3d mean_base = Eigen::Vector3d::Zero();
  for (const auto& b : t.base_W) mean_base += b;
  mean_base /= static_cast<double>(n);
  res.view_direction_W = opt.view_direction_W ? opt.view_direction_W->normalized()
                                              : front_view_direction(t.meta.edges.front(), mean_base);

  res.frames.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    res.frames[i].time = t.time[i];
    res.frames[i].contact = t.contact[i] != 0;
  }
  const auto& periods = res.pre.periods;
  res.periods.resize(periods.size());
  SolveOptions sopt = opt.solve;
  sopt.compute_shape = t.has_shapes();
  sopt.find_other_roots = false;
  const WhiskerProperties props = whisker_properties(t.meta.material);

  std::exception_ptr error;
  std::mutex error_mutex;
  std::size_t contact_frames = 0;
  for (const ContactPeriod& p : periods) contact_frames += p.size();
  ProgressCounter counter(control, contact_frames);
#pragma omp parallel for schedule(dynamic)
  for (std::ptrdiff_t pi = 0; pi < static_cast<std::ptrdiff_t>(periods.size()); ++pi) {
    try {
      const auto pu = static_cast<std::size_t>(pi);
      const ContactPeriod& p = periods[pu];
      const Whisker base_w = Whisker::from_points(res.pre.rest_shapes[pu], props, pose_at(t, p.first));
      PeriodInfo& info = res.periods[pu];
      info.edge_index = choose_edge(t, p, base_w);
      const Edge& edge = t.meta.edges[static_cast<std::size_t>(info.edge_index)];
      const Eigen::Vector3d d = edge.direction.normalized();
      // Direction of motion into the edge at onset (frames on either side of the first contact frame).
      const NearestOnWhisker touch0 = nearest_rest_point(base_w, edge);
      const Whisker w_before = base_w.placed(pose_at(t, p.first > 0 ? p.first - 1 : p.first));
      const Whisker w_after = base_w.placed(pose_at(t, std::min(p.first + 1, n - 1)));
      info.approach_W = approach_direction(w_before, w_after, touch0.arc_length, edge);
      const std::optional<Eigen::Vector3d> approach =
          info.approach_W.norm() > 0.0 ? std::optional<Eigen::Vector3d>(info.approach_W) : std::nullopt;

      std::optional<LoadState> warm_cp, warm_edge, warm_fric;
      std::optional<double> hint_cp, hint_edge;
      std::optional<Eigen::Vector3d> prev_fric;
      for (std::size_t i = p.first; i <= p.last; ++i) {
        counter.check();
        FrameResult& fr = res.frames[i];
        fr.period = static_cast<int>(pi);
        const std::size_t k = i - p.first;
        fr.period_edge = k < 2 || k + 2 >= p.size();
        const Whisker w = base_w.placed(pose_at(t, i));
        fr.kinematic_height = kinematic_contact_height(w, edge, res.view_direction_W);
        const std::vector<Eigen::Vector3d>* tracked = t.has_shapes() ? &t.shape_W[i] : nullptr;
        if (res.has_contact_point_mode) {
          const Solution s = solve_point(w, t.contact_W[i], hint_cp, sopt, warm_cp ? &*warm_cp : nullptr, d);
          record(w, s, edge, tracked, fr.contact_point);
          warm_cp = s.status == Status::converged ? std::optional<LoadState>(s.state) : std::nullopt;
          hint_cp = s.status == Status::converged ? std::optional<double>(s.arc_length) : std::nullopt;
        }
        if (res.has_edge_mode) {
          const Solution s = solve_edge(w, edge, hint_edge, sopt, warm_edge ? &*warm_edge : nullptr, approach);
          record(w, s, edge, tracked, fr.edge);
          warm_edge = s.status == Status::converged ? std::optional<LoadState>(s.state) : std::nullopt;
          hint_edge = s.status == Status::converged ? std::optional<double>(s.arc_length) : std::nullopt;
          if (s.status == Status::converged && std::isnan(info.onset_height_edge))
            info.onset_height_edge = fr.edge.height;
        }
        if (res.has_frictional_mode) {
          // Contact history: the last frame's contact, or where the rest whisker first touches the edge.
          const Eigen::Vector3d previous = prev_fric ? *prev_fric : nearest_rest_point(w, edge).on_edge_W;
          const Solution s =
              solve_frictional_edge(w, edge, *opt.mu, previous, sopt, warm_fric ? &*warm_fric : nullptr, approach);
          record(w, s, edge, tracked, fr.frictional);
          warm_fric = s.status == Status::converged ? std::optional<LoadState>(s.state) : std::nullopt;
          prev_fric = s.status == Status::converged ? std::optional<Eigen::Vector3d>(s.contact_point) : std::nullopt;
        }
        counter.advance();
      }
    } catch (...) {
      std::lock_guard<std::mutex> lock(error_mutex);
      if (!error) error = std::current_exception();
    }
  }
  if (error) std::rethrow_exception(error);
  return res;
}

}  // namespace vibrissa::trial
