#include "vibrissa/objects/mesh.hpp"

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Simple_cartesian.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iterator>
#include <limits>
#include <map>
#include <optional>
#include <numbers>
#include <unordered_map>

#include "surface_math.hpp"
#include "vibrissa/core/checks.hpp"

namespace vibrissa {

// CGAL's AABB tree over the triangles (double-precision kernel: closest points to rounding).
struct Mesh::Tree {
  using K = CGAL::Simple_cartesian<double>;
  using Triangles = std::vector<K::Triangle_3>;
  using Primitive = CGAL::AABB_triangle_primitive<K, Triangles::const_iterator>;
  using AABB = CGAL::AABB_tree<CGAL::AABB_traits<K, Primitive>>;
  Triangles triangles;
  AABB tree;
};

namespace {

using Tree = CGAL::Simple_cartesian<double>;

std::uint64_t edge_key(int a, int b) {
  const auto lo = static_cast<std::uint64_t>(std::min(a, b)), hi = static_cast<std::uint64_t>(std::max(a, b));
  return (lo << 32) | hi;
}

/// Triangles oriented consistently with their neighbours across manifold edges (breadth first per component),
/// each closed component then outward (positive volume). Returns whether every edge has exactly two triangles.
bool orient(const std::vector<Eigen::Vector3d>& v, std::vector<std::array<int, 3>>& t) {
  std::unordered_map<std::uint64_t, std::vector<std::size_t>> by_edge;
  for (std::size_t f = 0; f < t.size(); ++f)
    for (int e = 0; e < 3; ++e) by_edge[edge_key(t[f][e], t[f][(e + 1) % 3])].push_back(f);
  bool closed = true;
  for (const auto& [key, faces] : by_edge) closed = closed && faces.size() == 2;
  auto has_directed = [](const std::array<int, 3>& tri, int a, int b) {
    for (int e = 0; e < 3; ++e)
      if (tri[e] == a && tri[(e + 1) % 3] == b) return true;
    return false;
  };
  std::vector<int> component(t.size(), -1);
  std::vector<std::size_t> queue;
  int components = 0;
  for (std::size_t seed = 0; seed < t.size(); ++seed) {
    if (component[seed] >= 0) continue;
    queue.assign(1, seed);
    component[seed] = components;
    std::vector<std::size_t> members;
    bool component_closed = true;
    for (std::size_t head = 0; head < queue.size(); ++head) {
      const std::size_t f = queue[head];
      members.push_back(f);
      for (int e = 0; e < 3; ++e) {
        const int a = t[f][e], b = t[f][(e + 1) % 3];
        const auto& faces = by_edge[edge_key(a, b)];
        if (faces.size() != 2) {
          component_closed = false;
          continue;
        }
        const std::size_t g = faces[0] == f ? faces[1] : faces[0];
        if (component[g] >= 0) continue;
        if (has_directed(t[g], a, b)) std::swap(t[g][1], t[g][2]);  // a neighbour runs the shared edge backwards
        component[g] = components;
        queue.push_back(g);
      }
    }
    if (component_closed) {
      double volume = 0.0;
      for (std::size_t f : members) volume += v[t[f][0]].dot(v[t[f][1]].cross(v[t[f][2]]));
      if (volume < 0.0)
        for (std::size_t f : members) std::swap(t[f][1], t[f][2]);
    }
    ++components;
  }
  return closed;
}

}  // namespace

Mesh::Mesh(TriangleSoup soup, std::string source) : Shape("mesh"), source_(std::move(source)) {
  const std::string what = source_.empty() ? std::string("mesh") : "mesh '" + source_ + "'";
  // Merge vertices at identical positions (STL and unindexed files repeat them per triangle).
  std::map<std::array<double, 3>, int> index;
  std::vector<int> remap(soup.vertices.size());
  for (std::size_t i = 0; i < soup.vertices.size(); ++i) {
    const Eigen::Vector3d& p = soup.vertices[i];
    if (!p.allFinite()) invalid_input(what + ": vertex " + std::to_string(i) + " is not finite: " + format_value(p));
    const auto [it, added] = index.try_emplace({p.x(), p.y(), p.z()}, static_cast<int>(vertices_.size()));
    if (added) vertices_.push_back(p);
    remap[i] = it->second;
  }
  const int n = static_cast<int>(soup.vertices.size());
  for (std::size_t f = 0; f < soup.triangles.size(); ++f) {
    std::array<int, 3> tri = soup.triangles[f];
    for (int& k : tri) {
      if (k < 0 || k >= n)
        invalid_input(what + ": triangle " + std::to_string(f) + " refers to vertex " + std::to_string(k) + " of " +
                      std::to_string(n));
      k = remap[static_cast<std::size_t>(k)];
    }
    const Eigen::Vector3d& a = vertices_[tri[0]];
    if ((vertices_[tri[1]] - a).cross(vertices_[tri[2]] - a).norm() > 0.0) triangles_.push_back(tri);
  }
  if (triangles_.empty()) invalid_input(what + ": no triangles (of non-zero area)");
  closed_ = orient(vertices_, triangles_);

  // Pseudo-normals: faces, edges (the sum of the two faces' normals), vertices (angle-weighted).
  const std::size_t F = triangles_.size();
  face_normal_.resize(F);
  vertex_normal_.assign(vertices_.size(), Eigen::Vector3d::Zero());
  std::unordered_map<std::uint64_t, Eigen::Vector3d> edge_sum;
  for (std::size_t f = 0; f < F; ++f) {
    const auto& tri = triangles_[f];
    const Eigen::Vector3d &a = vertices_[tri[0]], &b = vertices_[tri[1]], &c = vertices_[tri[2]];
    face_normal_[f] = (b - a).cross(c - a).normalized();
    for (int e = 0; e < 3; ++e) {
      const Eigen::Vector3d& p = vertices_[tri[e]];
      const Eigen::Vector3d u = (vertices_[tri[(e + 1) % 3]] - p).normalized(), w = (vertices_[tri[(e + 2) % 3]] - p).normalized();
      vertex_normal_[tri[e]] += std::acos(std::clamp(u.dot(w), -1.0, 1.0)) * face_normal_[f];
      auto [it, added] = edge_sum.try_emplace(edge_key(tri[e], tri[(e + 1) % 3]), Eigen::Vector3d::Zero());
      it->second += face_normal_[f];
      longest_edge_ = std::max(longest_edge_, (vertices_[tri[(e + 1) % 3]] - p).norm());
    }
  }
  for (auto& nv : vertex_normal_) nv.normalize();
  edge_normal_.resize(F);
  for (std::size_t f = 0; f < F; ++f)
    for (int i = 0; i < 3; ++i)  // the edge opposite vertex i runs from vertex i+1 to i+2
      edge_normal_[f][i] = edge_sum[edge_key(triangles_[f][(i + 1) % 3], triangles_[f][(i + 2) % 3])].normalized();
  bounds_.lower = bounds_.upper = vertices_.front();
  for (const auto& p : vertices_) {
    bounds_.lower = bounds_.lower.cwiseMin(p);
    bounds_.upper = bounds_.upper.cwiseMax(p);
  }

  tree_ = std::make_unique<Tree>();
  tree_->triangles.reserve(F);
  for (const auto& tri : triangles_) {
    auto P = [&](int k) { return Tree::K::Point_3(vertices_[k].x(), vertices_[k].y(), vertices_[k].z()); };
    tree_->triangles.emplace_back(P(tri[0]), P(tri[1]), P(tri[2]));
  }
  tree_->tree.insert(tree_->triangles.cbegin(), tree_->triangles.cend());
  tree_->tree.build();
  tree_->tree.accelerate_distance_queries();
  // The first query builds the search structure: done here, so that concurrent queries only read.
  (void)tree_->tree.closest_point(Tree::K::Point_3(vertices_[0].x(), vertices_[0].y(), vertices_[0].z()));
}

Mesh::~Mesh() = default;

SurfacePoint Mesh::nearest(const Eigen::Vector3d& p) const {
  const auto hit = tree_->tree.closest_point_and_primitive(Tree::K::Point_3(p.x(), p.y(), p.z()));
  return on_triangle(p, Eigen::Vector3d(hit.first.x(), hit.first.y(), hit.first.z()),
                     static_cast<std::size_t>(hit.second - tree_->triangles.cbegin()));
}

SurfacePoint Mesh::on_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& q, std::size_t f) const {
  const auto& tri = triangles_[f];
  const Eigen::Vector3d &a = vertices_[tri[0]], &b = vertices_[tri[1]], &c = vertices_[tri[2]];
  // Barycentric coordinates of q: which feature of the triangle holds it.
  const Eigen::Vector3d n = (b - a).cross(c - a);
  const double area2 = n.squaredNorm();
  const std::array<double, 3> lambda = {(c - b).cross(q - b).dot(n) / area2, (a - c).cross(q - c).dot(n) / area2,
                                        (b - a).cross(q - a).dot(n) / area2};
  constexpr double on_feature = 1e-10;
  int zeros = 0, nonzero = 0, zero = 0;
  for (int i = 0; i < 3; ++i) {
    if (lambda[i] <= on_feature) {
      ++zeros;
      zero = i;
    } else {
      nonzero = i;
    }
  }
  const int code = zeros == 0 ? 0 : zeros == 1 ? 1 + zero : 4 + nonzero;
  return feature_point(p, q, f, code);
}

