#include "vibrissa/trial/plausibility.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>
#include <utility>

#include "vibrissa/core/plausibility.hpp"

namespace vibrissa::trial {

namespace {

double polyline_length(const std::vector<Eigen::Vector3d>& points) {
  double L = 0.0;
  for (std::size_t i = 1; i < points.size(); ++i) L += (points[i] - points[i - 1]).norm();
  return L;
}

}  // namespace

std::vector<std::string> trial_warnings(const Trial& t) {
  std::vector<std::string> out;
  const double L = polyline_length(t.meta.rest_shape);
  try {  // the whisker the pipeline builds: its length, base radius and Young's modulus
    const Whisker w = Whisker::from_points(t.meta.rest_shape, whisker_properties(t.meta.material));
    out = plausibility_warnings(w);
  } catch (const std::exception&) {  // too short or degenerate to build: the length alone says why
    if (auto m = length_warning("whisker length", L)) out.push_back(std::move(*m));
  }
  const bool degrees = t.meta.declared_units.angle == "deg";
  const std::array<std::pair<const char*, const std::vector<double>*>, 3> series = {
      {{"theta", &t.theta}, {"phi", &t.phi}, {"zeta", &t.zeta}}};
  for (const auto& [name, values] : series)
    if (auto m = angle_series_warning(name, *values, degrees)) out.push_back(std::move(*m));
  // An edge is out of reach if it is so in every reconstructed frame (the whisker base moves with the head).
  for (std::size_t e = 0; e < t.meta.edges.size(); ++e) {
    const Edge& edge = t.meta.edges[e];
    std::optional<std::string> nearest;
    double nearest_distance = std::numeric_limits<double>::infinity();
    bool any_frame = false;
    for (std::size_t i = 0; i < t.frames(); ++i) {
      if (!t.base_W[i].allFinite()) continue;
      any_frame = true;
      const Eigen::Vector3d u = edge.direction.normalized();
      Eigen::Vector3d d = edge.point - t.base_W[i];
      d -= d.dot(u) * u;  // the distance of the edge's line from this frame's base
      if (d.norm() < nearest_distance) {
        nearest_distance = d.norm();
        nearest = reach_warning("edge " + std::to_string(e + 1) + " (peg)", edge.point, edge.direction, t.base_W[i], L);
      }
    }
    if (any_frame && nearest) out.push_back(*nearest + " (at its nearest over all frames)");
  }
  return out;
}

}  // namespace vibrissa::trial
