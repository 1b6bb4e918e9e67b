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
  Eigen::Vector2d other_tangent;  ///< unit direction of the other view's polyline there (ideal pixels)
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
      best = Match{i, px, own.arc[i], arc, other.likelihood[j] + tl * (other.likelihood[j + 1] - other.likelihood[j]),
                   (other.ideal[j + 1] - other.ideal[j]) / seg};
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

/// A point seen at `ideal[0]` by the reference camera and on the curves of the other views near `ideal[k]`
/// (k >= 1), whose directions there are `tangent[k]`: the least-squares point of the reference pixel (2D) and of
/// the distances across each other curve (1D), by Gauss-Newton from `start`. Where a point lies along another
/// view's curve is only known through the epipolar intersection, which carries the reference view's noise and
/// is ill-conditioned where the epipolar line is nearly tangent to the curve; with one other view the solution
/// is the pair's triangulation (the intersection lies on the epipolar line), with more it uses only what each
/// view measures.
Eigen::Vector3d refine_on_curves(const std::vector<const Camera*>& cams, const std::vector<Eigen::Vector2d>& ideal,
                                 const std::vector<Eigen::Vector2d>& tangent, Eigen::Vector3d X) {
  for (int it = 0; it < 10; ++it) {
    Eigen::Matrix3d JtJ = Eigen::Matrix3d::Zero();
    Eigen::Vector3d Jtr = Eigen::Vector3d::Zero();
    for (std::size_t k = 0; k < cams.size(); ++k) {
      const Eigen::Matrix<double, 3, 4>& P = cams[k]->P;
      const Eigen::Vector3d h = P * X.homogeneous();
      const Eigen::Vector2d x = h.head<2>() / h.z();
      Eigen::Matrix<double, 2, 3> J;
      J.row(0) = (P.block<1, 3>(0, 0) - x.x() * P.block<1, 3>(2, 0)) / h.z();
      J.row(1) = (P.block<1, 3>(1, 0) - x.y() * P.block<1, 3>(2, 0)) / h.z();
      const Eigen::Vector2d r = x - ideal[k];
      if (k == 0) {
        JtJ += J.transpose() * J;
        Jtr += J.transpose() * r;
      } else {
        const Eigen::Vector2d n(-tangent[k].y(), tangent[k].x());
        const Eigen::RowVector3d Jn = n.transpose() * J;
        JtJ += Jn.transpose() * Jn;
        Jtr += Jn.transpose() * n.dot(r);
      }
    }
    const Eigen::Vector3d step = JtJ.ldlt().solve(-Jtr);
    if (!step.allFinite()) break;
    X += step;
    if (step.norm() <= 1e-15 * std::max(1.0, X.norm())) break;
  }
  return X;
}

/// Fundamental matrices of every ordered pair of views: x_j^T F[i][j] x_i = 0 (ideal pixels).
using PairMatrices = std::vector<std::vector<Eigen::Matrix3d>>;

