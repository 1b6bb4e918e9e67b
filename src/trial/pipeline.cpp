#include "vibrissa/trial/pipeline.hpp"

#include <exception>
#include <limits>
#include <mutex>

#include "vibrissa/solve/solvers.hpp"
#include "vibrissa/contact/contact_geometry.hpp"
#include "vibrissa/contact/tracker.hpp"
#include "vibrissa/trial/kinematic_prediction.hpp"
#include "vibrissa/trial/shape_error.hpp"

namespace vibrissa::trial {

namespace {

Pose pose_at(const Trial& t, std::size_t i) {
  Pose p;
  p.p_W_base = t.base_W[i];
  p.theta = t.theta[i];
  p.phi = t.phi[i];
  p.zeta = t.zeta[i];
  return p;
}

void record(const Whisker& w, const TrackedFrame& fr, const Edge& edge, const std::vector<Eigen::Vector3d>* tracked,
            ModeFrame& m) {
  const Solution& s = fr.solution;
  m.solved = fr.solved;
  m.status = s.status;
  m.friction = s.friction;
  m.iterations = s.iterations;
  if (s.status != Status::converged) return;
  const Eigen::Vector3d d = edge.direction.normalized();
  m.contact_W = s.contact_point_W;
  m.s_applied = s.arc_length;
  m.force_W = s.force_W;
  m.moment_W = s.moment_W;
  m.signals_B = s.whisker_frame;
  m.friction_force = s.edge_force ? *s.edge_force : s.force_W.dot(d);
  m.normal_force = s.normal_force ? *s.normal_force : (s.force_W - s.force_W.dot(d) * d).norm();
  m.height = height_along_edge(edge, s.contact_point_W);
  if (tracked && !tracked->empty() && !s.shape_W.empty())
    m.shape_error = mean_shape_error(s.shape_W, w.node_arc_lengths(), s.arc_length, *tracked);
}

/// The edge a period touches: nearest to the tracked contact points, else to the rest whisker at onset.
int choose_edge(const Trial& t, const ContactPeriod& p, const Whisker& w, const Placement& X_onset) {
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
      dist = nearest_rest_point(w, X_onset, edges[k]).distance;
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
      const Whisker w = Whisker::from_points(res.pre.rest_shapes[pu], props, pose_at(t, p.first));
      PeriodInfo& info = res.periods[pu];
      info.edge_index = choose_edge(t, p, w, Placement(pose_at(t, p.first)));
      const Edge& edge = t.meta.edges[static_cast<std::size_t>(info.edge_index)];
      const EdgeSegment segment = infinite_segment(edge);

      // One contact tracker per mode, driven by the tracked contact flags (contact/tracker.hpp). The frame
      // before the period (when there is one) gives the direction of motion into the edge at onset.
      std::vector<std::pair<ContactMode, ModeFrame FrameResult::*>> modes;
      if (res.has_contact_point_mode) modes.emplace_back(ContactMode::contact_point, &FrameResult::contact_point);
      if (res.has_edge_mode) modes.emplace_back(ContactMode::edge, &FrameResult::edge);
      if (res.has_frictional_mode) modes.emplace_back(ContactMode::frictional_edge, &FrameResult::frictional);
      std::vector<ContactTracker> trackers;
      trackers.reserve(modes.size());
      for (const auto& [mode, member] : modes) {
        TrackerOptions to;
        to.mode = mode;
        to.mu = opt.mu.value_or(0.0);
        to.solve = sopt;
        trackers.emplace_back(w, to);
        TrackedInput before;
        before.in_contact = false;
        if (p.first > 0) trackers.back().step_tracked(Placement(pose_at(t, p.first - 1)), &segment, before);
      }
      for (std::size_t i = p.first; i <= p.last; ++i) {
        counter.check();
        FrameResult& fr = res.frames[i];
        fr.period = static_cast<int>(pi);
        const std::size_t k = i - p.first;
        fr.period_edge = k < 2 || k + 2 >= p.size();
        const Placement X(pose_at(t, i));
        fr.kinematic_height = kinematic_contact_height(w, X, edge, res.view_direction_W);
        const std::vector<Eigen::Vector3d>* tracked = t.has_shapes() ? &t.shape_W[i] : nullptr;
        TrackedInput in;
        if (res.has_contact_point_mode) in.p_W_contact = t.contact_W[i];
        for (std::size_t m = 0; m < modes.size(); ++m) {
          const TrackedFrame& tf = trackers[m].step_tracked(X, &segment, in);
          record(w, tf, edge, tracked, fr.*(modes[m].second));
          if (tf.onset) info.approach_W = tf.approach_W;
          if (modes[m].first == ContactMode::edge && std::isnan(info.onset_height_edge) && fr.edge.ok())
            info.onset_height_edge = fr.edge.height;
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