// A solve's queries gather about its contacts: the triangles near each place, gathered once from the tree (a box
// query about the first point asked there within the margin of the surface, reaching twice the margin farther),
// answer them with a loop over about a hundred; a query
// whose nearest candidate is farther than its box's boundary (a triangle outside the box might be nearer) goes to
// the tree. Every answer is the nearest triangle's, as the tree's; among triangles at the same distance (a shared
// edge or vertex: the same feature and normal) the candidates take the first in the mesh's order, the tree the
// first it visits: feature_id may name the other triangle of the same edge.
class Mesh::Neighbourhood final : public Shape {
 public:
  Neighbourhood(const Mesh& mesh, double margin) : Shape("mesh"), mesh_(mesh), margin_(margin) {}
  [[nodiscard]] SurfacePoint nearest(const Eigen::Vector3d& p) const override {
    if (asked_ && p == last_p_) return last_;  // the checks ask at the same points again
    last_ = answer(p);
    last_p_ = p;
    asked_ = true;
    return last_;
  }
  [[nodiscard]] SurfacePoint nearest_on_feature(const Eigen::Vector3d& p, std::int64_t feature_id) const override {
    return mesh_.nearest_on_feature(p, feature_id);
  }
  [[nodiscard]] Bounds bounds() const override { return mesh_.bounds(); }
  [[nodiscard]] bool needs_thickness() const override { return true; }
  [[nodiscard]] ShapeDescription describe() const override { return mesh_.describe(); }

