#include "vibrissa/trial/analysis.hpp"

#include <cmath>

#include "vibrissa/contact/contact_geometry.hpp"

namespace vibrissa::trial {

namespace {
double mean_finite(const std::vector<FrameResult>& frames, Mode mode) {
  double s = 0.0;
  std::size_t c = 0;
  for (const auto& f : frames) {
    const double e = f.mode(mode).shape_error;
    if (std::isfinite(e)) {
      s += e;
      ++c;
    }
  }
  return c ? s / static_cast<double>(c) : std::nan("");
}
}  // namespace

TrialAnalysis analyse_trial(const PipelineResult& r, const AnalysisOptions& o) {
  TrialAnalysis a;
  const Trial& t = r.pre.trial;
  double len = 0.0;
  for (std::size_t k = 1; k < t.meta.rest_shape.size(); ++k) len += (t.meta.rest_shape[k] - t.meta.rest_shape[k - 1]).norm();
  a.whisker_length = len;
  if (r.has_contact_point_mode) a.friction = analyse_friction(r, Mode::contact_point, o.friction);
  if (r.has_frictional_mode) a.friction_frictional = analyse_friction(r, Mode::frictional_edge, o.friction);
  a.directions = analyse_force_directions(r);
  double mu = 0.48;
  if (o.mu_eq7) mu = *o.mu_eq7;
  else if (a.friction && std::isfinite(a.friction->median)) mu = a.friction->median;
  else if (r.mu) mu = *r.mu;
  if (r.has_contact_point_mode && r.has_edge_mode) a.z_error = analyse_z_error(r, len, mu);

  // Fig. 2f: measured height of contact (tracked point) vs the kinematic prediction.
  const std::size_t n = r.frames.size();
  a.kinematic.measured.assign(n, std::nan(""));
  a.kinematic.predicted.assign(n, std::nan(""));
  std::vector<double> x, y;
  for (std::size_t i = 0; i < n; ++i) {
    const FrameResult& f = r.frames[i];
    if (f.period < 0 || !t.has_contact_point()) continue;
    const Edge& e = t.meta.edges[static_cast<std::size_t>(r.periods[static_cast<std::size_t>(f.period)].edge_index)];
    a.kinematic.measured[i] = height_along_edge(e, t.contact_W[i]);
    a.kinematic.predicted[i] = f.kinematic_height;
    if (std::isfinite(f.kinematic_height)) {
      x.push_back(a.kinematic.measured[i]);
      y.push_back(f.kinematic_height);
    }
  }
  if (x.size() >= 3) {
    try {
      a.kinematic.fit = fit_line(x, y);
    } catch (const std::invalid_argument&) {
    }
  }
  a.shape_error.contact_point_mean = mean_finite(r.frames, Mode::contact_point);
  a.shape_error.edge_mean = mean_finite(r.frames, Mode::edge);
  a.shape_error.frictional_mean = mean_finite(r.frames, Mode::frictional_edge);
  return a;
}

}  // namespace vibrissa::trial
