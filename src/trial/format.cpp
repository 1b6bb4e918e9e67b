#include "vibrissa/trial/format.hpp"

#include <cmath>
#include <numbers>
#include <sstream>
#include <stdexcept>

#include "vibrissa/core/checks.hpp"

namespace vibrissa::trial {

namespace {
[[noreturn]] void fail(const std::string& source, std::size_t row, const std::string& column,
                       const std::string& message) {
  throw std::invalid_argument(located_message(source, row, column, message));
}
std::string fmt(double v) { return format_value(v); }
}  // namespace

std::string located_message(const std::string& source, std::size_t row, const std::string& column,
                            const std::string& message) {
  std::ostringstream os;
  os << (source.empty() ? std::string("<trial>") : source) << ": ";
  if (row > 0) os << "row " << row << ", ";
  if (!column.empty()) os << "column '" << column << "': ";
  os << message;
  return os.str();
}

double length_scale(const std::string& unit, const std::string& where) {
  if (unit == "m") return 1.0;
  if (unit == "mm") return 1e-3;
  if (unit == "um" || unit == "µm") return 1e-6;
  throw std::invalid_argument(where + ": unknown length unit '" + unit + "' (expected m, mm or um)");
}
double angle_scale(const std::string& unit, const std::string& where) {
  if (unit == "rad") return 1.0;
  if (unit == "deg") return std::numbers::pi / 180.0;
  throw std::invalid_argument(where + ": unknown angle unit '" + unit + "' (expected rad or deg)");
}
double time_scale(const std::string& unit, const std::string& where) {
  if (unit == "s") return 1.0;
  if (unit == "ms") return 1e-3;
  throw std::invalid_argument(where + ": unknown time unit '" + unit + "' (expected s or ms)");
}

std::vector<ContactPeriod> contact_periods(const std::vector<std::uint8_t>& contact) {
  std::vector<ContactPeriod> periods;
  for (std::size_t i = 0; i < contact.size(); ++i) {
    if (!contact[i]) continue;
    if (i == 0 || !contact[i - 1]) periods.push_back({i, i});
    periods.back().last = i;
  }
  return periods;
}

Trial reconstructed_frames_only(const Trial& t) {
  if (t.reconstructed.empty()) return t;
  Trial out;
  out.source = t.source;
  out.meta = t.meta;
  auto keep = [&](const auto& column, auto& into, std::size_t i) {
    if (!column.empty()) into.push_back(column[i]);
  };
  for (std::size_t i = 0; i < t.frames(); ++i) {
    if (!t.is_reconstructed(i)) continue;
    keep(t.time, out.time, i);
    keep(t.base_W, out.base_W, i);
    keep(t.theta, out.theta, i);
    keep(t.phi, out.phi, i);
    keep(t.zeta, out.zeta, i);
    keep(t.contact, out.contact, i);
    keep(t.contact_W, out.contact_W, i);
    keep(t.shape_W, out.shape_W, i);
    keep(t.reprojection_px, out.reprojection_px, i);
    keep(t.likelihood, out.likelihood, i);
  }
  return out;
}

WhiskerProperties whisker_properties(const TrialMaterial& m) {
  WhiskerProperties p;
  p.links = m.links;
  p.base_radius = m.base_radius;
  p.taper_ratio = m.taper_ratio;
  p.youngs_modulus = m.youngs_modulus;
  p.poisson_ratio = m.poisson_ratio;
  return p;
}

void validate(const Trial& t, const std::vector<std::size_t>* file_rows) {
  const std::string& src = t.source;
  const std::size_t n = t.time.size();
  if (n > limits::max_trial_frames)
    fail(src, 0, "time", "has " + std::to_string(n) + " frames, more than the limit of " +
                             std::to_string(limits::max_trial_frames));
  auto row = [&](std::size_t i) { return file_rows && i < file_rows->size() ? (*file_rows)[i] : i + 1; };
  if (n == 0) fail(src, 0, "time", "the trial has no frames");
  auto same_size = [&](std::size_t size, const char* column, bool optional) {
    if (optional && size == 0) return;
    if (size != n)
      fail(src, 0, column, "has " + std::to_string(size) + " rows but 'time' has " + std::to_string(n));
  };
  same_size(t.base_W.size(), "base", false);
  same_size(t.theta.size(), "theta", false);
  same_size(t.phi.size(), "phi", false);
  same_size(t.zeta.size(), "zeta", true);
  same_size(t.contact.size(), "contact", false);
  same_size(t.contact_W.size(), "contact_point", true);
  same_size(t.shape_W.size(), "shape", true);
  same_size(t.reconstructed.size(), "reconstructed", true);
  same_size(t.reprojection_px.size(), "reprojection_px", true);
  same_size(t.likelihood.size(), "likelihood", true);
  auto finite = [&](double v, std::size_t i, const char* column) {
    if (!std::isfinite(v)) fail(src, row(i), column, "value " + fmt(v) + " is not finite");
  };
  static const char* axes[3] = {"base_x", "base_y", "base_z"};
  static const char* caxes[3] = {"contact_x", "contact_y", "contact_z"};
  for (std::size_t i = 0; i < n; ++i) {
    finite(t.time[i], i, "time");
    if (i > 0 && !(t.time[i] > t.time[i - 1]))
      fail(src, row(i), "time",
           "time must increase strictly, got " + fmt(t.time[i]) + " s after " + fmt(t.time[i - 1]) + " s");
    if (!t.reconstructed.empty() && t.reconstructed[i] > 1)
      fail(src, row(i), "reconstructed", "flag must be 0 or 1, got " + std::to_string(t.reconstructed[i]));
    if (!t.is_reconstructed(i)) {  // values are NaN by design; such frames never count as contact
      if (t.contact[i] != 0) fail(src, row(i), "contact", "a frame that is not reconstructed cannot be in contact");
      continue;
    }
    for (int a = 0; a < 3; ++a) finite(t.base_W[i][a], i, axes[a]);
    finite(t.theta[i], i, "theta");
    finite(t.phi[i], i, "phi");
    if (t.has_zeta()) finite(t.zeta[i], i, "zeta");
    if (t.contact[i] > 1)
      fail(src, row(i), "contact", "contact flag must be 0 or 1, got " + std::to_string(t.contact[i]));
    if (t.has_contact_point() && t.contact[i])
      for (int a = 0; a < 3; ++a) finite(t.contact_W[i][a], i, caxes[a]);
  }
  if (contact_periods(t.contact).empty())
    fail(src, 0, "contact", "no frame is flagged as contact: the trial has no contact period to analyse");
  const auto& m = t.meta;
  if (m.rest_shape.size() < 3)
    fail(src, 0, "rest_shape", "needs at least 3 points, got " + std::to_string(m.rest_shape.size()));
  if (m.rest_shape.size() > limits::max_shape_points)
    fail(src, 0, "rest_shape", "has " + std::to_string(m.rest_shape.size()) + " points, more than the limit of " +
                                   std::to_string(limits::max_shape_points));
  double rest_length = 0.0;
  for (std::size_t k = 0; k < m.rest_shape.size(); ++k) {
    if (!m.rest_shape[k].allFinite()) fail(src, k + 1, "rest_shape", "point is not finite");
    if (k == 0) continue;
    const double chord = (m.rest_shape[k] - m.rest_shape[k - 1]).norm();
    if (!(chord > 0.0))
      fail(src, k + 1, "rest_shape", "point " + format_value(m.rest_shape[k]) + " repeats the previous point");
    rest_length += chord;
  }
  if (!(rest_length >= limits::min_whisker_length_m && rest_length <= limits::max_whisker_length_m))
    fail(src, 0, "rest_shape", "the whisker's length must lie in [" + fmt(limits::min_whisker_length_m) + ", " +
                                   fmt(limits::max_whisker_length_m) + "] m, got " + fmt(rest_length) + " m");
  if (m.edges.empty()) fail(src, 0, "edges", "the trial names no object edge");
  if (m.edges.size() > limits::max_edges)
    fail(src, 0, "edges", "has " + std::to_string(m.edges.size()) + " edges, more than the limit of " +
                              std::to_string(limits::max_edges));
  for (std::size_t k = 0; k < m.edges.size(); ++k) {
    const auto& e = m.edges[k];
    const double n2 = e.direction.squaredNorm();
    if (!e.point.allFinite() || !e.direction.allFinite() || !(n2 >= 1e-300 && n2 <= 1e300))
      fail(src, k + 1, "edges", "edge needs a finite point and a non-zero finite direction, got point " +
                                    format_value(e.point) + ", direction " + format_value(e.direction));
  }
  auto in_range = [&](double v, double lo, double hi, const char* field) {
    if (!(v >= lo && v <= hi)) fail(src, 0, field, "must lie in [" + fmt(lo) + ", " + fmt(hi) + "], got " + fmt(v));
  };
  in_range(m.material.youngs_modulus, limits::min_youngs_modulus_Pa, limits::max_youngs_modulus_Pa, "youngs_modulus_Pa");
  in_range(m.material.base_radius, limits::min_radius_m, limits::max_radius_m, "base_radius");
  in_range(m.material.taper_ratio, 1.0 / limits::max_taper_ratio, limits::max_taper_ratio, "taper_ratio");
  if (!(std::isfinite(m.frame_rate) && m.frame_rate > 0.0)) fail(src, 0, "frame_rate_Hz", "must be positive, got " + fmt(m.frame_rate));
  if (!(m.material.poisson_ratio > -1.0 && m.material.poisson_ratio < 0.5))
    fail(src, 0, "poisson_ratio", "must lie in (-1, 0.5), got " + fmt(m.material.poisson_ratio));
  if (m.material.links < 2 || m.material.links > limits::max_links)
    fail(src, 0, "links", "must be an integer in [2, " + std::to_string(limits::max_links) + "], got " +
                              std::to_string(m.material.links));
}

}  // namespace vibrissa::trial
