#pragma once
// Objects the array whisks against (issue 5 item 3): straight edges (infinite or finite), a peg (a line
// along the frame's z axis through a point) and a triangular prism (its three long edges; the whisker meets
// whichever edge it reaches, as in Supplementary Video 1). Each object is fixed in the world or moves with
// the head. Edge mode (spec §2.1) touches lines only, so an object is the set of its edges.
#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include <memory>

#include "vibrissa/array/head.hpp"
#include "vibrissa/contact/edge_segment.hpp"
#include "vibrissa/objects/shape.hpp"

namespace vibrissa::array {

enum class ObjectFrame { world, head };
std::string_view to_string(ObjectFrame frame);
ObjectFrame object_frame_from_string(std::string_view name, const char* field);

struct SceneObject {
  std::string kind;  ///< "edge", "peg" or "prism"; or a surface: "cylinder", "plane", "sphere", "box", "mesh"
  ObjectFrame frame = ObjectFrame::world;
  std::vector<EdgeSegment> edges;  ///< in `frame` (edge kinds)
  std::shared_ptr<const Shape> shape;  ///< surfaces (docs/objects.md), parameters in `frame`
};

/// Whether the scene's objects are surfaces (object modes) rather than edges; a scene is one or the other.
bool scene_of_surfaces(const std::vector<SceneObject>& objects);
/// Every surface where it is for a head pose (world objects as given, head objects moved with the head).
std::vector<PlacedShape> shapes_in_world(const std::vector<SceneObject>& objects, const HeadPose& head);

/// A straight edge through `point` along `direction` (normalised here); infinite unless `length` is finite,
/// in which case it runs from `point` for `length`. Throws for a zero direction or a non-positive length.
SceneObject make_edge(const Eigen::Vector3d& point, const Eigen::Vector3d& direction, double length,
                      ObjectFrame frame, const std::string& field = "objects[0]");
/// A peg: the line along the frame's z axis through `point`, infinite or `height` long upward from `point`.
SceneObject make_peg(const Eigen::Vector3d& point, double height, ObjectFrame frame,
                     const std::string& field = "objects[0]");
/// A triangular prism with cross-section vertices `vertices` extruded `length` along `axis` from them.
SceneObject make_prism(const std::vector<Eigen::Vector3d>& vertices, const Eigen::Vector3d& axis, double length,
                       ObjectFrame frame, const std::string& field = "objects[0]");

/// All edges of all objects in world coordinates for a head pose, in object order.
std::vector<EdgeSegment> edges_in_world(const std::vector<SceneObject>& objects, const HeadPose& head);

}  // namespace vibrissa::array