ReconstructedFrame reconstruct_frame(std::int64_t frame, const std::vector<const TrackFrame*>& tracks,
                                     const std::vector<View>& views, const PairMatrices& F,
                                     const ReconstructOptions& o) {
  ReconstructedFrame f;
  f.frame = frame;
  const std::size_t n_views = views.size();
  std::vector<ViewPoints> pts(n_views);
  std::vector<std::size_t> usable;  // views tracked here with at least two usable points
  std::size_t tracked = 0;
  for (std::size_t v = 0; v < n_views; ++v) {
    if (!tracks[v]) continue;
    ++tracked;
    pts[v] = usable_points(*tracks[v], views[v].camera, o.min_likelihood);
    if (pts[v].px.size() >= 2) usable.push_back(v);
  }
  if (tracked < 2) return f;
  f.status = FrameStatus::too_few_points;
  f.views_used = usable.size();
  if (usable.size() < 2) return f;
  // The reference view is the first usable one. Each of its points is matched to every other view's polyline
  // and triangulated from all the views that matched it (N-view DLT + Gauss-Newton: the least-squares point of
  // every ray, not a pair). Then each other view's points are matched back to the reference polyline, so that
  // a point the reference lost (e.g. the base) is still reconstructed from that view.
  const std::size_t r = usable.front();
  struct Point3 {
    double arc;  ///< mean relative arc length over its views (orders the points base to tip)
    Eigen::Vector3d p_W;
    std::vector<std::pair<std::size_t, Eigen::Vector2d>> px;  ///< (view, pixel) it was triangulated from
    double likelihood;
    std::size_t measured = 0;  ///< which entry of px a view tracked; the others are epipolar intersections
  };
  std::vector<Point3> found;
  std::vector<std::vector<std::pair<std::size_t, Match>>> partners(pts[r].px.size());
  for (std::size_t u = 1; u < usable.size(); ++u)
    for (const Match& m : match_views(pts[r], pts[usable[u]], F[r][usable[u]])) partners[m.own].push_back({usable[u], m});
  double first_arc = std::numeric_limits<double>::infinity(), last_arc = -first_arc;  // of the reference matches
  for (std::size_t i = 0; i < partners.size(); ++i) {
    if (partners[i].empty()) continue;
    std::vector<const Camera*> cams{&views[r].camera};
    std::vector<Eigen::Vector2d> pix{pts[r].px[i]};
    Point3 p{pts[r].arc[i], Eigen::Vector3d::Zero(), {{r, pts[r].px[i]}}, std::log(std::max(pts[r].likelihood[i], 1e-300))};
    for (const auto& [v, m] : partners[i]) {
      cams.push_back(&views[v].camera);
      pix.push_back(m.other_px);
      p.px.push_back({v, m.other_px});
      p.arc += m.other_arc;
      p.likelihood += std::log(std::max(m.other_likelihood, 1e-300));
    }
    const double k = double(p.px.size());
    p.arc /= k;
    p.likelihood = std::exp(p.likelihood / k);  // geometric mean (two views: sqrt of the product)
    const Triangulated t = triangulate(cams, pix);
    if (!t.ok) continue;
    p.p_W = t.p_W;
    if (partners[i].size() >= 2) {
      std::vector<Eigen::Vector2d> ideal{pts[r].ideal[i]}, tangent{Eigen::Vector2d::Zero()};
      for (const auto& [v, m] : partners[i]) {
        ideal.push_back(views[v].camera.undistort(m.other_px));
        tangent.push_back(m.other_tangent);
      }
      const Eigen::Vector3d X = refine_on_curves(cams, ideal, tangent, t.p_W);
      if (X.allFinite()) p.p_W = X;
    }
    first_arc = std::min(first_arc, p.arc);
    last_arc = std::max(last_arc, p.arc);
    found.push_back(std::move(p));
  }
  // A point of another view counts as beyond an end of the reference matches only by more than half of that
  // view's spacing (relative arc length): a point the reference lost is a whole spacing out, while the views'
  // own end points differ by pixel noise only, and keeping those of them that happen to fall outside
  // lengthened the curve at both ends (a base ~0.6 px behind the follicle at 0.5 px noise, and a systematic
  // angle bias). Inside, they would repeat the same stretch with pixel errors shared with the reference
  // matches (correlated residuals make the fit follow the noise).
  for (std::size_t u = 1; u < usable.size(); ++u) {
    const std::size_t v = usable[u];
    const double beyond_margin = 0.5 / double(pts[v].px.size() - 1);
    for (const Match& m : match_views(pts[v], pts[r], F[v][r])) {
      const double arc = 0.5 * (m.own_arc + m.other_arc);
      if (arc >= first_arc - beyond_margin && arc <= last_arc + beyond_margin) continue;
      const Triangulated t = triangulate({&views[r].camera, &views[v].camera}, {m.other_px, pts[v].px[m.own]});
      if (!t.ok) continue;
      found.push_back({arc, t.p_W, {{r, m.other_px}, {v, pts[v].px[m.own]}},
                       std::sqrt(pts[v].likelihood[m.own] * m.other_likelihood), 1});
    }
  }
  std::stable_sort(found.begin(), found.end(), [](const Point3& x, const Point3& y) { return x.arc < y.arc; });
  if (found.size() < std::size_t(o.min_points)) return f;
  // Fit, then drop the triangulated points whose pixels lie farther than max(outlier_px, 3 median) from the
  // fitted curve projected into their views, and fit again. (A wild point paired with its epipolar partner
  // reprojects exactly; only its distance to the curve the other points define shows it.)
  std::vector<bool> use(found.size(), true);
  std::optional<FittedCurve> curve;
  std::size_t used = 0;
  for (int pass = 0; pass < 2; ++pass) {
    std::vector<Eigen::Vector3d> points;
    std::vector<double> weights;
    for (std::size_t i = 0; i < found.size(); ++i)
      if (use[i]) {
        points.push_back(found[i].p_W);
        weights.push_back(found[i].likelihood);
      }
    used = points.size();
    if (used < std::size_t(o.min_points)) return f;
    curve = fit_curve(points, weights, std::min(o.fit_segments, int(used) - 4), o.nodes);
    if (!curve) return f;
    if (pass == 1) break;
    std::vector<std::vector<Eigen::Vector2d>> curve_px(n_views);
    for (std::size_t v : usable) curve_px[v] = project_curve(curve->dense, views[v].camera);
    std::vector<double> err(found.size(), 0.0);
    // An intersection's position along its curve is not measured: at an end, where the epipolar line may meet
    // the curve's extension at a grazing angle, it can lie pixels beyond the end although the point is right.
    for (std::size_t i = 0; i < found.size(); ++i)
      for (std::size_t k = 0; k < found[i].px.size(); ++k) {
        const auto& [v, px] = found[i].px[k];
        err[i] = std::max(err[i], k == found[i].measured ? distance_to_curve(curve_px[v], px)
                                                         : distance_across_curve(curve_px[v], px));
      }
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
  std::vector<double> base_gap(n_views, 0.0);
  f.point_reprojection_px.resize(n_views);
  double sum_like = 0.0;
  std::size_t n_like = 0;
  for (std::size_t v = 0; v < n_views; ++v) {
    if (!tracks[v]) continue;
    const ViewPoints& view = pts[v];
    const std::vector<Eigen::Vector2d> curve_px = project_curve(curve->dense, views[v].camera);
    f.point_reprojection_px[v].assign(tracks[v]->points_px.size(), nan_v);
    for (std::size_t k = 0; k < view.px.size(); ++k) {
      const double d = distance_to_curve(curve_px, view.px[k]);
      f.point_reprojection_px[v][view.index[k]] = d;
      all.push_back(d);
      sum_like += view.likelihood[k];
      ++n_like;
    }
    // A view's tracked base (point 0) beyond the start of the curve: its partner in the other views was lost
    // farther out than the end extension reaches, and the curve would start a tracked spacing out.
    if (!view.index.empty() && view.index.front() == 0) base_gap[v] = distance_to_curve(curve_px, view.px.front());
    // The base (point 0, when this view tracked it) is where the curve starts, not merely a point near it:
    // its distance to the projected start of the curve. Along their length two views' curves can always be
    // matched by epipolar lines, so with two views a calibration error shows only where they end: the base
    // points do not lie on each other's epipolar lines and the curve, which reaches the farther of them,
    // overshoots the other view's base. (The tip is left out: trackers often end the views' tracks at
    // different points of the whisker.) A third view sees such errors along the whole curve.
    if (!view.index.empty() && view.index.front() == 0) {
      const double d = (curve_px.front() - view.px.front()).norm();
      f.point_reprojection_px[v][0] = d;
      all[all.size() - view.px.size()] = d;  // point 0's entry of this view
    }
  }
  const double gate = std::max(o.outlier_px, 3.0 * median_of(all));
  double sum2 = 0.0;
  std::size_t n_in = 0;
  for (std::size_t v = 0; v < n_views; ++v) {
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
  if (*std::max_element(base_gap.begin(), base_gap.end()) > gate) {
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
  const std::size_t used = f.points_used, outliers = f.outliers, views_used = f.views_used;
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
  f.views_used = views_used;
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

/// The trackers' pixel noise [px], from the tracks alone (no calibration): the median over every view and
/// frame of the third differences of consecutive tracked points across the local chord, scaled to a standard
/// deviation (a third difference of independent noise of deviation sigma per coordinate has deviation
/// sqrt(20) sigma; the median of its absolute value is 0.6745 of that). A smooth whisker sampled at a few dozen
/// points has third differences far below a pixel. NaN without four consecutive points.
double track_noise_px(const std::vector<View>& views, double min_likelihood) {
  std::vector<double> d;
  for (const auto& v : views)
    for (const auto& f : v.tracks.frames)
      for (std::size_t k = 0; k + 3 < f.points_px.size(); ++k) {
        bool ok = true;
        for (std::size_t j = k; j < k + 4; ++j) ok = ok && f.likelihood[j] >= min_likelihood && f.points_px[j].allFinite();
        if (!ok) continue;
        const Eigen::Vector2d chord = f.points_px[k + 3] - f.points_px[k];
        if (!(chord.norm() > 0.0)) continue;
        const Eigen::Vector2d third = f.points_px[k + 3] - 3.0 * f.points_px[k + 2] + 3.0 * f.points_px[k + 1] - f.points_px[k];
        d.push_back(std::abs(third.x() * chord.y() - third.y() * chord.x()) / chord.norm());
      }
  return d.empty() ? nan_v : median_of(d) / (0.6745 * std::sqrt(20.0));
}

/// Inconsistent inputs (ReconstructOptions: max_unpaired, max_epipolar_px, min_yield), each with its likely cause
/// and naming the view. `views` hold the tracks with their frame offsets applied.
void check_inputs(Reconstruction& rec, const std::vector<View>& views, const std::vector<std::int64_t>& offsets,
                  const ReconstructOptions& o) {
  const std::size_t n_views = views.size();
  struct Range {
    std::int64_t lo = 0, hi = -1;
    std::size_t n = 0;
  };
  std::vector<Range> range(n_views);
  for (std::size_t v = 0; v < n_views; ++v)
    for (const auto& f : views[v].tracks.frames) {
      range[v].lo = range[v].n ? std::min(range[v].lo, f.frame) : f.frame;
      range[v].hi = range[v].n ? std::max(range[v].hi, f.frame) : f.frame;
      ++range[v].n;
    }
  for (const auto& f : rec.frames) {
    std::size_t seen = 0;
    for (const auto& v : views) seen += v.tracks.find(f.frame) != nullptr;
    rec.frames_in_both += seen >= 2;
  }
  // Out of step: each view against the first (the reference), over the frames either of the two tracks.
  const std::string& ref = rec.view_names[0];
  for (std::size_t v = 1; v < n_views; ++v) {
    const std::string& name = rec.view_names[v];
    const bool shifted = offsets[v] != offsets[0];
    // With an explicit offset the views' ranges differ by design: only gaps inside their overlap count.
    const std::int64_t lo = std::max(range[0].lo, range[v].lo), hi = std::min(range[0].hi, range[v].hi);
    std::size_t all = 0, unpaired = 0;
    for (const auto& f : rec.frames) {
      const bool a = views[0].tracks.find(f.frame) != nullptr, b = views[v].tracks.find(f.frame) != nullptr;
      if (!(a || b) || (shifted && (f.frame < lo || f.frame > hi))) continue;
      ++all;
      unpaired += a != b;
    }
    // Views whose frame ranges differ (one file starts or ends later) are out of step, however few the frames:
    // a frame or two lost at either end is tolerated.
    const std::int64_t range_gap = std::abs(range[0].lo - range[v].lo) + std::abs(range[0].hi - range[v].hi);
    const bool ranges_differ = range[0].n > 0 && range[v].n > 0 && !shifted && o.max_unpaired < 1.0 &&
                               double(range_gap) > std::max(2.0, 0.01 * double(all));
    if (all == 0 || !((unpaired > 2 && double(unpaired) > o.max_unpaired * double(all)) || ranges_differ)) continue;
    auto describe = [&](std::size_t w) {
      return rec.view_names[w] + ": frames " + std::to_string(range[w].lo) + " to " + std::to_string(range[w].hi) +
             ", " + std::to_string(range[w].n) + " frames";
    };
    std::string msg = std::to_string(unpaired) + " of " + std::to_string(all) +
                      " frames are tracked in one view only (" + describe(0) + "; " + describe(v) + ")";
    if (ranges_differ) {
      const std::string flag = name == "front" ? "--front-frame-offset N" : "--frame-offset " + name + "=N";
      msg += ": the views are out of step or from different videos? If the " + name + " video starts later, give the "
             "offset (" + flag + ": " + name + " frame f is " + ref + " frame f + N); --max-unpaired 1 accepts it";
    } else {
      msg += "; --max-unpaired " + fixed(double(unpaired) / double(all), 2) + " accepts it";
    }
    rec.problems.push_back(msg);
  }
  // Agreement with the calibration, per pair of views. "Far above the noise": the limit is max_epipolar_px or
  // 4x the median reprojection error (about the noise).
  auto pair_median = [&](std::size_t a, std::size_t b, std::size_t tracks_a, std::size_t tracks_b) {
    return median_base_epipolar(views[tracks_a].tracks, views[a].camera, views[tracks_b].tracks, views[b].camera,
                                o.min_likelihood);
  };
  std::vector<double> reprojection;
  for (const auto& f : rec.frames)
    if (std::isfinite(f.reprojection_px)) reprojection.push_back(f.reprojection_px);
  // With three or more views the reprojection error itself rises with a wrong calibration (the views' rays no
  // longer meet), so the noise is taken from the tracks' smoothness instead.
  rec.track_noise_px = track_noise_px(views, o.min_likelihood);
  const double median_reprojection = reprojection.empty() ? nan_v : median_of(reprojection);
  const double noise = n_views == 2 ? median_reprojection : rec.track_noise_px;
  const double limit = std::max(o.max_epipolar_px, std::isfinite(noise) ? 4.0 * noise : 0.0);
  const ViewPairCheck* worst = nullptr;
  std::vector<const ViewPairCheck*> failing;
  for (std::size_t a = 0; a < n_views; ++a)
    for (std::size_t b = a + 1; b < n_views; ++b) {
      ViewPairCheck c;
      c.a = a;
      c.b = b;
      c.base_epipolar_px = pair_median(a, b, a, b);
      c.swapped_epipolar_px = pair_median(a, b, b, a);
      rec.view_pairs.push_back(c);
    }
  for (const auto& c : rec.view_pairs) {
    if (std::isfinite(c.base_epipolar_px) && (!worst || c.base_epipolar_px > worst->base_epipolar_px)) worst = &c;
    if (std::isfinite(c.base_epipolar_px) && c.base_epipolar_px > limit) failing.push_back(&c);
  }
  if (worst) {
    rec.base_epipolar_px = worst->base_epipolar_px;
    rec.swapped_epipolar_px = worst->swapped_epipolar_px;
  }
  if (!failing.empty()) {
    const std::string limit_text = " (about the pixel noise when they agree; limit " + fixed(limit) +
                                   " px: --max-epipolar-px or 4x " +
                                   (n_views == 2 ? "the median reprojection error)" : "the tracks' pixel noise)");
    if (n_views == 2) {
      const ViewPairCheck& c = *failing.front();
      std::string msg = "the views do not agree with the calibration: the base points lie a median " +
                        fixed(c.base_epipolar_px) + " px from each other's epipolar lines" + limit_text;
      if (std::isfinite(c.swapped_epipolar_px) && c.swapped_epipolar_px <= limit)
        msg += ": the views are swapped (with the " + rec.view_names[0] + " and " + rec.view_names[1] +
               " tracks exchanged, " + fixed(c.swapped_epipolar_px) + " px)";
      else
        msg += ": views swapped or given the wrong camera names, a wrong calibration, or views out of step";
      rec.problems.push_back(msg);
    } else {
      // Which view: one whose every pair fails while some other pair agrees. Else an exchange of two views'
      // tracks after which every pair agrees. Else the failing pairs.
      std::string pairs_text;
      for (const ViewPairCheck* c : failing)
        pairs_text += std::string(pairs_text.empty() ? "" : ", ") + rec.view_names[c->a] + "-" + rec.view_names[c->b] +
                      " " + fixed(c->base_epipolar_px) + " px";
      std::optional<std::size_t> culprit;
      for (std::size_t v = 0; v < n_views && !culprit; ++v) {
        bool all_fail = true, other_agrees = false;
        for (const auto& c : rec.view_pairs) {
          const bool fails = std::find(failing.begin(), failing.end(), &c) != failing.end();
          if (c.a == v || c.b == v)
            all_fail = all_fail && fails;
          else
            other_agrees = other_agrees || (std::isfinite(c.base_epipolar_px) && !fails);
        }
        if (all_fail && other_agrees) culprit = v;
      }
      std::optional<std::pair<std::size_t, std::size_t>> swap;
      double swapped_worst = 0.0;
      for (std::size_t a = 0; a < n_views && !swap; ++a)
        for (std::size_t b = a + 1; b < n_views && !swap; ++b) {
          std::vector<std::size_t> t(n_views);
          for (std::size_t k = 0; k < n_views; ++k) t[k] = k;
          std::swap(t[a], t[b]);
          double w = 0.0;
          bool ok = true;
          for (std::size_t x = 0; x < n_views && ok; ++x)
            for (std::size_t y = x + 1; y < n_views && ok; ++y) {
              const double d = pair_median(x, y, t[x], t[y]);
              ok = std::isfinite(d) && d <= limit;
              w = std::max(w, d);
            }
          if (ok) {
            swap = std::make_pair(a, b);
            swapped_worst = w;
          }
        }
      std::string msg = "the views do not agree with the calibration: base points a median of " + pairs_text +
                        " from each other's epipolar lines" + limit_text;
      if (swap)
        msg += ": the views '" + rec.view_names[swap->first] + "' and '" + rec.view_names[swap->second] +
               "' are swapped (with their tracks exchanged every pair of views agrees, at most " +
               fixed(swapped_worst) + " px)";
      else if (culprit)
        msg += ": view '" + rec.view_names[*culprit] + "' disagrees with every other view while they agree with "
               "each other: its tracks are of another camera, its calibration is wrong, or its video is out of step";
      else
        msg += ": views swapped or given the wrong camera names, a wrong calibration, or views out of step";
      rec.problems.push_back(msg);
    }
  }
  // Per view, the median reprojection error over the frames with a curve. With three or more views it is about
  // the pixel noise when the calibration is right, and rises along the whole whisker when it is not.
  rec.view_reprojection_px_median.assign(n_views, nan_v);
  for (std::size_t v = 0; v < n_views; ++v) {
    std::vector<double> d;
    for (const auto& f : rec.frames)
      if (v < f.view_reprojection_px.size() && std::isfinite(f.view_reprojection_px[v])) d.push_back(f.view_reprojection_px[v]);
    if (!d.empty()) rec.view_reprojection_px_median[v] = median_of(d);
  }
  const double reprojection_limit = std::max(0.5 * o.max_epipolar_px, 2.0 * rec.track_noise_px);
  if (n_views >= 3 && std::isfinite(median_reprojection) && std::isfinite(rec.track_noise_px) &&
      median_reprojection > reprojection_limit) {
    std::string per_view;
    for (std::size_t v = 0; v < n_views; ++v)
      per_view += std::string(v ? ", " : "") + rec.view_names[v] + " " + fixed(rec.view_reprojection_px_median[v], 2);
    rec.problems.push_back("the views do not agree with the calibration: the median reprojection error, " +
                           fixed(median_reprojection, 2) + " px (per view: " + per_view + " px), is far above the " +
                           "tracks' pixel noise, " + fixed(rec.track_noise_px, 2) + " px (limit " +
                           fixed(reprojection_limit, 2) + " px: 2x the noise or half --max-epipolar-px): with three or "
                           "more views the rays of a wrong calibration do not meet; a camera moved or turned after "
                           "calibrating, a wrong focal length or distortion, or views out of step");
  }
  const std::size_t ok = rec.count(FrameStatus::ok);
  const std::string both = n_views == 2 ? "both views" : "at least two views";
  if (rec.frames_in_both > 0 && double(ok) < o.min_yield * double(rec.frames_in_both)) {
    std::string msg = "only " + std::to_string(ok) + " of the " + std::to_string(rec.frames_in_both) +
                      " frames tracked in " + both + " were reconstructed (--min-yield " + fixed(o.min_yield, 2) + ")";
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

Reconstruction::Reconstruction() : base_epipolar_px(nan_v), swapped_epipolar_px(nan_v), track_noise_px(nan_v) {}

ViewPairCheck::ViewPairCheck() : base_epipolar_px(nan_v), swapped_epipolar_px(nan_v) {}

std::int64_t ReconstructOptions::frame_offset(const std::string& view) const {
  const auto it = frame_offsets.find(view);
  if (it != frame_offsets.end()) return it->second;
  return view == "front" ? front_frame_offset : 0;
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
  require(min_yield >= 0.0 && min_yield <= 1.0, "min_yield", min_yield, "in [0, 1]");
  require(max_unpaired >= 0.0 && max_unpaired <= 1.0, "max_unpaired", max_unpaired, "in [0, 1]");
  require(max_epipolar_px > 0.0, "max_epipolar_px", max_epipolar_px, "> 0");
  if (front_frame_offset != 0 && frame_offsets.count("front"))
    throw std::invalid_argument("front_frame_offset (" + std::to_string(front_frame_offset) +
                                ") and frame_offsets['front'] are both given: give one");
  for (std::size_t k = 0; k < edges.size(); ++k)
    if (!edges[k].point.allFinite() || !edges[k].direction.allFinite() || edges[k].direction.norm() == 0.0)
      throw std::invalid_argument("edges[" + std::to_string(k) + "] needs a finite point and non-zero direction");
}

Reconstruction reconstruct(const Tracks2D& top, const Camera& top_camera, const Tracks2D& front,
                           const Camera& front_camera, const ReconstructOptions& o, const RunControl& control) {
  return reconstruct(std::vector<View>{{"top", top, top_camera}, {"front", front, front_camera}}, o, control);
}

Reconstruction reconstruct(const std::vector<View>& input, const ReconstructOptions& o, const RunControl& control) {
  o.validate();
  if (input.size() < 2)
    throw std::invalid_argument("reconstruct: views: at least two camera views are needed, got " +
                                std::to_string(input.size()));
  for (std::size_t v = 0; v < input.size(); ++v) {
    if (input[v].name.empty()) throw std::invalid_argument("reconstruct: views[" + std::to_string(v) + "]: empty name");
    for (std::size_t w = 0; w < v; ++w)
      if (input[w].name == input[v].name)
        throw std::invalid_argument("reconstruct: views: the name '" + input[v].name + "' is given twice");
  }
  for (const auto& entry : o.frame_offsets)
    if (std::none_of(input.begin(), input.end(), [&](const View& v) { return v.name == entry.first; }))
      throw std::invalid_argument("frame_offsets: no view named '" + entry.first + "' (offset " +
                                  std::to_string(entry.second) + ")");
  // Frame offsets applied: every view's frame f is the common frame f + offset.
  std::vector<View> views = input;
  std::vector<std::int64_t> offsets;
  for (auto& v : views) {
    offsets.push_back(o.frame_offset(v.name));
    if (offsets.back() != 0)
      for (auto& f : v.tracks.frames) f.frame += offsets.back();
  }
  const std::size_t n_views = views.size();
  std::vector<std::int64_t> frames;
  for (const auto& v : views)
    for (const auto& f : v.tracks.frames) frames.push_back(f.frame);
  std::sort(frames.begin(), frames.end());
  frames.erase(std::unique(frames.begin(), frames.end()), frames.end());
  PairMatrices F(n_views, std::vector<Eigen::Matrix3d>(n_views, Eigen::Matrix3d::Zero()));
  for (std::size_t a = 0; a < n_views; ++a)
    for (std::size_t b = 0; b < n_views; ++b)
      if (a != b) F[a][b] = fundamental_matrix(views[a].camera, views[b].camera);
  Reconstruction rec;
  for (const auto& v : views) rec.view_names.push_back(v.name);
  rec.frames.resize(frames.size());
  ProgressCounter progress(control, frames.size());
  std::vector<const TrackFrame*> tracks(n_views);
  for (std::size_t i = 0; i < frames.size(); ++i) {
    for (std::size_t v = 0; v < n_views; ++v) tracks[v] = views[v].tracks.find(frames[i]);
    rec.frames[i] = reconstruct_frame(frames[i], tracks, views, F, o);
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
  check_inputs(rec, views, offsets, o);
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
