#include "vibrissa/recon/reconstruct.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <stdexcept>

#include "curve_fit.hpp"
#include "vibrissa/core/checks.hpp"
#include "vibrissa/core/limits.hpp"
#include "vibrissa/core/pose.hpp"
#include "vibrissa/core/rest_curve.hpp"
#include "vibrissa/recon/geometry.hpp"

namespace vibrissa::recon {

namespace {
constexpr double nan_v = std::numeric_limits<double>::quiet_NaN();
const Eigen::Vector3d nan3 = Eigen::Vector3d::Constant(nan_v);

double median_of(std::vector<double> v) {
  std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(v.size() / 2), v.end());
  return v[v.size() / 2];
}

struct ViewPoints {
  std::vector<Eigen::Vector2d> px, ideal;
  std::vector<double> likelihood;
  std::vector<double> arc;  ///< cumulative ideal-pixel arc length, normalised to [0, 1]
};

ViewPoints usable_points(const TrackFrame& f, const Camera& cam, double min_likelihood) {
  ViewPoints v;
  for (std::size_t k = 0; k < f.points_px.size(); ++k) {
    if (!(f.likelihood[k] >= min_likelihood) || !f.points_px[k].allFinite()) continue;
    v.px.push_back(f.points_px[k]);
    v.ideal.push_back(cam.undistort(f.points_px[k]));
    v.likelihood.push_back(f.likelihood[k]);
  }
  v.arc.assign(v.px.size(), 0.0);
  for (std::size_t k = 1; k < v.px.size(); ++k) v.arc[k] = v.arc[k - 1] + (v.ideal[k] - v.ideal[k - 1]).norm();
  if (!v.arc.empty() && v.arc.back() > 0.0)
    for (double& a : v.arc) a /= v.arc.back();
  return v;
}

struct Match {
  std::size_t own;          ///< index into the points of the view whose epipolar lines are drawn
  Eigen::Vector2d other_px; ///< the matched pixel on the other view's polyline (measured pixels)
  double own_arc, other_arc;  ///< relative arc lengths in both views
  double other_likelihood;
};

/// Where the epipolar line `l` (unit normal, ideal pixels) crosses the parabola through the three end points of
/// a view beyond its base (`at_base`) or tip, near the straight extension's parameter `t_line` (in units of
/// the end segment): the measured pixel there, or nullopt when the line misses the parabola beyond the end.
/// The parabola is parameterised by chord length (points need not be equally spaced: some may be lost).
std::optional<Eigen::Vector2d> end_parabola(const ViewPoints& v, const Eigen::Vector3d& l, bool at_base,
                                            double t_line) {
  const std::size_t n = v.ideal.size();
  // Nodes at chord lengths 0, s1, s2 from point 0 (base end) or from point n - 3 (tip end).
  const std::array<std::size_t, 3> k = at_base ? std::array<std::size_t, 3>{0, 1, 2}
                                               : std::array<std::size_t, 3>{n - 3, n - 2, n - 1};
  const double s1 = (v.ideal[k[1]] - v.ideal[k[0]]).norm(), s2 = s1 + (v.ideal[k[2]] - v.ideal[k[1]]).norm();
  if (!(s1 > 0.0 && s2 > s1)) return std::nullopt;
  const double sigma_line = at_base ? t_line * s1 : s1 + t_line * (s2 - s1);
  // Newton form: f(sigma) = f0 + sigma f01 + sigma (sigma - s1) f012.
  const auto newton = [&](const Eigen::Vector2d& f0, const Eigen::Vector2d& f1, const Eigen::Vector2d& f2,
                          double sigma) -> Eigen::Vector2d {
    const Eigen::Vector2d f01 = (f1 - f0) / s1;
    const Eigen::Vector2d f012 = ((f2 - f1) / (s2 - s1) - f01) / s2;
    return f0 + sigma * f01 + sigma * (sigma - s1) * f012;
  };
  std::array<double, 3> d{};
  for (std::size_t m = 0; m < 3; ++m) d[m] = l.dot(v.ideal[k[m]].homogeneous());
  const double f01 = (d[1] - d[0]) / s1, f012 = ((d[2] - d[1]) / (s2 - s1) - f01) / s2;
  const double a = f012, b = f01 - s1 * f012, c = d[0];  // a sigma^2 + b sigma + c
  double sigma = 0.0;
  if (std::abs(a) * s2 * s2 <= 1e-12 * (std::abs(b) * s2 + std::abs(c))) {
    if (b == 0.0) return std::nullopt;
    sigma = -c / b;
  } else {
    const double disc = b * b - 4.0 * a * c;
    if (disc < 0.0) return std::nullopt;
    const double r1 = (-b + std::sqrt(disc)) / (2.0 * a), r2 = (-b - std::sqrt(disc)) / (2.0 * a);
    sigma = std::abs(r1 - sigma_line) < std::abs(r2 - sigma_line) ? r1 : r2;
  }
  if (at_base ? sigma > 0.0 : sigma < s2) return std::nullopt;  // not beyond the end
  return newton(v.px[k[0]], v.px[k[1]], v.px[k[2]], sigma);
}

/// For each point of `own`, the intersection of its epipolar line (F * x_own) with the `other` polyline
/// nearest the same relative arc length (gated), then the longest run monotonic in the other view's arc
/// length. Beyond its ends, `other` is extended by up to `end_extension` tracked spacings along the parabola
/// through its three end points: a base (or tip) point lost in the other view is then still matched.
std::vector<Match> match_views(const ViewPoints& own, const ViewPoints& other, const Eigen::Matrix3d& F) {
  constexpr double min_sine = 0.05;  // epipolar line nearly tangent to the curve: position undetermined
  constexpr double arc_gate = 0.35;  // relative arc lengths of the two views differ by foreshortening
  constexpr double end_extension = 2.5;  // [segments]: up to two lost end points
  std::vector<Match> candidates;
  for (std::size_t i = 0; i < own.ideal.size(); ++i) {
    Eigen::Vector3d l = F * own.ideal[i].homogeneous();
    const double norm = l.head<2>().norm();
    if (!(norm > 0.0)) continue;
    l /= norm;  // l . x = signed distance [px]
    std::optional<Match> best;
    double best_gap = arc_gate;
    for (std::size_t j = 0; j + 1 < other.ideal.size(); ++j) {
      const double d0 = l.dot(other.ideal[j].homogeneous()), d1 = l.dot(other.ideal[j + 1].homogeneous());
      if (d0 == d1) continue;
      const double seg = (other.ideal[j + 1] - other.ideal[j]).norm();
      if (!(std::abs(d0 - d1) > min_sine * seg)) continue;
      const double t = d0 / (d0 - d1);
      const double t_min = j == 0 ? -end_extension : 0.0;
      const double t_max = j + 2 == other.ideal.size() ? 1.0 + end_extension : 1.0;
      if (t < t_min || t > t_max) continue;
      const double arc = other.arc[j] + t * (other.arc[j + 1] - other.arc[j]);
      const double gap = std::abs(arc - own.arc[i]);
      if (gap >= best_gap) continue;
      Eigen::Vector2d px = other.px[j] + t * (other.px[j + 1] - other.px[j]);
      if ((t < 0.0 || t > 1.0) && other.ideal.size() >= 3) {
        const auto q = end_parabola(other, l, t < 0.0, t);
        if (!q) continue;
        px = *q;
      }
      best_gap = gap;
      const double tl = std::clamp(t, 0.0, 1.0);
      best = Match{i, px, own.arc[i], arc, other.likelihood[j] + tl * (other.likelihood[j + 1] - other.likelihood[j])};
    }
    if (best) candidates.push_back(*best);
  }
  // Longest subsequence increasing in the other view's arc length (O(n^2); n is a few hundred at most).
  const std::size_t n = candidates.size();
  std::vector<std::size_t> len(n, 1), prev(n, n);
  std::size_t end = 0;
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = 0; j < i; ++j)
      if (candidates[j].other_arc < candidates[i].other_arc && len[j] + 1 > len[i]) {
        len[i] = len[j] + 1;
        prev[i] = j;
      }
    if (len[i] > len[end]) end = i;
  }
  std::vector<Match> out;
  for (std::size_t i = n ? end : n; i < n; i = prev[i]) out.push_back(candidates[i]);
  std::reverse(out.begin(), out.end());
  return out;
}

