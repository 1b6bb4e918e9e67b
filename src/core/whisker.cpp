#include "vibrissa/core/whisker.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include <Eigen/Geometry>
#include <Eigen/SVD>

#include "vibrissa/core/rest_curve.hpp"
#include "vibrissa/core/simple_curve.hpp"

namespace vibrissa {
namespace {

[[noreturn]] void fail(const std::string& what) { throw std::invalid_argument(what); }

// Value at fraction u in [0, 1] of samples equally spaced base to tip (piecewise linear).
double sample_profile(const std::vector<double>& values, double u) {
  const double pos = std::clamp(u, 0.0, 1.0) * double(values.size() - 1);
  const std::size_t i = std::min(static_cast<std::size_t>(pos), values.size() - 2);
  const double f = pos - double(i);
  return (1.0 - f) * values[i] + f * values[i + 1];
}

Eigen::Matrix3d minimal_rotation(const Eigen::Vector3d& from, const Eigen::Vector3d& to) {
  return Eigen::Quaterniond::FromTwoVectors(from, to).toRotationMatrix();
}

}  // namespace

void check_rest_geometry(const Whisker& w, std::string_view source) {
  const double L = w.length();
  if (!(L >= limits::min_whisker_length_m && L <= limits::max_whisker_length_m))
    fail(std::string(source) + ": the whisker's arc length must lie in [" + format_value(limits::min_whisker_length_m) +
         ", " + format_value(limits::max_whisker_length_m) + "] m, got " + format_value(L));
  for (std::size_t i = 0; i < w.link_lengths().size(); ++i) {
    const double l = w.link_lengths()[i];
    if (!(std::isfinite(l) && l > 0.0))
      fail(std::string(source) + ": link " + std::to_string(i) + " has length " + format_value(l) +
           " after resampling: the points are too close together or too far apart");
  }
  for (std::size_t j = 0; j < w.bending_compliance().size(); ++j)
    if (!(std::isfinite(w.bending_compliance()[j]) && std::isfinite(w.torsion_compliance()[j])))
      fail(std::string(source) + ": the stiffness at joint " + std::to_string(j) +
           " is not finite (radius or Young's modulus out of range)");
}

void validate(const WhiskerProperties& p) {
  require_integer(p.links, 2, limits::max_links, "whisker.links");
  if (p.radii.empty()) {
    require_in_range(p.base_radius, limits::min_radius_m, limits::max_radius_m, "whisker.base_radius");
    require_in_range(p.taper_ratio, 1.0 / limits::max_taper_ratio, limits::max_taper_ratio, "whisker.taper_ratio");
  } else {
    if (p.radii.size() < 2) fail("whisker.radii needs at least 2 values, got " + std::to_string(p.radii.size()));
    require_at_most(p.radii.size(), limits::max_list_length, "whisker.radii");
    for (std::size_t i = 0; i < p.radii.size(); ++i)
      require_in_range(p.radii[i], limits::min_radius_m, limits::max_radius_m,
                       "whisker.radii[" + std::to_string(i) + "]");
  }
  if (p.youngs_moduli.empty()) {
    require_in_range(p.youngs_modulus, limits::min_youngs_modulus_Pa, limits::max_youngs_modulus_Pa,
                     "whisker.youngs_modulus");
  } else {
    if (p.youngs_moduli.size() < 2)
      fail("whisker.youngs_modulus as a list needs at least 2 values, got " + std::to_string(p.youngs_moduli.size()));
    require_at_most(p.youngs_moduli.size(), limits::max_list_length, "whisker.youngs_modulus");
    for (std::size_t i = 0; i < p.youngs_moduli.size(); ++i)
      require_in_range(p.youngs_moduli[i], limits::min_youngs_modulus_Pa, limits::max_youngs_modulus_Pa,
                       "whisker.youngs_modulus[" + std::to_string(i) + "]");
  }
  if (!(std::isfinite(p.poisson_ratio) && p.poisson_ratio > -1.0 && p.poisson_ratio < 0.5 + 1e-12))
    fail("whisker.poisson_ratio must lie in (-1, 0.5], got " + format_value(p.poisson_ratio));
  if (p.base_stiffness) {
    require_in_range(*p.base_stiffness, limits::min_base_stiffness_Nm_per_rad, limits::max_base_stiffness_Nm_per_rad,
                     "whisker.base_stiffness [N m/rad]");
    if (p.base == BaseJoint::rigid) fail("whisker.base_stiffness needs base \"elastic\", got base \"rigid\"");
  }
}

Whisker Whisker::from_points(const std::vector<Eigen::Vector3d>& points, const WhiskerProperties& props,
                             const std::optional<Pose>& pose) {
  validate(props);
  if (points.size() < 3) fail("whisker.points needs at least 3 points, got " + std::to_string(points.size()));
  require_at_most(points.size(), limits::max_shape_points, "whisker.points");
  for (std::size_t i = 0; i < points.size(); ++i) require_finite(points[i], "whisker.points[" + std::to_string(i) + "]");
  require_simple_curve(points, "whisker.points");
  Eigen::Vector3d tangent0;
  std::vector<Eigen::Vector3d> nodes = resample_points(points, props.links, &tangent0);
  WhiskerProperties used = props;
  if (props.scheme == Scheme::paper) {  // Elastica3D takes the nodes as given
    nodes = points;
    used.links = static_cast<int>(points.size()) - 1;
  }
  const Eigen::Matrix3d R = whisker_frame(nodes, tangent0);  // columns: B axes in the input frame
  const Eigen::Vector3d base = nodes.front();
  for (auto& p : nodes) p = R.transpose() * (p - base);
  if (!R.allFinite() || !base.allFinite())
    fail("whisker.points: the curve through the points is not finite (coordinates too large or too close)");
  Whisker w;
  try {
    w.build(std::move(nodes), used);
  } catch (const std::invalid_argument& e) {
    fail(std::string("whisker.points: the rest curve cannot be modelled: ") + e.what());
  }
  check_rest_geometry(w, "whisker.points");
  w.placement_ = pose ? Placement(*pose) : Placement(R, base);
  return w;
}

Whisker Whisker::from_parabola(double length, double a, const WhiskerProperties& props, const Pose& pose) {
  require_finite(a, "whisker.curvature");
  return from_cubic(length, 0.0, a, props, pose);
}

Whisker Whisker::from_cubic(double length, double A, double B, const WhiskerProperties& props, const Pose& pose) {
  validate(props);
  validate(pose);
  require_in_range(length, limits::min_whisker_length_m, limits::max_whisker_length_m, "whisker.length");
  require_finite(A, "whisker.cubic[0]");
  require_finite(B, "whisker.cubic[1]");
  Whisker w;
  try {
    w.build(planar_polynomial_nodes(length, A, B, props.links), props);
  } catch (const std::invalid_argument& e) {  // e.g. a curve too steep for the paper scheme's spline
    fail(std::string("whisker.curvature/cubic (A = ") + format_value(A) + " 1/m^2, B = " + format_value(B) +
         " 1/m): the rest curve cannot be modelled: " + e.what());
  }
  check_rest_geometry(w, "whisker.curvature/cubic");
  w.placement_ = Placement(pose);
  return w;
}

void Whisker::build(std::vector<Eigen::Vector3d> nodes_B, const WhiskerProperties& props) {
  props_ = props;
  nodes_B_ = std::move(nodes_B);
  const std::size_t N = nodes_B_.size() - 1;
  link_length_.resize(N);
  arc_.assign(N + 1, 0.0);
  for (std::size_t i = 0; i < N; ++i) {
    link_length_[i] = (nodes_B_[i + 1] - nodes_B_[i]).norm();
    arc_[i + 1] = arc_[i] + link_length_[i];
  }
  const double L = arc_.back();

  // Parallel-transported (twist-free) rest link frames and the rest rotation across each joint.
  R_link_B_.resize(N);
  Q_rest_.resize(N);
  Eigen::Vector3d prev = Eigen::Vector3d::UnitX();
  Eigen::Matrix3d R_prev = Eigen::Matrix3d::Identity();
  for (std::size_t i = 0; i < N; ++i) {
    const Eigen::Vector3d t = (nodes_B_[i + 1] - nodes_B_[i]) / link_length_[i];
    R_link_B_[i] = minimal_rotation(prev, t) * R_prev;
    Q_rest_[i] = R_prev.transpose() * R_link_B_[i];
    prev = t;
    R_prev = R_link_B_[i];
  }

  // Rest curvature across each link, averaged from the rest rotations at its two nodes.
  load_curvature_.assign(N, Eigen::Vector3d::Zero());
  if (props.scheme == Scheme::second_order && N >= 2) {
    auto rate = [&](std::size_t j) {  // rotation vector of joint j (1 <= j < N) per unit arc length
      const Eigen::AngleAxisd aa(Q_rest_[j]);
      return Eigen::Vector3d(aa.angle() * aa.axis() / (0.5 * (link_length_[j - 1] + link_length_[j])));
    };
    for (std::size_t k = 0; k < N; ++k) {
      if (k == 0)
        load_curvature_[k] = rate(1);
      else if (k == N - 1)
        load_curvature_[k] = rate(N - 1);
      else
        load_curvature_[k] = 0.5 * (rate(k) + rate(k + 1));
    }
  }

  // Material and section per node (spec §2.1): I = pi r^4 / 4, J = pi r^4 / 2, G = E / (2 (1 + nu)).
  radius_.resize(N + 1);
  youngs_.resize(N + 1);
  for (std::size_t i = 0; i <= N; ++i) {
    const double u = arc_[i] / L;
    radius_[i] = props.radii.empty() ? props.base_radius * (1.0 - (1.0 - 1.0 / props.taper_ratio) * u)
                                     : sample_profile(props.radii, u);
    youngs_[i] = props.youngs_moduli.empty() ? props.youngs_modulus : sample_profile(props.youngs_moduli, u);
  }
  cb_.resize(N);
  ct_.resize(N);
  for (std::size_t j = 0; j < N; ++j) {
    const double r4 = std::pow(radius_[j], 4);
    const double E = youngs_[j], G = E / (2.0 * (1.0 + props.poisson_ratio));
    cb_[j] = 1.0 / (E * std::numbers::pi * r4 / 4.0);
    ct_[j] = 1.0 / (G * std::numbers::pi * r4 / 2.0);
  }

  compliance_link_.resize(N);
  for (std::size_t j = 0; j < N; ++j) {
    const Eigen::AngleAxisd half(-0.5 * Eigen::AngleAxisd(Q_rest_[j]).angle(), Eigen::AngleAxisd(Q_rest_[j]).axis());
    const Eigen::Matrix3d H = half.toRotationMatrix();
    compliance_link_[j] = H * Eigen::Vector3d(ct_[j], cb_[j], cb_[j]).asDiagonal() * H.transpose();
  }

  // Joint weights (docs/conventions.md, "Discretisation").
  weight_.resize(N);
  weight_load_base_.resize(N);
  for (std::size_t j = 0; j < N; ++j) {
    const double left = j == 0 ? 0.0 : link_length_[j - 1];
    weight_[j] = 0.5 * (left + link_length_[j]);
    weight_load_base_[j] = 0.5 * left;
  }
  weight_load_slope_ = 0.5;
  compliance_B_.resize(N);
  weighted_compliance_B_.resize(N);
  link_vector_B_.resize(N);
  for (std::size_t j = 0; j < N; ++j) {
    compliance_B_[j] = R_link_B_[j] * compliance_link_[j] * R_link_B_[j].transpose();
    weighted_compliance_B_[j] = weight_[j] * compliance_B_[j];
    link_vector_B_[j] = link_length_[j] * R_link_B_[j].col(0);
  }
  if (props.scheme == Scheme::paper) {
    for (int d = 0; d < 3; ++d) {
      std::vector<double> c(N + 1);
      for (std::size_t i = 0; i <= N; ++i) c[i] = nodes_B_[i][d];
      remesh_.node_B[static_cast<std::size_t>(d)] = CubicSpline::not_a_knot(arc_, c);
    }
    const std::vector<double> s_tail(arc_.begin() + 1, arc_.end());
    std::vector<double> E(youngs_.begin() + 1, youngs_.end()), I(N);
    for (std::size_t i = 0; i < N; ++i) I[i] = std::numbers::pi / 4.0 * std::pow(radius_[i + 1], 4);
    remesh_.youngs = CubicSpline::not_a_knot(s_tail, E);
    remesh_.inertia = CubicSpline::not_a_knot(s_tail, I);
  }
  base_extra_compliance_ = props.base_stiffness ? 1.0 / *props.base_stiffness : 0.0;
  // FNV-1a over the bytes of every array the walk and the paper scheme's re-mesh are built from.
  std::uint64_t h = 14695981039346656037ull;
  auto bytes = [&h](const void* data, std::size_t size) {
    const auto* b = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < size; ++i) h = (h ^ b[i]) * 1099511628211ull;
  };
  auto all = [&bytes](const auto& v) { bytes(v.data(), v.size() * sizeof(v[0])); };
  all(nodes_B_), all(radius_), all(youngs_), all(cb_), all(ct_), all(weight_), all(weight_load_base_);
  all(compliance_link_), all(compliance_B_), all(weighted_compliance_B_), all(link_vector_B_), all(load_curvature_);
  bytes(&weight_load_slope_, sizeof weight_load_slope_);
  bytes(&base_extra_compliance_, sizeof base_extra_compliance_);
  const auto scheme = static_cast<int>(props.scheme), base = static_cast<int>(props.base);
  bytes(&scheme, sizeof scheme);
  bytes(&base, sizeof base);
  fingerprint_ = h;
}

void Whisker::locate(double s, int& link, double& h) const {
  const int N = links();
  if (s >= arc_[static_cast<std::size_t>(N - 1)]) {
    link = N - 1;
  } else if (!(s > 0.0)) {  // also NaN: never an index past the arrays
    link = 0;
  } else {
    auto it = std::upper_bound(arc_.begin(), arc_.end(), s);
    link = static_cast<int>(it - arc_.begin()) - 1;
  }
  h = s - arc_[static_cast<std::size_t>(link)];
}

Eigen::Vector3d Whisker::rest_point_B(double s) const {
  int k;
  double h;
  locate(s, k, h);
  return nodes_B_[static_cast<std::size_t>(k)] + h * R_link_B_[static_cast<std::size_t>(k)].col(0);
}

}  // namespace vibrissa