 private:
  /// Places a solve gathers triangles about (a contact, a second contact, the steps of a continuation); beyond
  /// them the tree answers.
  static constexpr std::size_t max_regions = 16;
  struct Candidate {
    Eigen::Vector3d centre;  // of a sphere holding the triangle
    double radius;
    std::size_t f;
  };
  struct Region {
    Eigen::Vector3d lower, upper;  // the box: every triangle meeting it is a candidate
    std::vector<Candidate> candidates;  // in the mesh's order
    std::size_t hint = 0;  // the candidate nearest to the last point answered here
  };

  [[nodiscard]] SurfacePoint from_tree(const Eigen::Vector3d& p, double& distance) const {
    const auto hit = mesh_.tree_->tree.closest_point_and_primitive(Tree::K::Point_3(p.x(), p.y(), p.z()));
    const Eigen::Vector3d q(hit.first.x(), hit.first.y(), hit.first.z());
    distance = (p - q).norm();
    return mesh_.on_triangle(p, q, static_cast<std::size_t>(hit.second - mesh_.tree_->triangles.cbegin()));
  }

  /// The box [p - h, p + h] (h: p's distance to the surface and twice the margin) and the triangles meeting it.
  void gather(const Eigen::Vector3d& p, double distance) const {
    Region r;
    const double h = distance + 2.0 * margin_;
    r.lower = p.array() - h;
    r.upper = p.array() + h;
    std::vector<Tree::Triangles::const_iterator> hits;
    mesh_.tree_->tree.all_intersected_primitives(
        CGAL::Bbox_3(r.lower.x(), r.lower.y(), r.lower.z(), r.upper.x(), r.upper.y(), r.upper.z()),
        std::back_inserter(hits));
    for (const auto& it : hits) {
      const auto f = static_cast<std::size_t>(it - mesh_.tree_->triangles.cbegin());
      const auto& tri = mesh_.triangles_[f];
      const Eigen::Vector3d centre = (mesh_.vertices_[tri[0]] + mesh_.vertices_[tri[1]] + mesh_.vertices_[tri[2]]) / 3.0;
      double radius = 0.0;
      for (int k : tri) radius = std::max(radius, (mesh_.vertices_[k] - centre).norm());
      r.candidates.push_back({centre, radius * (1.0 + 1e-12), f});
    }
    std::sort(r.candidates.begin(), r.candidates.end(), [](const Candidate& a, const Candidate& b) { return a.f < b.f; });
    last_region_ = regions_.size();
    regions_.push_back(std::move(r));
  }