/// Closest approach of the polyline to the edges: distance, point on the whisker, its arc length.
void closest_approach(ReconstructedFrame& f, const std::vector<Edge>& edges, double threshold) {
  double best = std::numeric_limits<double>::infinity();
  double s_along = 0.0;
  for (const Edge& e : edges) {
    const Eigen::Vector3d d = e.direction.normalized();
    double s0 = 0.0;
    for (std::size_t k = 0; k + 1 < f.shape_W.size(); ++k) {
      const Eigen::Vector3d p = f.shape_W[k], u = f.shape_W[k + 1] - p;
      const Eigen::Vector3d w0 = p - e.point;
      const double uu = u.squaredNorm(), ud = u.dot(d);
      const double denom = uu - ud * ud;
      double s = denom > 1e-300 ? (ud * d.dot(w0) - u.dot(w0)) / denom : 0.0;
      s = std::clamp(s, 0.0, 1.0);
      const Eigen::Vector3d q = p + s * u;
      const double dist = ((q - e.point) - d.dot(q - e.point) * d).norm();
      if (dist < best) {
        best = dist;
        s_along = s0 + s * std::sqrt(uu);
        f.contact_W = e.point + d.dot(q - e.point) * d;  // on the edge, where the object is touched
      }
      s0 += std::sqrt(uu);
    }
  }
  f.approach = best;
  f.contact = best < threshold;
  f.contact_s = f.contact ? s_along : nan_v;
  if (!f.contact) f.contact_W = nan3;
}

