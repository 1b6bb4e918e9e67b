#pragma once
// A triangle mesh (docs/objects.md): closest points through CGAL's AABB tree (libcgal-dev), the sign of the
// distance from the angle-weighted pseudo-normal of the nearest feature (Baerentzen & Aanaes 2005: exact for a
// closed, consistently oriented mesh), files read with assimp (libassimp-dev): OBJ, STL, PLY and whatever else
// assimp reads. A closed mesh is oriented outward when read; an open one keeps its orientation (the outside is
// the side its triangles' normals point to). Contacts with a mesh need the whisker's thickness: its edges and
// vertices are touched by the whisker's surface, never by its centre line.
#include <array>
#include <memory>
#include <string>
#include <vector>

#include "vibrissa/objects/shape.hpp"

namespace vibrissa {

/// Vertices [m] and triangles (indices into the vertices, counter-clockwise seen from outside).
struct TriangleSoup {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<std::array<int, 3>> triangles;
};

class Mesh final : public Shape {
 public:
  /// Throws std::invalid_argument naming `source` for no triangles, indices out of range or non-finite vertices.
  /// Degenerate (zero-area) triangles are dropped; vertices at identical positions are merged.
  explicit Mesh(TriangleSoup soup, std::string source = "");
  ~Mesh() override;

  /// Reads a mesh file with assimp; coordinates times `scale` are metres (0.001 for a file in mm), then turned by
  /// `pose` (the mesh's placement in its frame). Throws std::invalid_argument naming the file.
  static std::shared_ptr<const Mesh> from_file(const std::string& path, double scale = 1.0,
                                               const ObjectPose& pose = {});

  [[nodiscard]] SurfacePoint nearest(const Eigen::Vector3d& p) const override;
  /// feature_id = 8 * triangle + code: code 0 the face, 1 + i the edge opposite its vertex i, 4 + i vertex i.
  [[nodiscard]] SurfacePoint nearest_on_feature(const Eigen::Vector3d& p, std::int64_t feature_id) const override;
  [[nodiscard]] Bounds bounds() const override { return bounds_; }
  [[nodiscard]] bool needs_thickness() const override { return true; }
  [[nodiscard]] ShapeDescription describe() const override;
  /// About each place the solve asks within `margin` of the surface (up to 16), the triangles within about three
  /// margins (one search of the tree); each later query answered from them where none of the others can be nearer,
  /// else from the tree: the same answers.
  [[nodiscard]] std::unique_ptr<const Shape> local_view(double margin) const override;

  [[nodiscard]] const std::vector<Eigen::Vector3d>& vertices() const { return vertices_; }
  [[nodiscard]] const std::vector<std::array<int, 3>>& triangles() const { return triangles_; }
  /// Every edge shared by exactly two triangles (a watertight surface).
  [[nodiscard]] bool closed() const { return closed_; }
  /// Longest edge [m] (the tessellation's resolution).
  [[nodiscard]] double longest_edge() const { return longest_edge_; }
  [[nodiscard]] const std::string& source() const { return source_; }

 private:
  struct Tree;
  class Neighbourhood;
  /// The query at p whose nearest point q lies on triangle f (its feature from q's barycentric coordinates).
  [[nodiscard]] SurfacePoint on_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& q, std::size_t f) const;
  /// The query at p of feature `code` of triangle f continued as a plane, line or point (q: its nearest point).
  [[nodiscard]] SurfacePoint feature_point(const Eigen::Vector3d& p, const Eigen::Vector3d& q, std::size_t f,
                                           int code) const;
  std::vector<Eigen::Vector3d> vertices_;
  std::vector<std::array<int, 3>> triangles_;
  std::vector<Eigen::Vector3d> face_normal_;              // unit
  std::vector<std::array<Eigen::Vector3d, 3>> edge_normal_;  // per triangle, edge opposite vertex i: pseudo-normal
  std::vector<Eigen::Vector3d> vertex_normal_;            // angle-weighted pseudo-normals
  Bounds bounds_;
  bool closed_ = false;
  double longest_edge_ = 0.0;
  std::string source_;
  std::unique_ptr<Tree> tree_;
};

/// A sphere tessellated from an icosahedron subdivided `subdivisions` times (20 * 4^n triangles), vertices on
/// the sphere.
TriangleSoup tessellated_sphere(const Eigen::Vector3d& centre, double radius, int subdivisions);
/// A capped cylinder along +z from `base`, `segments` around and `rings` along, vertices on the surface.
TriangleSoup tessellated_cylinder(const Eigen::Vector3d& base, double radius, double length, int segments, int rings);

}  // namespace vibrissa