  /// The answer from region r's candidates, if no triangle outside it can be nearer.
  [[nodiscard]] std::optional<SurfacePoint> from_region(const Eigen::Vector3d& p, Region& r) const {
    // How far p is inside the box: no triangle outside it is nearer than that.
    const double room = std::min((p - r.lower).minCoeff(), (r.upper - p).minCoeff());
    if (!(room > 0.0) || r.candidates.empty()) return std::nullopt;
    const Tree::K::Point_3 point(p.x(), p.y(), p.z());
    const Tree::K::Construct_projected_point_3 project;
    double best2 = std::numeric_limits<double>::infinity(), best = best2;
    std::size_t best_at = 0;
    Tree::K::Point_3 best_q(0.0, 0.0, 0.0);
    auto consider = [&](std::size_t k) {
      const Candidate& c = r.candidates[k];
      const double reach = best + c.radius;
      if ((p - c.centre).squaredNorm() > reach * reach) return;
      const Tree::K::Point_3 q = project(mesh_.tree_->triangles[c.f], point);
      const double d2 = CGAL::squared_distance(point, q);
      if (d2 < best2 || (d2 == best2 && k < best_at)) {
        best2 = d2;
        best = std::sqrt(d2);
        best_at = k;
        best_q = q;
      }
    };
    consider(std::min(r.hint, r.candidates.size() - 1));  // usually the nearest: it culls the rest
    for (std::size_t k = 0; k < r.candidates.size(); ++k) consider(k);
    if (!(best <= room)) return std::nullopt;
    r.hint = best_at;
    return mesh_.on_triangle(p, Eigen::Vector3d(best_q.x(), best_q.y(), best_q.z()), r.candidates[best_at].f);
  }

  [[nodiscard]] SurfacePoint answer(const Eigen::Vector3d& p) const {
    if (last_region_ < regions_.size())
      if (auto q = from_region(p, regions_[last_region_])) return *q;
    for (std::size_t k = 0; k < regions_.size(); ++k) {
      if (k == last_region_) continue;
      if (auto q = from_region(p, regions_[k])) {
        last_region_ = k;
        return *q;
      }
    }
    double distance = 0.0;
    SurfacePoint q = from_tree(p, distance);
    if (distance <= margin_ && regions_.size() < max_regions) gather(p, distance);
    return q;
  }

  const Mesh& mesh_;
  double margin_;
  mutable std::vector<Region> regions_;
  mutable std::size_t last_region_ = 0;
  mutable bool asked_ = false;
  mutable Eigen::Vector3d last_p_ = Eigen::Vector3d::Zero();
  mutable SurfacePoint last_;
};

std::unique_ptr<const Shape> Mesh::local_view(double margin) const {
  return std::make_unique<Neighbourhood>(*this, margin);
}

SurfacePoint Mesh::feature_point(const Eigen::Vector3d& p, const Eigen::Vector3d& q, std::size_t f, int code) const {
  const auto& tri = triangles_[f];
  Eigen::Vector3d pseudo;
  Eigen::Matrix3d J;
  SurfaceFeature feature;
  Eigen::Vector3d direction = Eigen::Vector3d::Zero();
  if (code == 0) {
    feature = SurfaceFeature::face;
    pseudo = face_normal_[f];
    J = Eigen::Matrix3d::Identity() - pseudo * pseudo.transpose();
  } else if (code < 4) {
    const int i = code - 1;
    feature = SurfaceFeature::edge;
    pseudo = edge_normal_[f][static_cast<std::size_t>(i)];
    direction = (vertices_[tri[(i + 2) % 3]] - vertices_[tri[(i + 1) % 3]]).normalized();
    J = direction * direction.transpose();
  } else {
    feature = SurfaceFeature::vertex;
    pseudo = vertex_normal_[tri[code - 4]];
    J.setZero();
  }
  const double sign = (p - q).dot(pseudo) >= 0.0 ? 1.0 : -1.0;
  SurfacePoint s = detail::surface_point(p, q, J, sign, pseudo, feature);
  s.edge_direction = direction;
  s.feature_id = static_cast<std::int64_t>(8 * f) + code;
  return s;
}