ReconstructedFrame reconstruct_frame(std::int64_t frame, const TrackFrame* top, const Camera& top_cam,
                                     const TrackFrame* front, const Camera& front_cam, const Eigen::Matrix3d& F,
                                     const ReconstructOptions& o) {
  ReconstructedFrame f;
  f.frame = frame;
  if (!top || !front) return f;
  const ViewPoints a = usable_points(*top, top_cam, o.min_likelihood);
  const ViewPoints b = usable_points(*front, front_cam, o.min_likelihood);
  f.status = FrameStatus::too_few_points;
  if (a.px.size() < 2 || b.px.size() < 2) return f;
  // Match both ways (top points on the front polyline and front points on the top polyline), so that a
  // point lost in one view (e.g. the base) is still reconstructed from the other; order along the whisker.
  struct Point3 {
    double arc;  ///< mean relative arc length of the two views (orders the points base to tip)
    Eigen::Vector3d p_W;
    double error_px, likelihood;
  };
  std::vector<Point3> found;
  double first_arc = std::numeric_limits<double>::infinity(), last_arc = -first_arc;  // of the top matches
  // A front point counts as beyond an end of the top matches only by more than half a front-view spacing
  // (relative arc length): a point the top view lost is a whole spacing out, while the views' own end points
  // differ by pixel noise only, and keeping those of them that happen to fall outside lengthened the curve at
  // both ends (a base ~0.6 px behind the follicle at 0.5 px noise, and a systematic angle bias).
  const double beyond_margin = 0.5 / double(b.px.size() - 1);
  for (const bool from_top : {true, false}) {
    const ViewPoints& own = from_top ? a : b;
    for (const Match& m : match_views(own, from_top ? b : a, from_top ? F : Eigen::Matrix3d(F.transpose()))) {
      const double arc = 0.5 * (m.own_arc + m.other_arc);
      // Front points only beyond the ends of the top matches: inside, they would repeat the same stretch with
      // pixel errors shared with the top matches (correlated residuals make the fit follow the noise).
      if (!from_top && arc >= first_arc - beyond_margin && arc <= last_arc + beyond_margin) continue;
      const Eigen::Vector2d top_px = from_top ? own.px[m.own] : m.other_px;
      const Eigen::Vector2d front_px = from_top ? m.other_px : own.px[m.own];
      const Triangulated t = triangulate({&top_cam, &front_cam}, {top_px, front_px});
      if (!t.ok) continue;
      found.push_back({arc, t.p_W, t.reprojection_px, std::sqrt(own.likelihood[m.own] * m.other_likelihood)});
      if (from_top) {
        first_arc = std::min(first_arc, arc);
        last_arc = std::max(last_arc, arc);
      }
    }
  }
  std::stable_sort(found.begin(), found.end(), [](const Point3& x, const Point3& y) { return x.arc < y.arc; });
  std::vector<Eigen::Vector3d> pts;
  std::vector<double> err, like;
  for (const Point3& p : found) {
    pts.push_back(p.p_W);
    err.push_back(p.error_px);
    like.push_back(p.likelihood);
  }
  if (pts.size() < std::size_t(o.min_points)) return f;
  const double gate = std::max(o.outlier_px, 3.0 * median_of(err));
  std::vector<Eigen::Vector3d> kept;
  std::vector<double> weights;
  double sum2 = 0.0, sum_like = 0.0;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    if (err[i] > gate) continue;
    kept.push_back(pts[i]);
    weights.push_back(like[i]);
    sum2 += err[i] * err[i];
    sum_like += like[i];
  }
  f.points_used = kept.size();
  if (kept.size() < std::size_t(o.min_points)) return f;
  f.reprojection_px = std::sqrt(sum2 / double(kept.size()));
  f.likelihood = sum_like / double(kept.size());
  if (f.reprojection_px > o.max_reprojection_px) {
    f.status = FrameStatus::reprojection;
    return f;
  }
  const auto curve = fit_curve(kept, weights, std::min(o.fit_segments, int(kept.size()) - 4), o.nodes);
  if (!curve) return f;
  // theta and phi are the direction of the base tangent (the rigid base, spec §2.2). whisker_frame projects the
  // tangent into the best-fit plane of the proximal shape: the same for an undeflected (planar) whisker, but
  // a deflected one leaves that plane and the projection tilts by about 1 degree. So x = the tangent, and the
  // plane only fixes the roll about it.
  Eigen::Matrix3d R_WB = whisker_frame(curve->nodes, curve->tangent0);
  const Eigen::Vector3d x = curve->tangent0;
  const Eigen::Vector3d z = (R_WB.col(2) - R_WB.col(2).dot(x) * x).normalized();
  R_WB.col(0) = x;
  R_WB.col(1) = z.cross(x);
  R_WB.col(2) = z;
  const Pose pose = pose_from_rotation(R_WB, curve->nodes.front());
  f.status = FrameStatus::ok;
  f.shape_W = curve->nodes;
  f.base_W = pose.p_W_base;
  f.theta = pose.theta;
  f.phi = pose.phi;
  f.zeta = pose.zeta;
  if (!o.edges.empty()) closest_approach(f, o.edges, o.contact_threshold);
  return f;
}

