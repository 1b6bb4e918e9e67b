#include "vibrissa/array/objects.hpp"

#include <cmath>

#include <Eigen/Geometry>

#include "array_util.hpp"

namespace vibrissa::array {
namespace {

std::string vec_mm(const Eigen::Vector3d& v) {
  return std::string("[") + fmt(v.x() * 1e3) + ", " + fmt(v.y() * 1e3) + ", " + fmt(v.z() * 1e3) + "]";
}

void check_point(const Eigen::Vector3d& p, const std::string& field) {
  if (!p.allFinite()) fail(field + " must be finite, got " + vec_mm(p) + " mm");
}

// Any unit vector normal to the unit vector d (deterministic).
Eigen::Vector3d normal_to(const Eigen::Vector3d& d) {
  const Eigen::Vector3d helper = std::abs(d.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  return (helper - helper.dot(d) * d).normalized();
}

EdgeSegment segment(const Eigen::Vector3d& p0, const Eigen::Vector3d& d, double length) {
  return EdgeSegment{p0, d, length, normal_to(d)};
}

void check_length(double length, const std::string& field) {
  if (std::isnan(length) || !(length > 0.0))
    fail(field + " must be positive (omit it for an infinite edge), got " + fmt(length * 1e3) + " mm");
}

}  // namespace

std::string_view to_string(ObjectFrame frame) { return frame == ObjectFrame::world ? "world" : "head"; }

ObjectFrame object_frame_from_string(std::string_view name, const char* field) {
  if (name == "world") return ObjectFrame::world;
  if (name == "head") return ObjectFrame::head;
  fail(std::string(field) + " must be 'world' or 'head', got '" + std::string(name) + "'");
}

SceneObject make_edge(const Eigen::Vector3d& point, const Eigen::Vector3d& direction, double length,
                      ObjectFrame frame, const std::string& field) {
  check_point(point, field + ".point_mm");
  check_length(length, field + ".length_mm");
  SceneObject o{"edge", frame, {segment(point, vibrissa::unit_direction(direction, field + ".direction"), length)}, nullptr};
  return o;
}

SceneObject make_peg(const Eigen::Vector3d& point, double height, ObjectFrame frame, const std::string& field) {
  check_point(point, field + ".point_mm");
  check_length(height, field + ".height_mm");
  return SceneObject{"peg", frame, {segment(point, Eigen::Vector3d::UnitZ(), height)}, nullptr};
}

SceneObject make_prism(const std::vector<Eigen::Vector3d>& vertices, const Eigen::Vector3d& axis, double length,
                       ObjectFrame frame, const std::string& field) {
  if (vertices.size() != 3)
    fail(field + ".vertices_mm must hold 3 points, got " + std::to_string(vertices.size()));
  for (std::size_t i = 0; i < 3; ++i) check_point(vertices[i], field + ".vertices_mm[" + std::to_string(i) + "]");
  const Eigen::Vector3d d = vibrissa::unit_direction(axis, field + ".axis");
  check_length(length, field + ".length_mm");
  const Eigen::Vector3d n = (vertices[1] - vertices[0]).cross(vertices[2] - vertices[0]);
  if (n.norm() < 1e-12) fail(field + ".vertices_mm must span a triangle, but the 3 points are collinear");
  if (std::abs(n.normalized().dot(d)) < 1e-6)
    fail(field + ".axis must not lie in the plane of the cross-section");
  SceneObject o{"prism", frame, {}, nullptr};
  for (const Eigen::Vector3d& v : vertices) o.edges.push_back(segment(v, d, length));
  return o;
}

bool scene_of_surfaces(const std::vector<SceneObject>& objects) {
  bool surfaces = false, edges = false;
  for (const SceneObject& o : objects) (o.shape ? surfaces : edges) = true;
  if (surfaces && edges)
    fail("objects: a scene holds edges (peg, edge, prism) or surfaces (cylinder, plane, sphere, box, mesh), not "
         "both (a peg is a cylinder of radius 0)");
  return surfaces;
}

std::vector<PlacedShape> shapes_in_world(const std::vector<SceneObject>& objects, const HeadPose& head) {
  std::vector<PlacedShape> out;
  for (const SceneObject& o : objects) {
    if (!o.shape) continue;
    PlacedShape p{o.shape.get(), {}};
    if (o.frame == ObjectFrame::head) p.X_WO = ObjectPose{head.R_WH, head.p_W_head};
    out.push_back(p);
  }
  return out;
}

std::vector<EdgeSegment> edges_in_world(const std::vector<SceneObject>& objects, const HeadPose& head) {
  std::vector<EdgeSegment> out;
  for (const SceneObject& o : objects) {
    for (const EdgeSegment& e : o.edges) {
      if (o.frame == ObjectFrame::world) {
        out.push_back(e);
      } else {
        out.push_back(EdgeSegment{head.point_to_world(e.p0), head.vector_to_world(e.direction), e.length,
                                  head.vector_to_world(e.normal)});
      }
    }
  }
  return out;
}

}  // namespace vibrissa::array
