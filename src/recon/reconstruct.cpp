#include "vibrissa/recon/reconstruct.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <optional>
#include <stdexcept>

#include <Eigen/Dense>

#include "curve_fit.hpp"
#include "curve_reprojection.hpp"
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
  std::vector<std::size_t> index;  ///< of each usable point in the track frame
  std::vector<Eigen::Vector2d> px, ideal;
  std::vector<double> likelihood;
  std::vector<double> arc;  ///< cumulative ideal-pixel arc length, normalised to [0, 1]
};

ViewPoints usable_points(const TrackFrame& f, const Camera& cam, double min_likelihood) {
  ViewPoints v;
  for (std::size_t k = 0; k < f.points_px.size(); ++k) {
    if (!(f.likelihood[k] >= min_likelihood) || !f.points_px[k].allFinite()) continue;
    v.index.push_back(k);
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

/// Where the epipolar line `l` (unit normal, ideal pixels) crosses the view's curve extended beyond its base
/// (`at_base`) or tip, near the straight extension's parameter `t_line` (in units of the end segment): the
/// measured pixel there, or nullopt when the line misses the extension beyond the end. The extension is the
/// parabola in chord length through the end point fitted by least squares to the next seven (weighted by
/// likelihood), not the one through the last three: that one amplified pixel noise 4.4x one spacing out and
/// 14x at 2.5 spacings (Lagrange weights 3, -3, 1 and 7.875, -11.25, 4.375); the fit, 1.6x and 2.95x on
/// equally spaced points (the norm of the extrapolation weights). The matching reaches 1.5 spacings out.
std::optional<Eigen::Vector2d> end_parabola(const ViewPoints& v, const Eigen::Vector3d& l, bool at_base,
                                            double t_line) {
  constexpr std::size_t end_fit_points = 8;
  const std::size_t n = v.ideal.size();
  if (n < 3) return std::nullopt;
  const std::size_t m = std::min(end_fit_points, n);
  // sigma: chord length from the end point inward (> 0 inside, < 0 beyond the end).
  std::vector<std::size_t> k(m);
  std::vector<double> sigma(m, 0.0);
  for (std::size_t j = 0; j < m; ++j) {
    k[j] = at_base ? j : n - 1 - j;
    if (j > 0) sigma[j] = sigma[j - 1] + (v.ideal[k[j]] - v.ideal[k[j - 1]]).norm();
  }
  const double seg = sigma[1];
  if (!(seg > 0.0)) return std::nullopt;
  const double sigma_line = at_base ? t_line * seg : -(t_line - 1.0) * seg;
  // Weighted least squares for x(sigma) = p_end + c1 sigma + c2 sigma^2 (through the end point itself, so exact
  // views extend exactly), measured and ideal pixels alike; sigma in units of the end segment.
  Eigen::MatrixXd A(Eigen::Index(m - 1), 2), Y(Eigen::Index(m - 1), 4);
  Eigen::Matrix<double, 1, 4> end;
  end << v.ideal[k[0]].transpose(), v.px[k[0]].transpose();
  for (std::size_t j = 1; j < m; ++j) {
    const double w = std::sqrt(std::max(v.likelihood[k[j]], 1e-6)), x = sigma[j] / seg;
    A.row(Eigen::Index(j - 1)) << w * x, w * x * x;
    Eigen::Matrix<double, 1, 4> y;
    y << v.ideal[k[j]].transpose(), v.px[k[j]].transpose();
    Y.row(Eigen::Index(j - 1)) = w * (y - end);
  }
  Eigen::MatrixXd C(3, 4);  // rows: p_end, c1, c2
  C.row(0) = end;
  C.bottomRows<2>() = A.colPivHouseholderQr().solve(Y);
  if (!C.allFinite()) return std::nullopt;
  // l . [x(sigma); 1] = 0: a x^2 + b x + c with x = sigma / seg.
  const double a = l.head<2>().dot(C.block<1, 2>(2, 0).transpose());
  const double b = l.head<2>().dot(C.block<1, 2>(1, 0).transpose());
  const double c = l.head<2>().dot(C.block<1, 2>(0, 0).transpose()) + l.z();
  const double x_line = sigma_line / seg;
  double x = 0.0;
  if (std::abs(a) <= 1e-12 * (std::abs(b) + std::abs(c))) {
    if (b == 0.0) return std::nullopt;
    x = -c / b;
  } else {
    const double disc = b * b - 4.0 * a * c;
    if (disc < 0.0) return std::nullopt;
    const double r1 = (-b + std::sqrt(disc)) / (2.0 * a), r2 = (-b - std::sqrt(disc)) / (2.0 * a);
    x = std::abs(r1 - x_line) < std::abs(r2 - x_line) ? r1 : r2;
  }
  if (x > 0.0) return std::nullopt;  // not beyond the end
  const Eigen::Vector3d basis(1.0, x, x * x);
  return Eigen::Vector2d((basis.transpose() * C.rightCols<2>()).transpose());
}

/// For each point of `own`, the intersection of its epipolar line (F * x_own) with the `other` polyline
/// nearest the same relative arc length (gated), then the longest run monotonic in the other view's arc
/// length. Beyond its ends, `other` is extended by up to `end_extension` tracked spacings along the parabola
/// through its three end points: a base (or tip) point lost in the other view is then still matched.
std::vector<Match> match_views(const ViewPoints& own, const ViewPoints& other, const Eigen::Matrix3d& F) {
  constexpr double min_sine = 0.05;  // epipolar line nearly tangent to the curve: position undetermined
  constexpr double arc_gate = 0.35;  // relative arc lengths of the two views differ by foreshortening
  // [segments]: one lost end point. Two (2.5 spacings) cost 3.3x the base error of intact frames at 0.5 px
  // (tests/recon/input_checks_test.cpp); such a frame's curve now starts one spacing out and is flagged.
  constexpr double end_extension = 1.5;
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
      if (t < 0.0 || t > 1.0) {
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
    std::array<Eigen::Vector2d, 2> px;  ///< the pixels it was triangulated from (top, front)
    double likelihood;
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
      found.push_back({arc, t.p_W, {top_px, front_px}, std::sqrt(own.likelihood[m.own] * m.other_likelihood)});
      if (from_top) {
        first_arc = std::min(first_arc, arc);
        last_arc = std::max(last_arc, arc);
      }
    }
  }
  std::stable_sort(found.begin(), found.end(), [](const Point3& x, const Point3& y) { return x.arc < y.arc; });
  if (found.size() < std::size_t(o.min_points)) return f;
  const std::array<const Camera*, 2> cams{&top_cam, &front_cam};
  const std::array<const ViewPoints*, 2> views{&a, &b};
  // Fit, then drop the triangulated points whose pixels lie farther than max(outlier_px, 3 median) from the
  // fitted curve projected into their views, and fit again. (A wild point paired with its epipolar partner
  // reprojects exactly; only its distance to the curve the other points define shows it.)
  std::vector<bool> use(found.size(), true);
  std::optional<FittedCurve> curve;
  std::size_t used = 0;
  for (int pass = 0; pass < 2; ++pass) {
    std::vector<Eigen::Vector3d> pts;
    std::vector<double> weights;
    for (std::size_t i = 0; i < found.size(); ++i)
      if (use[i]) {
        pts.push_back(found[i].p_W);
        weights.push_back(found[i].likelihood);
      }
    used = pts.size();
    if (used < std::size_t(o.min_points)) return f;
    curve = fit_curve(pts, weights, std::min(o.fit_segments, int(used) - 4), o.nodes);
    if (!curve) return f;
    if (pass == 1) break;
    std::array<std::vector<Eigen::Vector2d>, 2> curve_px;
    for (std::size_t v = 0; v < 2; ++v) curve_px[v] = project_curve(curve->dense, *cams[v]);
    std::vector<double> err(found.size());
    for (std::size_t i = 0; i < found.size(); ++i)
      err[i] = std::max(distance_to_curve(curve_px[0], found[i].px[0]), distance_to_curve(curve_px[1], found[i].px[1]));
    const double gate = std::max(o.outlier_px, 3.0 * median_of(err));
    bool dropped = false;
    for (std::size_t i = 0; i < found.size(); ++i)
      if (!(err[i] <= gate)) {
        use[i] = false;
        dropped = true;
      }
    if (!dropped) break;
  }
  f.points_used = used;
  // The reprojection error: each tracked point's distance to the final curve projected into its view.
  std::vector<double> all;
  std::array<double, 2> base_gap{0.0, 0.0};
  f.point_reprojection_px.resize(2);
  double sum_like = 0.0;
  std::size_t n_like = 0;
  for (std::size_t v = 0; v < 2; ++v) {
    const std::vector<Eigen::Vector2d> curve_px = project_curve(curve->dense, *cams[v]);
    const TrackFrame& track = v == 0 ? *top : *front;
    f.point_reprojection_px[v].assign(track.points_px.size(), nan_v);
    for (std::size_t k = 0; k < views[v]->px.size(); ++k) {
      const double d = distance_to_curve(curve_px, views[v]->px[k]);
      f.point_reprojection_px[v][views[v]->index[k]] = d;
      all.push_back(d);
      sum_like += views[v]->likelihood[k];
      ++n_like;
    }
    // A view's tracked base (point 0) beyond the start of the curve: its partner in the other view was lost
    // farther out than the end extension reaches, and the curve would start a tracked spacing out.
    if (!views[v]->index.empty() && views[v]->index.front() == 0) base_gap[v] = distance_to_curve(curve_px, views[v]->px.front());
    // The base (point 0, when this view tracked it) is where the curve starts, not merely a point near it:
    // its distance to the projected start of the curve. Along their length two views' curves can always be
    // matched by epipolar lines, so a calibration error shows only where they end: the two views' base points
    // do not lie on each other's epipolar lines and the curve, which reaches the farther of them, overshoots
    // the other view's base. (The tip is left out: trackers often end the two views' tracks at different
    // points of the whisker.)
    if (!views[v]->index.empty() && views[v]->index.front() == 0) {
      const double d = (curve_px.front() - views[v]->px.front()).norm();
      f.point_reprojection_px[v][0] = d;
      all[all.size() - views[v]->px.size()] = d;  // point 0's entry of this view
    }
  }
  const double gate = std::max(o.outlier_px, 3.0 * median_of(all));
  double sum2 = 0.0;
  std::size_t n_in = 0;
  for (std::size_t v = 0; v < 2; ++v) {
    double view_sum2 = 0.0;
    std::size_t view_n = 0;
    for (double d : f.point_reprojection_px[v]) {
      if (!(d <= gate)) {
        f.outliers += std::isnan(d) ? 0 : 1;
        continue;
      }
      view_sum2 += d * d;
      ++view_n;
    }
    f.view_reprojection_px.push_back(view_n ? std::sqrt(view_sum2 / double(view_n)) : nan_v);
    sum2 += view_sum2;
    n_in += view_n;
  }
  f.reprojection_px = n_in ? std::sqrt(sum2 / double(n_in)) : nan_v;
  f.likelihood = n_like ? sum_like / double(n_like) : nan_v;
  if (std::max(base_gap[0], base_gap[1]) > gate) {
    f.status = FrameStatus::base_not_reached;
    return f;
  }
  if (!(f.reprojection_px <= o.max_reprojection_px)) {
    f.status = FrameStatus::reprojection;
    return f;
  }
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
  const std::size_t used = f.points_used, outliers = f.outliers;
  const std::int64_t frame = f.frame;
  std::vector<double> view_rep = std::move(f.view_reprojection_px);
  std::vector<std::vector<double>> point_rep = std::move(f.point_reprojection_px);
  f = ReconstructedFrame();
  f.view_reprojection_px = std::move(view_rep);
  f.point_reprojection_px = std::move(point_rep);
  f.outliers = outliers;
  f.frame = frame;
  f.status = status;
  f.reprojection_px = rep;
  f.likelihood = like;
  f.points_used = used;
}

/// Symmetric epipolar distance [ideal px] of the base points (point 0 of both tracks) of one frame, NaN if
/// either is untracked.
double base_epipolar_distance(const TrackFrame& top, const Camera& top_cam, const TrackFrame& front,
                              const Camera& front_cam, const Eigen::Matrix3d& F, double min_likelihood) {
  if (top.points_px.empty() || front.points_px.empty() || !(top.likelihood[0] >= min_likelihood) ||
      !(front.likelihood[0] >= min_likelihood) || !top.points_px[0].allFinite() || !front.points_px[0].allFinite())
    return nan_v;
  const Eigen::Vector3d x1 = top_cam.undistort(top.points_px[0]).homogeneous();
  const Eigen::Vector3d x2 = front_cam.undistort(front.points_px[0]).homogeneous();
  const Eigen::Vector3d l2 = F * x1, l1 = F.transpose() * x2;  // lines in the front and top images
  return 0.5 * (std::abs(l2.dot(x2)) / l2.head<2>().norm() + std::abs(l1.dot(x1)) / l1.head<2>().norm());
}

double median_base_epipolar(const Tracks2D& top, const Camera& top_cam, const Tracks2D& front,
                            const Camera& front_cam, double min_likelihood) {
  const Eigen::Matrix3d F = fundamental_matrix(top_cam, front_cam);
  std::vector<double> d;
  for (const auto& t : top.frames)
    if (const TrackFrame* f = front.find(t.frame)) {
      const double e = base_epipolar_distance(t, top_cam, *f, front_cam, F, min_likelihood);
      if (std::isfinite(e)) d.push_back(e);
    }
  return d.empty() ? nan_v : median_of(d);
}

std::string fixed(double v, int digits = 1) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", digits, v);
  return buf;
}