void clear_values(ReconstructedFrame& f) {
  const FrameStatus status = f.status;
  const double rep = f.reprojection_px, like = f.likelihood;
  const std::size_t used = f.points_used;
  const std::int64_t frame = f.frame;
  f = ReconstructedFrame();
  f.frame = frame;
  f.status = status;
  f.reprojection_px = rep;
  f.likelihood = like;
  f.points_used = used;
}

}  // namespace

ReconstructedFrame::ReconstructedFrame()
    : reprojection_px(nan_v), likelihood(nan_v), base_W(nan3), theta(nan_v), phi(nan_v), zeta(nan_v),
      contact_W(nan3), contact_s(nan_v), approach(nan_v) {}

const char* frame_status_name(FrameStatus s) {
  switch (s) {
    case FrameStatus::ok: return "ok";
    case FrameStatus::missing_view: return "missing_view";
    case FrameStatus::too_few_points: return "too_few_points";
    case FrameStatus::reprojection: return "reprojection";
    case FrameStatus::inconsistent_base: return "inconsistent_base";
  }
  return "unknown";
}

std::size_t Reconstruction::count(FrameStatus s) const {
  return std::size_t(std::count_if(frames.begin(), frames.end(), [&](const auto& f) { return f.status == s; }));
}

void ReconstructOptions::validate() const {
  auto require = [](bool ok, const std::string& field, double v, const char* expected) {
    if (!ok) throw std::invalid_argument(field + " must be " + expected + ", got " + format_value(v));
  };
  require(min_likelihood >= 0.0 && min_likelihood <= 1.0, "min_likelihood", min_likelihood, "in [0, 1]");
  require(min_points >= 3, "min_points", min_points, ">= 3");
  require(max_reprojection_px > 0.0, "max_reprojection_px", max_reprojection_px, "> 0");
  require(outlier_px > 0.0, "outlier_px", outlier_px, "> 0");
  require(fit_segments >= 1 && fit_segments <= 50, "fit_segments", fit_segments, "in [1, 50]");
  // nodes + 1 points are written: at most limits::max_shape_points, the limit of every trial reader.
  require(nodes >= 2 && nodes < int(limits::max_shape_points), "nodes", nodes,
          ("in [2, " + std::to_string(limits::max_shape_points - 1) + "]").c_str());
  require(contact_threshold > 0.0 && std::isfinite(contact_threshold), "contact_threshold", contact_threshold, "> 0");
  require(base_jump > 0.0, "base_jump", base_jump, "> 0");
  require(base_window >= 1, "base_window", base_window, ">= 1");
  require(frame_rate > 0.0 && std::isfinite(frame_rate), "frame_rate", frame_rate, "> 0");
  for (std::size_t k = 0; k < edges.size(); ++k)
    if (!edges[k].point.allFinite() || !edges[k].direction.allFinite() || edges[k].direction.norm() == 0.0)
      throw std::invalid_argument("edges[" + std::to_string(k) + "] needs a finite point and non-zero direction");
}

