// Contact points of a deflected whisker on a surface during motion (surface_contact.hpp).
#include "surface_contact.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "vibrissa/objects/clearance.hpp"

namespace vibrissa::dynamics::detail {

void surface_contacts(const PlacedShape& object, std::span<const Eigen::Vector3d> nodes, std::span<const double> arc,
                      std::span<const double> radii, std::span<const double> previous_arc,
                      std::span<const int> hold_link, std::span<SurfaceCandidate> slots, SurfaceCandidate& nearest) {
  const std::size_t n = nodes.size(), links = n - 1;
  auto radius = [&](std::size_t i) { return radii.empty() ? 0.0 : radii[i]; };
  // Links farther than kNear from the shape's bounding box (by a lower bound of their gap: the signed distance
  // changes no faster than the distance moved, the radius by the taper's slope) are not queried.
  constexpr double kNear = 1e-3;  // [m]
  double slope = 0.0;
  for (std::size_t i = 0; i < links; ++i)
    slope = std::max(slope, std::abs(radius(i + 1) - radius(i)) / std::max(arc[i + 1] - arc[i], 1e-300));
  const double K = 1.0 + slope;
  thread_local std::vector<double> lower;
  thread_local std::vector<SurfacePoint> query;
  thread_local std::vector<char> queried;
  thread_local std::vector<SurfaceCandidate> link_min;
  lower.resize(n);
  query.resize(n);
  queried.assign(n, 0);
  link_min.assign(links, SurfaceCandidate{});
  for (std::size_t i = 0; i < n; ++i) lower[i] = object.bound_distance_W(nodes[i]) - radius(i);
  auto held = [&](std::size_t i) {
    for (const int h : hold_link)
      if (h >= 0 && static_cast<std::size_t>(std::abs(h - static_cast<int>(i))) <= 1) return true;
    return false;
  };
  auto at = [&](std::size_t i) -> const SurfacePoint& {
    if (!queried[i]) {
      query[i] = object.nearest_W(nodes[i]);
      queried[i] = 1;
    }
    return query[i];
  };
  nearest = SurfaceCandidate{};
  for (std::size_t i = 0; i < links; ++i) {
    SurfaceCandidate& c = link_min[i];
    c.link = static_cast<int>(i);
    const double l = arc[i + 1] - arc[i];
    const double bound = 0.5 * (lower[i] + lower[i + 1] - K * l);
    if (bound >= kNear && !held(i)) {
      c.gap = bound;  // a lower bound, not a candidate
      if (c.gap < nearest.gap) {
        nearest = c;
        nearest.arc_length = arc[i];
        nearest.point_W = nodes[i];
      }
      continue;
    }
    const LinkGap m = link_minimum(object, nodes[i], nodes[i + 1], radius(i), radius(i + 1), at(i), at(i + 1));
    c.found = true;
    c.tau = m.tau;
    c.gap = m.gap;
    c.arc_length = arc[i] + m.tau * l;
    c.point_W = nodes[i] + m.tau * (nodes[i + 1] - nodes[i]);
    c.surface = m.surface;
    if (c.gap < nearest.gap) nearest = c;
  }
  // The places inside: runs of links with a negative gap, each at its deepest link.
  thread_local std::vector<SurfaceCandidate> places;
  places.clear();
  for (std::size_t i = 0; i < links;) {
    if (!(link_min[i].found && link_min[i].gap < 0.0)) {
      ++i;
      continue;
    }
    std::size_t deepest = i;
    for (; i < links && link_min[i].found && link_min[i].gap < 0.0; ++i)
      if (link_min[i].gap < link_min[deepest].gap) deepest = i;
    places.push_back(link_min[deepest]);
  }
  std::sort(places.begin(), places.end(),
            [](const SurfaceCandidate& a, const SurfaceCandidate& b) { return a.gap < b.gap; });
  if (places.size() > slots.size()) places.resize(slots.size());
  for (SurfaceCandidate& s : slots) s = SurfaceCandidate{};
  thread_local std::vector<char> taken;
  taken.assign(places.size(), 0);
  // Slots in contact before continue with the place nearest along the whisker.
  for (std::size_t k = 0; k < slots.size(); ++k) {
    if (!std::isfinite(previous_arc[k])) continue;
    std::size_t best = places.size();
    for (std::size_t p = 0; p < places.size(); ++p)
      if (!taken[p] && (best == places.size() || std::abs(places[p].arc_length - previous_arc[k]) <
                                                     std::abs(places[best].arc_length - previous_arc[k])))
        best = p;
    if (best == places.size()) continue;
    slots[k] = places[best];
    taken[best] = 1;
  }
  // New places: free slots first, then slots whose contact ended.
  for (int pass = 0; pass < 2; ++pass)
    for (std::size_t p = 0; p < places.size(); ++p) {
      if (taken[p]) continue;
      for (std::size_t k = 0; k < slots.size(); ++k)
        if (!slots[k].found && (pass == 1 || !std::isfinite(previous_arc[k]))) {
          slots[k] = places[p];
          taken[p] = 1;
          break;
        }
    }
  // Held slots without a place: the smallest gap near the held link.
  for (std::size_t k = 0; k < slots.size(); ++k) {
    if (slots[k].found || hold_link[k] < 0) continue;
    const auto h = static_cast<std::size_t>(hold_link[k]);
    for (std::size_t i = h > 0 ? h - 1 : 0; i <= std::min(h + 1, links - 1); ++i)
      if (link_min[i].found && (!slots[k].found || link_min[i].gap < slots[k].gap)) slots[k] = link_min[i];
  }
}

}  // namespace vibrissa::dynamics::detail
