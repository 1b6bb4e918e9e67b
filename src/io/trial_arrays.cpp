#include "trial_arrays.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>

#include "vibrissa/core/checks.hpp"

namespace vibrissa::io {

using trial::located_message;

namespace {

constexpr double nan_v = std::numeric_limits<double>::quiet_NaN();

std::string dims_text(const std::vector<std::size_t>& d) {
  std::string s;
  for (std::size_t i = 0; i < d.size(); ++i) s += (i ? "x" : "") + std::to_string(d[i]);
  return s.empty() ? "scalar" : s;
}

/// A vector of n values: accepts shapes (n), (n,1), (1,n).
std::vector<double> as_vector(const NamedArray& a, const std::string& src, const std::string& name) {
  std::size_t non_unit = 0;
  for (std::size_t d : a.dims) non_unit += d != 1;
  if (non_unit > 1)
    throw std::invalid_argument(located_message(src, 0, name, "expected a vector, got " + dims_text(a.dims)));
  return a.data;
}

/// Rows of `width` columns: accepts (n, width) and, for n != width, (width, n).
std::vector<Eigen::Vector3d> as_points(const NamedArray& a, const std::string& src, const std::string& name,
                                       double scale) {
  std::vector<Eigen::Vector3d> out;
  if (a.dims.size() == 2 && a.dims[1] == 3) {
    for (std::size_t i = 0; i < a.dims[0]; ++i)
      out.emplace_back(Eigen::Vector3d(a.data[3 * i], a.data[3 * i + 1], a.data[3 * i + 2]) * scale);
  } else if (a.dims.size() == 2 && a.dims[0] == 3) {
    const std::size_t n = a.dims[1];
    for (std::size_t i = 0; i < n; ++i)
      out.emplace_back(Eigen::Vector3d(a.data[i], a.data[n + i], a.data[2 * n + i]) * scale);
  } else {
    throw std::invalid_argument(located_message(src, 0, name, "expected an n x 3 array, got " + dims_text(a.dims)));
  }
  return out;
}

}  // namespace

trial::Trial assemble_trial(const ArrayReader& r) {
  const std::string& src = r.source;
  trial::Trial t;
  t.source = src;
  auto& u = t.meta.declared_units;
  if (auto s = r.text("length_unit")) u.length = *s;
  if (auto s = r.text("angle_unit")) u.angle = *s;
  if (auto s = r.text("time_unit")) u.time = *s;
  const double Ls = trial::length_scale(u.length, located_message(src, 0, "length_unit", ""));
  const double As = trial::angle_scale(u.angle, located_message(src, 0, "angle_unit", ""));
  const double Ts = trial::time_scale(u.time, located_message(src, 0, "time_unit", ""));

  auto required = [&](const char* name) {
    auto a = r.array(name);
    if (!a) throw std::invalid_argument(located_message(src, 0, name, "required array is missing"));
    return *a;
  };
  auto scaled = [](std::vector<double> v, double s) {
    for (double& x : v) x *= s;
    return v;
  };
  t.time = scaled(as_vector(required("time"), src, "time"), Ts);
  const std::size_t n = t.time.size();
  require_at_most(n, limits::max_trial_frames, src + ": number of frames");
  t.base_W = as_points(required("base"), src, "base", Ls);
  t.theta = scaled(as_vector(required("theta"), src, "theta"), As);
  t.phi = scaled(as_vector(required("phi"), src, "phi"), As);
  if (auto a = r.array("zeta")) t.zeta = scaled(as_vector(*a, src, "zeta"), As);
  const auto contact = as_vector(required("contact"), src, "contact");
  for (std::size_t i = 0; i < contact.size(); ++i) {
    if (!(contact[i] == 0.0 || contact[i] == 1.0))
      throw std::invalid_argument(
          located_message(src, i + 1, "contact", "contact flag must be 0 or 1, got " + format_value(contact[i])));
    t.contact.push_back(static_cast<std::uint8_t>(contact[i]));
  }
  if (auto a = r.array("contact_point")) t.contact_W = as_points(*a, src, "contact_point", Ls);
  if (auto a = r.array("shape")) {
    if (a->dims.size() != 3 || a->dims[2] != 3 || a->dims[0] != n)
      throw std::invalid_argument(located_message(src, 0, "shape", "expected frames x nodes x 3, got " +
                                                                      dims_text(a->dims)));
    const std::size_t K = a->dims[1];
    t.shape_W.resize(n);
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t k = 0; k < K; ++k) {
        const double* p = &a->data[(i * K + k) * 3];
        const Eigen::Vector3d q(p[0], p[1], p[2]);
        if (!q.allFinite()) break;  // NaN-padded
        t.shape_W[i].push_back(q * Ls);
      }
  }
  if (auto a = r.array("reconstructed")) {
    const auto flags = as_vector(*a, src, "reconstructed");
    for (std::size_t i = 0; i < flags.size(); ++i) {
      if (!(flags[i] == 0.0 || flags[i] == 1.0))
        throw std::invalid_argument(
            located_message(src, i + 1, "reconstructed", "flag must be 0 or 1, got " + std::to_string(flags[i])));
      t.reconstructed.push_back(static_cast<std::uint8_t>(flags[i]));
    }
  }
  if (auto a = r.array("reprojection_px")) t.reprojection_px = as_vector(*a, src, "reprojection_px");
  if (auto a = r.array("likelihood")) t.likelihood = as_vector(*a, src, "likelihood");
  t.meta.rest_shape = as_points(required("rest_shape"), src, "rest_shape", Ls);
  const auto edges = required("edges");
  if (edges.dims.size() != 2 || edges.dims[1] != 6)
    throw std::invalid_argument(located_message(src, 0, "edges", "expected an m x 6 array (point, direction), got " +
                                                                     dims_text(edges.dims)));
  for (std::size_t k = 0; k < edges.dims[0]; ++k) {
    const double* e = &edges.data[6 * k];
    Edge edge;
    edge.point = Eigen::Vector3d(e[0], e[1], e[2]) * Ls;
    edge.direction = Eigen::Vector3d(e[3], e[4], e[5]);
    t.meta.edges.push_back(edge);
  }
  auto& m = t.meta.material;
  if (auto v = r.number("frame_rate_Hz")) t.meta.frame_rate = *v;
  if (auto v = r.number("youngs_modulus_Pa")) m.youngs_modulus = *v;
  if (auto v = r.number("poisson_ratio")) m.poisson_ratio = *v;
  if (auto v = r.number("base_radius")) m.base_radius = *v * Ls;
  if (auto v = r.number("taper_ratio")) m.taper_ratio = *v;
  if (auto v = r.number("links")) {
    try {
      m.links = require_integer(*v, 2, limits::max_links, "links");
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(located_message(src, 0, "links", e.what()));
    }
  }
  trial::validate(t);
  return t;
}

