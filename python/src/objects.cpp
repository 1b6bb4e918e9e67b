// Objects from Python (docs/objects.md, docs/python.md "Objects"): the shapes, their query, and the object
// solves. vibrissa.Cylinder(...), Plane, Sphere, Box, Mesh(vertices, triangles) and Mesh.from_file(...).
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <limits>
#include <memory>

#include "bindings.hpp"
#include "convert.hpp"
#include "vibrissa/io/object_json.hpp"
#include "vibrissa/objects/box.hpp"
#include "vibrissa/objects/cylinder.hpp"
#include "vibrissa/objects/mesh.hpp"
#include "vibrissa/objects/plane.hpp"
#include "vibrissa/objects/sphere.hpp"
#include "vibrissa/solve/object_contact.hpp"
#include "vibrissa/trial/format.hpp"

namespace vibrissa::python {

namespace {

Eigen::Matrix3d matrix3_arg(const py::object& obj, const char* name) {
  if (obj.is_none()) return Eigen::Matrix3d::Identity();
  const auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(obj);
  if (!a || a.ndim() != 2 || a.shape(0) != 3 || a.shape(1) != 3)
    throw py::value_error(std::string(name) + " must be a 3x3 array");
  Eigen::Matrix3d R;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) R(i, j) = a.at(i, j);
  return R;
}

ObjectPose object_pose_arg(const py::object& position, const py::object& rotation) {
  ObjectPose X;
  if (!position.is_none()) X.p_WO = vec3(position, "object_position");
  X.R_WO = matrix3_arg(rotation, "object_rotation");
  require_rotation(X.R_WO, "object_rotation");
  return X;
}

py::dict point_dict(const SurfacePoint& q) {
  py::dict d;
  d["closest"] = to_array(q.closest);
  d["normal"] = to_array(q.normal);
  d["signed_distance"] = q.signed_distance;
  d["normal_derivative"] = to_array(q.normal_derivative);
  d["feature"] = std::string(to_string(q.feature));
  d["edge_direction"] = to_array(q.edge_direction);
  return d;
}

}  // namespace

