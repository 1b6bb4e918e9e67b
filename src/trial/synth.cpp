#include "vibrissa/trial/synth.hpp"

#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <stdexcept>
#include <string>

#include "vibrissa/core/rest_curve.hpp"
#include "vibrissa/solve/solvers.hpp"
#include "vibrissa/trial/contact_geometry.hpp"

namespace vibrissa::trial {

namespace {

void require(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument("synthetic trial: " + what);
}

/// Whether the rest whisker has swept past the peg: in the plane normal to the edge, the azimuth (about
/// the base) of the whisker point at the peg's radial distance exceeds the peg's azimuth. nullopt if the
/// whisker does not reach that distance.
std::optional<bool> past_peg(const Whisker& w, const Edge& edge) {
  const Eigen::Vector3d d = edge.direction.normalized();
  const Eigen::Vector3d base = w.p_W_base();
  auto perp = [&](const Eigen::Vector3d& p) {
    Eigen::Vector3d r = p - base;
    return Eigen::Vector3d(r - r.dot(d) * d);
  };
  const Eigen::Vector3d peg = perp(edge.point);
  const double radius = peg.norm();
  const auto& nodes = w.rest_nodes_B();
  Eigen::Vector3d prev = perp(w.to_world(nodes[0]));
  for (std::size_t i = 1; i < nodes.size(); ++i) {
    const Eigen::Vector3d cur = perp(w.to_world(nodes[i]));
    if (prev.norm() <= radius && cur.norm() >= radius) {
      const double t = (radius - prev.norm()) / std::max(cur.norm() - prev.norm(), 1e-300);
      const Eigen::Vector3d q = prev + t * (cur - prev);
      // Signed angle from the peg to q about d: positive = ahead in the sense of rotation about +d.
      return d.dot(peg.cross(q)) > 0.0;
    }
    prev = cur;
  }
  return std::nullopt;
}

}  // namespace

Trial synthesize_trial(const SynthOptions& o, SynthStats* stats, const RunControl& control) {
  require(o.duration > 0.0 && o.frame_rate > 0.0, "duration and frame rate must be positive");
  require(o.whisk_frequency > 0.0 && o.whisk_frequency < 0.5 * o.frame_rate, "whisk frequency must be in (0, fs/2)");
  require(o.whisker_length > 0.0 && o.peg_distance > 0.0, "whisker length and peg distance must be positive");
  require(o.mu >= 0.0 && std::isfinite(o.mu), "mu must be finite and >= 0");
  require(o.noise_position >= 0.0 && o.noise_angle >= 0.0, "noise levels must be >= 0");
  require(o.protraction_fraction > 0.0 && o.protraction_fraction < 1.0, "protraction fraction must lie in (0, 1)");
  require(o.rest_points >= 3 && o.shape_nodes >= 2, "need >= 3 rest points and >= 2 shape nodes");

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
  std::vector<Pose> poses(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double time = static_cast<double>(i) / o.frame_rate;
    // One whisk: protraction by a half cosine over protraction_fraction of the cycle, then retraction.
    const double phase = std::fmod(o.whisk_frequency * time, 1.0), pf = o.protraction_fraction;
    const double theta = phase < pf ? o.theta_center - o.theta_amplitude * std::cos(std::numbers::pi * phase / pf)
                                    : o.theta_center + o.theta_amplitude * std::cos(std::numbers::pi * (phase - pf) / (1.0 - pf));
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

  enum class State { free, touching, passed } state = State::free;
  std::optional<bool> was_past;
  std::optional<LoadState> warm;
  Eigen::Vector3d previous_contact = Eigen::Vector3d::Zero();
  std::optional<Eigen::Vector3d> approach;
  ProgressCounter counter(control, n);
  SolveOptions sopt;
  sopt.compute_shape = o.shapes;
  for (std::size_t i = 0; i < n; ++i) {
    const Whisker w = rest.placed(poses[i]);
    const std::optional<bool> past = past_peg(w, peg);
    if (state == State::free && past && *past && was_past && !*was_past) {
      // Onset: the rest whisker has just crossed the peg. The contact starts where it touches the peg.
      state = State::touching;
      const NearestOnWhisker touch = nearest_rest_point(w, peg);
      previous_contact = touch.on_edge_W;
      const Whisker before = rest.placed(poses[i - 1]);
      const Whisker after = rest.placed(poses[std::min(i + 1, n - 1)]);
      const Eigen::Vector3d a = approach_direction(before, after, touch.arc_length, peg);
      approach = a.norm() > 0.0 ? std::optional<Eigen::Vector3d>(a) : std::nullopt;
      warm.reset();
      ++st.periods;
    } else if (state == State::passed && past && !*past) {
      state = State::free;  // retracted behind the peg again
    }
    was_past = past;
    if (state == State::touching) {
      const Solution s = solve_frictional_edge(w, peg, o.mu, previous_contact, sopt, warm ? &*warm : nullptr, approach);
      if (s.status == Status::converged) {
        t.contact[i] = 1;
        t.contact_W[i] = s.contact_point;
        previous_contact = s.contact_point;
        warm = s.state;
        ++st.contact_frames;
        if (s.message.rfind("stick", 0) == 0) ++st.stick_frames;
        else ++st.slip_frames;
        if (o.shapes && !s.shape.empty()) {
          for (int k = 0; k < o.shape_nodes; ++k) {
            const double f = static_cast<double>(k) / (o.shape_nodes - 1) * static_cast<double>(s.shape.size() - 1);
            const auto j = static_cast<std::size_t>(std::floor(f));
            const double u = f - static_cast<double>(j);
            const std::size_t j1 = std::min(j + 1, s.shape.size() - 1);
            t.shape_W[i].push_back((1.0 - u) * s.shape[j] + u * s.shape[j1]);
          }
        }
      } else {
        if (s.status == Status::slipped_off) {
          ++st.slip_offs;
          state = State::passed;
        } else if (s.status == Status::no_contact) {
          ++st.releases;
          state = State::free;
        } else {
          ++st.failures;
          state = State::passed;
        }
      }
    }
    if (o.shapes && t.shape_W[i].empty())
      for (int k = 0; k < o.shape_nodes; ++k)
        t.shape_W[i].push_back(w.rest_point_W(o.whisker_length * k / (o.shape_nodes - 1)));
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