Reconstruction reconstruct(const Tracks2D& top, const Camera& top_camera, const Tracks2D& front,
                           const Camera& front_camera, const ReconstructOptions& o, const RunControl& control) {
  o.validate();
  std::vector<std::int64_t> frames;
  for (const auto* t : {&top, &front})
    for (const auto& f : t->frames) frames.push_back(f.frame);
  std::sort(frames.begin(), frames.end());
  frames.erase(std::unique(frames.begin(), frames.end()), frames.end());
  const Eigen::Matrix3d F = fundamental_matrix(top_camera, front_camera);
  Reconstruction rec;
  rec.frames.resize(frames.size());
  ProgressCounter progress(control, frames.size());
  for (std::size_t i = 0; i < frames.size(); ++i) {
    rec.frames[i] = reconstruct_frame(frames[i], top.find(frames[i]), top_camera, front.find(frames[i]), front_camera,
                                      F, o);
    progress.advance();
  }
  // Identity check: a base far from the median base of the neighbouring good frames is another whisker.
  std::vector<std::size_t> good;
  for (std::size_t i = 0; i < rec.frames.size(); ++i)
    if (rec.frames[i].ok()) good.push_back(i);
  std::vector<bool> inconsistent(rec.frames.size(), false);
  for (std::size_t g = 0; g < good.size(); ++g) {
    const std::size_t lo = g >= std::size_t(o.base_window) ? g - std::size_t(o.base_window) : 0;
    const std::size_t hi = std::min(good.size() - 1, g + std::size_t(o.base_window));
    Eigen::Vector3d med;
    for (int a = 0; a < 3; ++a) {
      std::vector<double> v;
      for (std::size_t k = lo; k <= hi; ++k) v.push_back(rec.frames[good[k]].base_W[a]);
      med[a] = median_of(v);
    }
    inconsistent[good[g]] = (rec.frames[good[g]].base_W - med).norm() > o.base_jump;
  }
  for (std::size_t i = 0; i < rec.frames.size(); ++i)
    if (inconsistent[i]) {
      rec.frames[i].status = FrameStatus::inconsistent_base;
      clear_values(rec.frames[i]);
    }
  // Undeflected shape of each contact period (periods over the reconstructed frames).
  good.clear();
  for (std::size_t i = 0; i < rec.frames.size(); ++i)
    if (rec.frames[i].ok()) good.push_back(i);
  for (std::size_t g = 0; g < good.size(); ++g) {
    const auto& f = rec.frames[good[g]];
    if (!f.contact || (g > 0 && rec.frames[good[g - 1]].contact)) continue;
    std::size_t last = g;
    while (last + 1 < good.size() && rec.frames[good[last + 1]].contact) ++last;
    UndeflectedShape u;
    u.first_frame = f.frame;
    u.last_frame = rec.frames[good[last]].frame;
    // The free stretch before the period (else after it): every free frame up to the neighbouring period.
    std::vector<std::size_t> stretch;
    for (std::size_t k = g; k-- > 0 && !rec.frames[good[k]].contact;) stretch.push_back(good[k]);
    for (std::size_t k = last + 1; stretch.empty() && k < good.size() && !rec.frames[good[k]].contact; ++k)
      stretch.push_back(good[k]);
    if (!stretch.empty()) {
      // Mean of the stretch's shapes in their own whisker frames (a free whisker keeps its shape; one frame
      // alone carries the full pixel noise), placed at the pose of the free frame nearest the period.
      const ReconstructedFrame& src = rec.frames[stretch.front()];
      std::vector<Eigen::Vector3d> mean_B(src.shape_W.size(), Eigen::Vector3d::Zero());
      for (std::size_t i : stretch) {
        const ReconstructedFrame& fr = rec.frames[i];
        const Placement X(Pose{fr.base_W, fr.theta, fr.phi, fr.zeta});
        for (std::size_t k = 0; k < mean_B.size(); ++k) mean_B[k] += X.R_WB.transpose() * (fr.shape_W[k] - fr.base_W);
      }
      const Placement X_src(Pose{src.base_W, src.theta, src.phi, src.zeta});
      for (const auto& p_B : mean_B) u.shape_W.push_back(src.base_W + X_src.R_WB * (p_B / double(stretch.size())));
      u.source_frame = src.frame;
      u.frames_averaged = stretch.size();
    }
    rec.undeflected.push_back(std::move(u));
  }
  return rec;
}