SurfacePoint Mesh::nearest_on_feature(const Eigen::Vector3d& p, std::int64_t feature_id) const {
  const auto f = static_cast<std::size_t>(feature_id / 8);
  const int code = static_cast<int>(feature_id % 8);
  if (feature_id < 0 || f >= triangles_.size() || code > 6) return nearest(p);
  const auto& tri = triangles_[f];
  Eigen::Vector3d q;
  if (code == 0) {
    const Eigen::Vector3d& n = face_normal_[f];
    q = p - (p - vertices_[tri[0]]).dot(n) * n;
  } else if (code < 4) {
    const Eigen::Vector3d& a = vertices_[tri[code % 3]];
    const Eigen::Vector3d d = (vertices_[tri[(code + 1) % 3]] - a).normalized();
    q = a + (p - a).dot(d) * d;
  } else {
    q = vertices_[tri[code - 4]];
  }
  return feature_point(p, q, f, code);
}

ShapeDescription Mesh::describe() const {
  ShapeDescription d{"mesh",
                     {{"vertex_count", {static_cast<double>(vertices_.size())}},
                      {"triangle_count", {static_cast<double>(triangles_.size())}},
                      {"bounds_lower", detail::values_of(bounds_.lower)},
                      {"bounds_upper", detail::values_of(bounds_.upper)},
                      {"closed", {closed_ ? 1.0 : 0.0}}},
                     source_};
  return d;
}

TriangleSoup tessellated_sphere(const Eigen::Vector3d& centre, double radius, int subdivisions) {
  TriangleSoup s;
  const double g = (1.0 + std::sqrt(5.0)) / 2.0;
  for (const auto& p : std::vector<Eigen::Vector3d>{{-1, g, 0}, {1, g, 0}, {-1, -g, 0}, {1, -g, 0}, {0, -1, g}, {0, 1, g},
                                                    {0, -1, -g}, {0, 1, -g}, {g, 0, -1}, {g, 0, 1}, {-g, 0, -1}, {-g, 0, 1}})
    s.vertices.push_back(p.normalized());
  s.triangles = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                 {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
                 {3, 8, 9},  {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  for (int level = 0; level < subdivisions; ++level) {
    std::map<std::uint64_t, int> middle;
    auto mid = [&](int a, int b) {
      const auto [it, added] = middle.try_emplace(edge_key(a, b), static_cast<int>(s.vertices.size()));
      if (added) s.vertices.push_back((s.vertices[a] + s.vertices[b]).normalized());
      return it->second;
    };
    std::vector<std::array<int, 3>> next;
    for (const auto& t : s.triangles) {
      const int ab = mid(t[0], t[1]), bc = mid(t[1], t[2]), ca = mid(t[2], t[0]);
      next.insert(next.end(), {{t[0], ab, ca}, {t[1], bc, ab}, {t[2], ca, bc}, {ab, bc, ca}});
    }
    s.triangles = std::move(next);
  }
  for (auto& p : s.vertices) p = centre + radius * p;
  return s;
}

TriangleSoup tessellated_cylinder(const Eigen::Vector3d& base, double radius, double length, int segments, int rings) {
  TriangleSoup s;
  for (int r = 0; r <= rings; ++r)
    for (int k = 0; k < segments; ++k) {
      const double a = 2.0 * std::numbers::pi * k / segments;
      s.vertices.push_back(base + Eigen::Vector3d(radius * std::cos(a), radius * std::sin(a), length * r / rings));
    }
  auto at = [&](int r, int k) { return r * segments + (k % segments); };
  for (int r = 0; r < rings; ++r)
    for (int k = 0; k < segments; ++k) {
      s.triangles.push_back({at(r, k), at(r, k + 1), at(r + 1, k + 1)});
      s.triangles.push_back({at(r, k), at(r + 1, k + 1), at(r + 1, k)});
    }
  const int bottom = static_cast<int>(s.vertices.size());
  s.vertices.push_back(base);
  s.vertices.push_back(base + Eigen::Vector3d(0, 0, length));
  for (int k = 0; k < segments; ++k) {
    s.triangles.push_back({bottom, at(0, k + 1), at(0, k)});
    s.triangles.push_back({bottom + 1, at(rings, k), at(rings, k + 1)});
  }
  return s;
}

}  // namespace vibrissa