/// Inconsistent inputs (ReconstructOptions: max_unpaired, max_epipolar_px, min_yield), each with its likely cause.
void check_inputs(Reconstruction& rec, const Tracks2D& top, const Camera& top_cam, const Tracks2D& front,
                  const Camera& front_cam, const ReconstructOptions& o) {
  std::int64_t top_lo = 0, top_hi = -1, front_lo = 0, front_hi = -1;
  std::size_t n_top = 0, n_front = 0;
  for (const auto& f : top.frames) {
    top_lo = n_top ? std::min(top_lo, f.frame) : f.frame;
    top_hi = n_top++ ? std::max(top_hi, f.frame) : f.frame;
  }
  for (const auto& f : front.frames) {
    front_lo = n_front ? std::min(front_lo, f.frame) : f.frame;
    front_hi = n_front++ ? std::max(front_hi, f.frame) : f.frame;
  }
  for (const auto& f : top.frames) rec.frames_in_both += front.find(f.frame) != nullptr;
  // With an explicit offset the views' ranges differ by design: only gaps inside their overlap count.
  std::size_t considered = rec.frames.size();
  if (o.front_frame_offset != 0) {
    const std::int64_t lo = std::max(top_lo, front_lo), hi = std::min(top_hi, front_hi);
    considered = std::size_t(std::count_if(rec.frames.begin(), rec.frames.end(),
                                           [&](const ReconstructedFrame& f) { return f.frame >= lo && f.frame <= hi; }));
  }
  rec.base_epipolar_px = median_base_epipolar(top, top_cam, front, front_cam, o.min_likelihood);
  rec.swapped_epipolar_px = median_base_epipolar(front, top_cam, top, front_cam, o.min_likelihood);
  const std::size_t all = considered;
  const std::size_t unpaired = all - std::min(all, rec.frames_in_both);
  // Views whose frame ranges differ (one file starts or ends later) are out of step, however few the frames:
  // a frame or two lost at either end is tolerated.
  const std::int64_t range_gap = std::abs(top_lo - front_lo) + std::abs(top_hi - front_hi);
  const bool ranges_differ = n_top > 0 && n_front > 0 && o.front_frame_offset == 0 && o.max_unpaired < 1.0 &&
                             double(range_gap) > std::max(2.0, 0.01 * double(rec.frames.size()));
  if (all > 0 && ((unpaired > 2 && double(unpaired) > o.max_unpaired * double(all)) || ranges_differ)) {
    std::string msg = std::to_string(unpaired) + " of " + std::to_string(all) +
                      " frames are tracked in one view only (top: frames " + std::to_string(top_lo) + " to " +
                      std::to_string(top_hi) + ", " + std::to_string(n_top) + " frames; front: frames " +
                      std::to_string(front_lo) + " to " + std::to_string(front_hi) + ", " + std::to_string(n_front) +
                      " frames)";
    if (ranges_differ)
      msg += ": the views are out of step or from different videos? If the front video starts later, give the "
             "offset (--front-frame-offset N: front frame f is top frame f + N); --max-unpaired 1 accepts it";
    else
      msg += "; --max-unpaired " + fixed(double(unpaired) / double(all), 2) + " accepts it";
    rec.problems.push_back(msg);
  }
  // "Far above the noise": the limit is max_epipolar_px or 4x the median reprojection error (about the noise).
  std::vector<double> reprojection;
  for (const auto& f : rec.frames)
    if (std::isfinite(f.reprojection_px)) reprojection.push_back(f.reprojection_px);
  const double limit = std::max(o.max_epipolar_px, reprojection.empty() ? 0.0 : 4.0 * median_of(reprojection));
  const bool disagree = std::isfinite(rec.base_epipolar_px) && rec.base_epipolar_px > limit;
  if (disagree) {
    std::string msg = "the views do not agree with the calibration: the base points lie a median " +
                      fixed(rec.base_epipolar_px) + " px from each other's epipolar lines (about the pixel noise " +
                      "when they agree; limit " + fixed(limit) + " px: --max-epipolar-px or 4x the median " +
                      "reprojection error)";
    if (std::isfinite(rec.swapped_epipolar_px) && rec.swapped_epipolar_px <= limit)
      msg += ": the views are swapped (with --top and --front exchanged, " + fixed(rec.swapped_epipolar_px) + " px)";
    else
      msg += ": views swapped or given the wrong camera names, a wrong calibration, or views out of step";
    rec.problems.push_back(msg);
  }
  const std::size_t ok = rec.count(FrameStatus::ok);
  if (rec.frames_in_both > 0 && double(ok) < o.min_yield * double(rec.frames_in_both)) {
    std::string msg = "only " + std::to_string(ok) + " of the " + std::to_string(rec.frames_in_both) +
                      " frames tracked in both views were reconstructed (--min-yield " + fixed(o.min_yield, 2) + ")";
    const std::size_t few = rec.count(FrameStatus::too_few_points), rep = rec.count(FrameStatus::reprojection);
    if (rep >= few && rep > 0)
      msg += "; most failed on the reprojection error (> --max-reprojection-px " + fixed(o.max_reprojection_px) +
             "): a wrong calibration, or views out of step";
    else if (few > 0)
      msg += "; most had too few matched points: views out of step, swapped, or a wrong calibration; or few "
             "points above --min-likelihood";
    rec.problems.push_back(msg);
  }
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
    case FrameStatus::base_not_reached: return "base_not_reached";
  }
  return "unknown";
}