void bind_objects(py::module_& m) {
  py::class_<Shape, std::shared_ptr<Shape>>(
      m, "Shape", "An object's geometry (docs/objects.md): query it with nearest() and signed_distance(); solve against "
                  "it with solve_object().")
      .def("nearest", [](const Shape& s, const py::object& p) { return point_dict(s.nearest(vec3(p, "p"))); },
           py::arg("p"),
           "The query at point p (the shape's frame, [m]): a dict with closest, normal (outward unit gradient of the "
           "signed distance), signed_distance [m] (> 0 outside), normal_derivative (3x3, d normal / d p [1/m]), "
           "feature ('face', 'edge', 'vertex') and edge_direction.")
      .def("signed_distance", [](const Shape& s, const py::object& p) { return s.signed_distance(vec3(p, "p")); },
           py::arg("p"), "Signed distance of p [m] (> 0 outside).")
      .def_property_readonly("type", [](const Shape& s) { return std::string(s.type()); })
      .def(
          "describe",
          [](const Shape& s) { return py::module_::import("json").attr("loads")(io::shape_to_json(s).dump()); },
          "The description outputs record (a dict, SI units; docs/formats.md, \"Objects\").");
  py::class_<Cylinder, Shape, std::shared_ptr<Cylinder>>(m, "Cylinder", "A peg with a radius (docs/objects.md).")
      .def(py::init([](const py::object& point, const py::object& axis, double radius, double length) {
             return std::make_shared<Cylinder>(vec3(point, "object.point"), vec3(axis, "object.axis"), radius, length);
           }),
           py::arg("point"), py::arg("axis"), py::arg("radius"),
           py::arg("length") = std::numeric_limits<double>::infinity(),
           "Cylinder(point, axis, radius, length=inf): the points at `radius` [m] from the axis through `point` "
           "along `axis`; finite (flat caps) from `point` for `length` [m].");
  py::class_<Plane, Shape, std::shared_ptr<Plane>>(m, "Plane", "A wall: outside is where the normal points.")
      .def(py::init([](const py::object& point, const py::object& normal) {
             return std::make_shared<Plane>(vec3(point, "object.point"), vec3(normal, "object.normal"));
           }),
           py::arg("point"), py::arg("normal"));
  py::class_<Sphere, Shape, std::shared_ptr<Sphere>>(m, "Sphere", "A sphere.")
      .def(py::init([](const py::object& centre, double radius) {
             return std::make_shared<Sphere>(vec3(centre, "object.centre"), radius);
           }),
           py::arg("centre"), py::arg("radius"));
  py::class_<Box, Shape, std::shared_ptr<Box>>(m, "Box", "A box: centre, half extents, rotation (its axes as columns).")
      .def(py::init([](const py::object& centre, const py::object& half_extents, const py::object& rotation) {
             return std::make_shared<Box>(vec3(centre, "object.centre"), vec3(half_extents, "object.half_extents"),
                                          matrix3_arg(rotation, "object.rotation"));
           }),
           py::arg("centre"), py::arg("half_extents"), py::arg("rotation") = py::none());
  py::class_<Mesh, Shape, std::shared_ptr<Mesh>>(
      m, "Mesh", "A triangle mesh (CGAL's AABB tree; files through assimp: OBJ, STL, PLY). Needs the whisker's thickness.")
      .def(py::init([](const py::object& vertices, const py::object& triangles) {
             const auto v = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(vertices);
             const auto t = py::array_t<long, py::array::c_style | py::array::forcecast>::ensure(triangles);
             if (!v || v.ndim() != 2 || v.shape(1) != 3) throw py::value_error("vertices must have shape (n, 3)");
             if (!t || t.ndim() != 2 || t.shape(1) != 3) throw py::value_error("triangles must have shape (m, 3)");
             TriangleSoup soup;
             for (py::ssize_t i = 0; i < v.shape(0); ++i) soup.vertices.emplace_back(v.at(i, 0), v.at(i, 1), v.at(i, 2));
             for (py::ssize_t i = 0; i < t.shape(0); ++i)
               soup.triangles.push_back({static_cast<int>(t.at(i, 0)), static_cast<int>(t.at(i, 1)), static_cast<int>(t.at(i, 2))});
             return std::make_shared<Mesh>(std::move(soup));
           }),
           py::arg("vertices"), py::arg("triangles"), "Mesh(vertices (n, 3) [m], triangles (m, 3) indices).")
      .def_static(
          "from_file",
          [](const std::string& path, const std::string& file_unit, const py::object& translation,
             const py::object& rotation) {
            const ObjectPose pose = object_pose_arg(translation, rotation);
            py::gil_scoped_release release;
            return std::const_pointer_cast<Mesh>(Mesh::from_file(path, trial::length_scale(file_unit, "file_unit"), pose));
          },
          py::arg("path"), py::arg("file_unit") = "m", py::arg("translation") = py::none(),
          py::arg("rotation") = py::none(),
          "Reads OBJ, STL, PLY (and other formats assimp reads); coordinates in `file_unit` ('m', 'mm', 'um'), then "
          "turned by `rotation` (3x3) and moved by `translation` [m].")
      .def_property_readonly("vertices", [](const Mesh& s) { return to_array(s.vertices()); }, "(n, 3) [m].")
      .def_property_readonly(
          "triangles",
          [](const Mesh& s) {
            py::array_t<long> a({static_cast<py::ssize_t>(s.triangles().size()), py::ssize_t(3)});
            auto r = a.mutable_unchecked<2>();
            for (std::size_t i = 0; i < s.triangles().size(); ++i)
              for (int k = 0; k < 3; ++k) r(static_cast<py::ssize_t>(i), k) = s.triangles()[i][static_cast<std::size_t>(k)];
            return a;
          },
          "(m, 3) vertex indices.")
      .def_property_readonly("closed", &Mesh::closed, "Every edge shared by two triangles.");

  m.def(
      "solve_object",
      [](const Whisker& w, const std::shared_ptr<Shape>& shape, bool thickness, const py::object& hint,
         const py::object& options, const py::object& warm, const py::object& approach_W, const py::object& pose,
         const py::object& object_position, const py::object& object_rotation) {
        const ObjectContact o{shape.get(), object_pose_arg(object_position, object_rotation), thickness};
        const std::optional<double> h = hint.is_none() ? std::nullopt : std::optional<double>(hint.cast<double>());
        const SolveOptions opt = options_arg(options);
        const std::optional<LoadState> st = warm_arg(warm);
        const std::optional<Eigen::Vector3d> a = optional_vec3(approach_W, "load.approach");
        const Placement X = placement_arg(pose, w);
        py::gil_scoped_release release;
        return solve_object(w, X, o, h, opt, st ? &*st : nullptr, a);
      },
      py::arg("whisker"), py::arg("object"), py::kw_only(), py::arg("thickness") = true,
      py::arg("arc_length_hint") = py::none(), py::arg("options") = py::none(), py::arg("warm") = py::none(),
      py::arg("approach_W") = py::none(), py::arg("pose") = py::none(), py::arg("object_position") = py::none(),
      py::arg("object_rotation") = py::none(),
      "Object mode, frictionless (docs/objects.md): the whisker's surface (its centre line with thickness=False) "
      "against the object, on its side or at its tip. object_position / object_rotation place the shape's frame "
      "in the world (default: where its parameters put it). Solution.surface has the normal, the tip flag, the "
      "clearance.");
  m.def(
      "solve_frictional_object",
      [](const Whisker& w, const std::shared_ptr<Shape>& shape, double mu, const py::object& previous_contact_W,
         bool thickness, const py::object& options, const py::object& warm, const py::object& approach_W,
         const py::object& pose, const py::object& object_position, const py::object& object_rotation) {
        const ObjectContact o{shape.get(), object_pose_arg(object_position, object_rotation), thickness};
        const Eigen::Vector3d q = vec3(previous_contact_W, "previous_contact");
        const SolveOptions opt = options_arg(options);
        const std::optional<LoadState> st = warm_arg(warm);
        const std::optional<Eigen::Vector3d> a = optional_vec3(approach_W, "load.approach");
        const Placement X = placement_arg(pose, w);
        py::gil_scoped_release release;
        return solve_frictional_object(w, X, o, mu, q, opt, st ? &*st : nullptr, a);
      },
      py::arg("whisker"), py::arg("object"), py::arg("mu"), py::arg("previous_contact_W"), py::kw_only(),
      py::arg("thickness") = true, py::arg("options") = py::none(), py::arg("warm") = py::none(),
      py::arg("approach_W") = py::none(), py::arg("pose") = py::none(), py::arg("object_position") = py::none(),
      py::arg("object_rotation") = py::none(),
      "Frictional object mode (Coulomb `mu`, with history): sticks at `previous_contact_W` across the whisker while "
      "|F . b| <= mu F . n, else slips. mu = 0 is solve_object.");
}

}  // namespace vibrissa::python
