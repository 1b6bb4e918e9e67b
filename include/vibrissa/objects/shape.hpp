#pragma once
// Objects are geometry (docs/objects.md): each shape is a small class behind one query interface, so that the
// solvers ask "where is the surface" and never "which kind of object is this". A Shape is immutable and defined
// in its own frame O (for most shapes O is the frame its parameters were given in: the world, or the head);
// where it is at a frame is an ObjectPose (R_WO, p_WO), a small value, as a Whisker and its Placement.
//
// The query: for a point p, the nearest point of the surface, the signed distance (> 0 outside), the unit
// normal n = grad(signed distance) at p (outward; (p - closest)/|p - closest| off the surface), and its
// derivative dn/dp (the Hessian of the signed distance), which the solvers' exact Jacobians need:
//   on a face            dn/dp = curvature of the distance field (0 for a flat face)
//   near an edge         (I - n n^T - d d^T) / |p - closest|       (the offset surface of an edge is a cylinder)
//   near a vertex        (I - n n^T) / |p - closest|               (... of a vertex, a sphere)
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <Eigen/Core>

namespace vibrissa {

/// Which part of a surface is nearest to a query point (the same codes in every file).
enum class SurfaceFeature : std::int8_t {
  face = 0,    ///< a smooth part of the surface (a plane, a sphere, a cylinder's side, a mesh triangle's interior)
  edge = 1,    ///< a crease: a box or mesh edge, a capped cylinder's rim
  vertex = 2,  ///< a corner of a box or mesh
};
std::string_view to_string(SurfaceFeature feature);

/// The answer to a query at a point p (all in the frame the query was asked in).
struct SurfacePoint {
  Eigen::Vector3d closest = Eigen::Vector3d::Zero();  ///< nearest point of the surface [m]
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  ///< unit gradient of the signed distance at p (outward)
  double signed_distance = 0.0;                       ///< [m], > 0 outside, < 0 inside
  Eigen::Matrix3d normal_derivative = Eigen::Matrix3d::Zero();  ///< d normal / d p [1/m] (symmetric)
  SurfaceFeature feature = SurfaceFeature::face;
  Eigen::Vector3d edge_direction = Eigen::Vector3d::Zero();  ///< unit tangent of the nearest edge (edges only)
  /// Which face, edge or vertex of a shape with creases is nearest (shape-specific; -1: a smooth shape), for
  /// Shape::nearest_on_feature.
  std::int64_t feature_id = -1;
};

/// Axis-aligned bounds (infinite for unbounded shapes) [m].
struct Bounds {
  Eigen::Vector3d lower = Eigen::Vector3d::Constant(-std::numeric_limits<double>::infinity());
  Eigen::Vector3d upper = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  /// Distance from p to the box (0 inside it).
  [[nodiscard]] double distance(const Eigen::Vector3d& p) const;
};

/// A surface made of the points at `radius` from an infinite line (a peg with a radius): the solvers write its
/// contact in the line's own terms, which stay regular as the radius (with the whisker's) goes to zero, where
/// the contact becomes edge mode's.
struct LineCore {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  Eigen::Vector3d direction = Eigen::Vector3d::UnitZ();  ///< unit
  double radius = 0.0;                                   ///< [m]
};

/// What an output records of a shape, so that a viewer or a figure can draw it again: the type and its
/// parameters in SI units in the shape's frame (a mesh: its file, and vertices and triangles are available from
/// Mesh itself).
struct ShapeDescription {
  std::string type;  ///< "plane", "sphere", "cylinder", "box", "mesh"
  std::vector<std::pair<std::string, std::vector<double>>> values;  ///< name -> numbers (SI; vectors as 3 numbers)
  std::string file;  ///< mesh: the file it was read from
};

/// A rigid transform from the shape's frame O to the world: where the shape is at a frame.
struct ObjectPose {
  Eigen::Matrix3d R_WO = Eigen::Matrix3d::Identity();  ///< columns: O's axes in W
  Eigen::Vector3d p_WO = Eigen::Vector3d::Zero();      ///< O's origin in W [m]
  [[nodiscard]] Eigen::Vector3d to_world(const Eigen::Vector3d& p_O) const { return p_WO + R_WO * p_O; }
  [[nodiscard]] Eigen::Vector3d to_object(const Eigen::Vector3d& p_W) const { return R_WO.transpose() * (p_W - p_WO); }
};

class Shape {
 public:
  virtual ~Shape() = default;
  Shape(const Shape&) = delete;
  Shape& operator=(const Shape&) = delete;

  /// The query at p (shape frame). Defined everywhere: on a degenerate point (the centre of a sphere, the axis
  /// of a cylinder) the normal is a fixed choice and the derivative is zero.
  [[nodiscard]] virtual SurfacePoint nearest(const Eigen::Vector3d& p) const = 0;
  /// The query against one feature of an earlier answer (its `feature_id`) continued as a smooth surface: a
  /// face's plane, an edge's line, a vertex's point. It equals nearest(p) wherever that feature is nearest, and
  /// is smooth where nearest() turns from one feature to the next: the object solves hold a feature while
  /// Newton converges and then check it (docs/objects.md, "Solver"). Smooth shapes (feature_id -1): nearest().
  [[nodiscard]] virtual SurfacePoint nearest_on_feature(const Eigen::Vector3d& p, std::int64_t feature_id) const {
    (void)feature_id;
    return nearest(p);
  }
  /// Signed distance alone (the same number as nearest().signed_distance; shapes may answer it faster).
  [[nodiscard]] virtual double signed_distance(const Eigen::Vector3d& p) const { return nearest(p).signed_distance; }
  [[nodiscard]] virtual Bounds bounds() const = 0;
  /// A view of this shape for one solve's queries, which gather about one place (the contact): it answers every
  /// query as this shape does, faster there (a mesh: from the triangles its tree finds about each place asked within
  /// `margin` [m] of the surface; docs/objects.md, "Speed"). It keeps state between queries: one
  /// view per solve and thread. nullptr: the shape's own queries are as fast.
  [[nodiscard]] virtual std::unique_ptr<const Shape> local_view(double margin) const {
    (void)margin;
    return nullptr;
  }
  /// A line core (an infinite cylinder), else nullopt.
  [[nodiscard]] virtual std::optional<LineCore> line_core() const { return std::nullopt; }
  /// Whether contacts need the whisker's thickness: shapes with edges and corners (box, mesh), whose normal is
  /// not defined where a centre line would touch them.
  [[nodiscard]] virtual bool needs_thickness() const { return false; }
  [[nodiscard]] virtual ShapeDescription describe() const = 0;
  [[nodiscard]] std::string_view type() const { return type_; }

 protected:
  explicit Shape(std::string_view type) : type_(type) {}

 private:
  std::string_view type_;
};

/// A shape where it is: queries in the world frame.
struct PlacedShape {
  const Shape* shape = nullptr;
  ObjectPose X_WO;
  [[nodiscard]] SurfacePoint nearest_W(const Eigen::Vector3d& p_W) const;
  [[nodiscard]] double signed_distance_W(const Eigen::Vector3d& p_W) const {
    return shape->signed_distance(X_WO.to_object(p_W));
  }
  /// Lower bound of the distance from p_W to the shape (bounding box).
  [[nodiscard]] double bound_distance_W(const Eigen::Vector3d& p_W) const {
    return shape->bounds().distance(X_WO.to_object(p_W));
  }
};

/// A SurfacePoint in frame O turned into the world frame.
SurfacePoint to_world(const SurfacePoint& q_O, const ObjectPose& X_WO);

}  // namespace vibrissa