TrialArrays disassemble_trial(const trial::Trial& t) {
  TrialArrays out;
  const std::size_t n = t.frames();
  auto vec = [&](const std::vector<double>& v, const char* units) { return NamedArray{{v.size()}, v, units}; };
  auto pts = [](const std::vector<Eigen::Vector3d>& p) {
    NamedArray a{{p.size(), 3}, {}, "m"};
    for (const auto& q : p) a.data.insert(a.data.end(), {q.x(), q.y(), q.z()});
    return a;
  };
  out.arrays.emplace_back("time", vec(t.time, "s"));
  out.arrays.emplace_back("base", pts(t.base_W));
  out.arrays.emplace_back("theta", vec(t.theta, "rad"));
  out.arrays.emplace_back("phi", vec(t.phi, "rad"));
  if (t.has_zeta()) out.arrays.emplace_back("zeta", vec(t.zeta, "rad"));
  out.arrays.emplace_back("contact", vec(std::vector<double>(t.contact.begin(), t.contact.end()), "1"));
  if (t.has_contact_point()) out.arrays.emplace_back("contact_point", pts(t.contact_W));
  if (t.has_shapes()) {
    std::size_t K = 0;
    for (const auto& s : t.shape_W) K = std::max(K, s.size());
    NamedArray a{{n, K, 3}, std::vector<double>(n * K * 3, nan_v), "m"};
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t k = 0; k < t.shape_W[i].size(); ++k)
        for (int c = 0; c < 3; ++c) a.data[(i * K + k) * 3 + static_cast<std::size_t>(c)] = t.shape_W[i][k][c];
    out.arrays.emplace_back("shape", std::move(a));
  }
  if (!t.reconstructed.empty())
    out.arrays.emplace_back("reconstructed",
                            vec(std::vector<double>(t.reconstructed.begin(), t.reconstructed.end()), "1"));
  if (!t.reprojection_px.empty()) out.arrays.emplace_back("reprojection_px", vec(t.reprojection_px, "px"));
  if (!t.likelihood.empty()) out.arrays.emplace_back("likelihood", vec(t.likelihood, "1"));
  out.arrays.emplace_back("rest_shape", pts(t.meta.rest_shape));
  NamedArray e{{t.meta.edges.size(), 6}, {}, "m"};  // point [m], then a unit direction
  for (const auto& edge : t.meta.edges)
    e.data.insert(e.data.end(), {edge.point.x(), edge.point.y(), edge.point.z(), edge.direction.x(),
                                 edge.direction.y(), edge.direction.z()});
  out.arrays.emplace_back("edges", std::move(e));
  out.texts = {{"length_unit", "m"}, {"angle_unit", "rad"}, {"time_unit", "s"}};
  const auto& m = t.meta.material;
  out.numbers = {{"frame_rate_Hz", t.meta.frame_rate}, {"youngs_modulus_Pa", m.youngs_modulus},
                 {"poisson_ratio", m.poisson_ratio},    {"base_radius", m.base_radius},
                 {"taper_ratio", m.taper_ratio},        {"links", static_cast<double>(m.links)}};
  return out;
}

}  // namespace vibrissa::io