trial::Trial to_trial(const Reconstruction& rec, const ReconstructOptions& o, const trial::TrialMaterial& material,
                      const std::string& source) {
  trial::Trial t;
  t.source = source;
  t.meta.material = material;
  t.meta.edges = o.edges;
  t.meta.frame_rate = o.frame_rate;
  bool any_shape = false;
  for (const auto& f : rec.frames) {
    t.time.push_back(double(f.frame) / o.frame_rate);
    t.base_W.push_back(f.base_W);
    t.theta.push_back(f.theta);
    t.phi.push_back(f.phi);
    t.zeta.push_back(f.zeta);
    t.contact.push_back(f.ok() && f.contact ? 1 : 0);
    t.contact_W.push_back(f.ok() && f.contact ? f.contact_W : nan3);
    t.shape_W.push_back(f.shape_W);
    any_shape = any_shape || !f.shape_W.empty();
    t.reconstructed.push_back(f.ok() ? 1 : 0);
    t.reprojection_px.push_back(f.reprojection_px);
    t.likelihood.push_back(f.likelihood);
  }
  if (!any_shape) t.shape_W.clear();
  for (const auto& u : rec.undeflected)
    if (!u.shape_W.empty()) {
      t.meta.rest_shape = u.shape_W;
      break;
    }
  if (t.meta.rest_shape.empty())  // no contact period: the first free frame's shape
    for (const auto& f : rec.frames)
      if (f.ok()) {
        t.meta.rest_shape = f.shape_W;
        break;
      }
  return t;
}

}  // namespace vibrissa::recon