Reconstruction::Reconstruction() : base_epipolar_px(nan_v), swapped_epipolar_px(nan_v) {}

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
  require(min_yield >= 0.0 && min_yield <= 1.0, "min_yield", min_yield, "in [0, 1]");
  require(max_unpaired >= 0.0 && max_unpaired <= 1.0, "max_unpaired", max_unpaired, "in [0, 1]");
  require(max_epipolar_px > 0.0, "max_epipolar_px", max_epipolar_px, "> 0");
  for (std::size_t k = 0; k < edges.size(); ++k)
    if (!edges[k].point.allFinite() || !edges[k].direction.allFinite() || edges[k].direction.norm() == 0.0)
      throw std::invalid_argument("edges[" + std::to_string(k) + "] needs a finite point and non-zero direction");
}

Reconstruction reconstruct(const Tracks2D& top, const Camera& top_camera, const Tracks2D& front_tracks,
                           const Camera& front_camera, const ReconstructOptions& o, const RunControl& control) {
  o.validate();
  Tracks2D shifted;
  if (o.front_frame_offset != 0) {
    shifted = front_tracks;
    for (auto& f : shifted.frames) f.frame += o.front_frame_offset;
  }
  const Tracks2D& front = o.front_frame_offset != 0 ? shifted : front_tracks;
  std::vector<std::int64_t> frames;
  for (const auto* t : {&top, &front})
    for (const auto& f : t->frames) frames.push_back(f.frame);
  std::sort(frames.begin(), frames.end());
  frames.erase(std::unique(frames.begin(), frames.end()), frames.end());
  const Eigen::Matrix3d F = fundamental_matrix(top_camera, front_camera);
  Reconstruction rec;
  rec.view_names = {"top", "front"};
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
  check_inputs(rec, top, top_camera, front, front_camera, o);
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
