#include "vibrissa/trial/synth.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <span>
#include <stdexcept>
#include <string>

#include "vibrissa/core/checks.hpp"
#include "vibrissa/core/limits.hpp"
#include "vibrissa/core/rest_curve.hpp"
#include "vibrissa/solve/solvers.hpp"
#include "vibrissa/contact/contact_geometry.hpp"
#include "vibrissa/contact/tracker.hpp"
#include "vibrissa/trial/synth_parameters.hpp"

namespace vibrissa::trial {

namespace {

void require(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument("synthetic trial: " + what);
}

}  // namespace

void validate_synth_options(const SynthOptions& o) {
  // Every parameter finite first (named as the flag / keyword in its unit), then the ranges; the frame
  // count is bounded by what `vibrissa trial` reads (limits::max_trial_frames) before anything is allocated.
  for (const SynthParameter& p : synth_parameters()) require_finite(o.*p.field * p.unit_per_si, p.name);
  require(o.duration > 0.0 && o.frame_rate > 0.0,
          "duration and frame rate must be positive, got " + format_value(o.duration) + " s and " +
              format_value(o.frame_rate) + " Hz");
  const double frame_count = std::floor(o.duration * o.frame_rate);
  require(frame_count <= double(limits::max_trial_frames),
          "duration x frame_rate = " + format_value(frame_count) + " frames, more than the " +
              std::to_string(limits::max_trial_frames) + " frames a trial may have (docs/formats.md, \"Limits\")");
  require(o.whisk_frequency > 0.0 && o.whisk_frequency < 0.5 * o.frame_rate,
          "whisk_hz must be in (0, frame_rate / 2), got " + format_value(o.whisk_frequency));
  require_in_range(o.whisker_length, limits::min_whisker_length_m, limits::max_whisker_length_m, "whisker_length [m]");
  require(o.peg_distance > 0.0, "peg_distance_mm must be positive, got " + format_value(o.peg_distance * 1e3));
  require(o.mu >= 0.0, "mu must be >= 0, got " + format_value(o.mu));
  require(o.noise_position >= 0.0 && o.noise_angle >= 0.0, "noise levels must be >= 0");
  require(o.protraction_fraction > 0.0 && o.protraction_fraction < 1.0,
          "protraction_fraction must lie in (0, 1), got " + format_value(o.protraction_fraction));
  require(o.rest_points >= 3 && o.shape_nodes >= 2 && std::size_t(o.rest_points) <= limits::max_shape_points &&
              std::size_t(o.shape_nodes) < limits::max_shape_points,
          "need 3 to " + std::to_string(limits::max_shape_points) + " rest points and 2 to " +
              std::to_string(limits::max_shape_points - 1) + " shape nodes");
  require(o.theta_center_jitter >= 0.0, "theta_center_jitter_deg must be >= 0, got " +
                                            format_value(o.theta_center_jitter * 180.0 / std::numbers::pi));
  require(o.theta_amplitude_jitter >= 0.0,
          "theta_amplitude_jitter must be >= 0, got " + format_value(o.theta_amplitude_jitter));
}

Trial synthesize_trial(const SynthOptions& o, SynthStats* stats, const RunControl& control) {
  validate_synth_options(o);
  Trial t;
  t.source = "synthetic";
  t.meta.material = o.material;
  t.meta.frame_rate = o.frame_rate;
  // Rest shape y = a x^2 (whisker frame), written as points; the simulation uses the whisker the pipeline
  // will rebuild from exactly these points.
  t.meta.rest_shape = planar_polynomial_nodes(o.whisker_length, 0.0, o.curvature, o.rest_points - 1);
  Edge peg;
  peg.point = Eigen::Vector3d(o.peg_distance * std::cos(o.peg_azimuth), o.peg_distance * std::sin(o.peg_azimuth), 0.0);
  peg.direction = Eigen::Vector3d::UnitZ();
  t.meta.edges.push_back(peg);
  const WhiskerProperties props = whisker_properties(o.material);

  const auto n = static_cast<std::size_t>(std::floor(o.duration * o.frame_rate));
  require(n >= 10, "the trial needs at least 10 frames");
  // Whisk k rises from its trough c_k - A_k to its peak c_k + A_k by a half cosine over protraction_fraction of
  // the cycle, then falls to the next whisk's trough: theta is continuous whatever the whisk-to-whisk
  // variation of set-point c_k and amplitude A_k (their own random stream, so tracking noise is unchanged).
  const auto whisks = static_cast<std::size_t>(std::ceil(o.duration * o.whisk_frequency)) + 2;
  std::vector<double> trough(whisks), peak(whisks);
  {
    std::mt19937_64 whisk_rng(o.seed ^ 0x9e3779b97f4a7c15ULL);
    std::normal_distribution<double> g(0.0, 1.0);
    for (std::size_t k = 0; k < whisks; ++k) {
      const double c = o.theta_center + o.theta_center_jitter * g(whisk_rng);
      const double A = o.theta_amplitude * std::max(0.1, 1.0 + o.theta_amplitude_jitter * g(whisk_rng));
      trough[k] = c - A;
      peak[k] = c + A;
    }
  }
  std::vector<Pose> poses(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double time = static_cast<double>(i) / o.frame_rate;
    const double cycles = o.whisk_frequency * time, pf = o.protraction_fraction;
    const auto k = static_cast<std::size_t>(std::floor(cycles));
    const double phase = cycles - std::floor(cycles);
    const double rise = phase < pf ? 0.5 * (1.0 - std::cos(std::numbers::pi * phase / pf))
                                   : 0.5 * (1.0 - std::cos(std::numbers::pi * (phase - pf) / (1.0 - pf)));
    const double theta = phase < pf ? trough[k] + (peak[k] - trough[k]) * rise : peak[k] + (trough[k + 1] - peak[k]) * rise;
    poses[i].theta = theta;
    poses[i].phi = o.phi_center + o.phi_slope * (theta - o.theta_center);    // spec §2.2
    poses[i].zeta = o.zeta_center + o.zeta_slope * (theta - o.theta_center);  // spec §2.2
    t.time.push_back(time);
  }
  const Whisker rest = Whisker::from_points(t.meta.rest_shape, props, poses[0]);

  t.contact.assign(n, 0);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  t.contact_W.assign(n, Eigen::Vector3d::Constant(nan));
  if (o.shapes) t.shape_W.assign(n, {});
  SynthStats st;
  st.frames = n;

  // Every frame through the one contact tracker (contact/tracker.hpp): onset when the rest whisker sweeps
  // across the peg, frictional edge mode while touching, push-past and release as everywhere else.
  TrackerOptions topt;
  topt.mode = ContactMode::frictional_edge;
  topt.mu = o.mu;
  topt.solve.compute_shape = false;
  ContactTracker tracker(rest, topt);
  const EdgeSegment peg_segment = infinite_segment(peg);
  const std::span<const EdgeSegment> scene(&peg_segment, 1);
  ProgressCounter counter(control, n);
  std::vector<Eigen::Vector3d> bent;
  for (std::size_t i = 0; i < n; ++i) {
    const Placement X(poses[i]);
    const TrackedFrame& fr = tracker.step(X, scene);
    if (fr.onset) ++st.periods;
    if (fr.solved) {
      const Solution& s = fr.solution;
      if (fr.state == ContactState::contact) {
        t.contact[i] = 1;
        t.contact_W[i] = s.contact_point_W;
        ++st.contact_frames;
        if (s.friction == FrictionState::stick) ++st.stick_frames;
        if (s.friction == FrictionState::slip) ++st.slip_frames;
      } else if (s.status == Status::slipped_off) {
        ++st.slip_offs;
      } else if (s.status == Status::no_contact) {
        ++st.releases;
      } else {
        ++st.failures;
      }
    }
    if (o.shapes) {  // the tracked shape: deflected in contact frames, the rest shape otherwise
      const double L = rest.length();
      if (t.contact[i]) {
        if (fr.solution.second_contact) bent = fr.solution.shape_W;  // two contacts: not the state's load alone
        else deflected_shape(rest, X, fr.solution.state, bent);
      }
      for (int k = 0; k < o.shape_nodes; ++k) {
        const double s_k = L * k / (o.shape_nodes - 1);
        if (!t.contact[i]) {
          t.shape_W[i].push_back(X.to_world(rest.rest_point_B(s_k)));
          continue;
        }
        const double f = static_cast<double>(k) / (o.shape_nodes - 1) * static_cast<double>(bent.size() - 1);
        const auto j = static_cast<std::size_t>(std::floor(f));
        const double u = f - static_cast<double>(j);
        const std::size_t j1 = std::min(j + 1, bent.size() - 1);
        t.shape_W[i].push_back((1.0 - u) * bent[j] + u * bent[j1]);
      }
    }
    counter.advance();
  }

  // Tracking noise (optional), then the tracked columns.
  std::mt19937_64 rng(o.seed);
  std::normal_distribution<double> gauss(0.0, 1.0);
  auto noisy_vec = [&](const Eigen::Vector3d& v) {
    return o.noise_position > 0.0 ? Eigen::Vector3d(v + o.noise_position * Eigen::Vector3d(gauss(rng), gauss(rng), gauss(rng))) : v;
  };
  auto noisy = [&](double v) { return o.noise_angle > 0.0 ? v + o.noise_angle * gauss(rng) : v; };
  for (std::size_t i = 0; i < n; ++i) {
    t.base_W.push_back(noisy_vec(poses[i].p_W_base));
    t.theta.push_back(noisy(poses[i].theta));
    t.phi.push_back(noisy(poses[i].phi));
    t.zeta.push_back(noisy(poses[i].zeta));
    if (t.contact[i]) t.contact_W[i] = noisy_vec(t.contact_W[i]);
  }
  if (stats) *stats = st;
  return t;
}

}  // namespace vibrissa::trial
