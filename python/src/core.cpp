// Bindings of the core layer: the whisker model (spec §2.1) and its placement in the world.
#include <sstream>
#include <stdexcept>

#include <pybind11/stl.h>

#include "bindings.hpp"
#include "convert.hpp"
#include "vibrissa/core/plausibility.hpp"
#include "vibrissa/core/pose.hpp"
#include "vibrissa/core/whisker.hpp"

namespace vibrissa::python {

namespace {

std::string scheme_name(Scheme s) { return s == Scheme::paper ? "paper" : "second_order"; }
std::string base_name(BaseJoint b) { return b == BaseJoint::rigid ? "rigid" : "elastic"; }

std::string fmt(double v) {
  std::ostringstream os;
  os.precision(6);
  os << v;
  return os.str();
}

std::string vec_repr(const Eigen::Vector3d& v) { return "[" + fmt(v.x()) + ", " + fmt(v.y()) + ", " + fmt(v.z()) + "]"; }

std::string pose_repr(const Pose& p) {
  return "Pose(base=" + vec_repr(p.p_W_base) + ", theta=" + fmt(p.theta) + ", phi=" + fmt(p.phi) +
         ", zeta=" + fmt(p.zeta) + ")";
}

std::optional<double> optional_double(const py::object& obj) {
  if (obj.is_none()) return std::nullopt;
  return obj.cast<double>();
}

/// Converts (3,) -> (3,) and (N, 3) -> (N, 3) through `f`, so geometry helpers take one point or many.
template <class F>
py::array_t<double> map_points(const py::object& obj, const char* name, F&& f) {
  const DoubleArray a = as_double_array(obj, name);
  if (a.ndim() == 1 && a.shape(0) == 3) return to_array(f(Eigen::Vector3d(a.at(0), a.at(1), a.at(2))));
  if (a.ndim() == 2 && a.shape(1) == 3) {
    std::vector<Eigen::Vector3d> rows = points3(a, name);
    for (auto& r : rows) r = f(r);
    return to_array(rows);
  }
  throw py::value_error(std::string(name) + " must have shape (3,) or (N, 3), got " + shape_string(a));
}

}  // namespace

Scheme scheme_arg(py::handle obj) {
  if (py::isinstance<Scheme>(obj)) return obj.cast<Scheme>();
  if (py::isinstance<py::str>(obj)) {
    const auto s = obj.cast<std::string>();
    if (s == "paper") return Scheme::paper;
    if (s == "second_order") return Scheme::second_order;
    throw py::value_error("whisker.scheme must be \"paper\" or \"second_order\", got \"" + s + "\"");
  }
  throw py::value_error("whisker.scheme must be a Scheme or a string, got " +
                        std::string(py::str(py::type::handle_of(obj).attr("__name__"))));
}

BaseJoint base_joint_arg(py::handle obj) {
  if (py::isinstance<BaseJoint>(obj)) return obj.cast<BaseJoint>();
  if (py::isinstance<py::str>(obj)) {
    const auto s = obj.cast<std::string>();
    if (s == "elastic") return BaseJoint::elastic;
    if (s == "rigid") return BaseJoint::rigid;
    throw py::value_error("whisker.base must be \"elastic\" or \"rigid\", got \"" + s + "\"");
  }
  throw py::value_error("whisker.base must be a BaseJoint or a string, got " +
                        std::string(py::str(py::type::handle_of(obj).attr("__name__"))));
}

Pose pose_arg(py::handle obj) {
  if (obj.is_none()) return Pose{};
  if (!py::isinstance<Pose>(obj))
    throw py::value_error("pose must be a vibrissa.Pose or None, got " +
                          std::string(py::str(py::type::handle_of(obj).attr("__name__"))));
  return obj.cast<Pose>();
}

Placement placement_arg(py::handle obj, const Whisker& whisker) {
  if (obj.is_none()) return whisker.placement();
  return Placement(pose_arg(obj));
}

void bind_core(py::module_& m) {
  py::enum_<Scheme>(m, "Scheme", "How the continuous rod is discretised into joints (docs/conventions.md).")
      .value("second_order", Scheme::second_order, "trapezoidal joint compliance, error O(1/N^2) (default)")
      .value("paper", Scheme::paper, "the published chain (spec §2.1), error O(1/N)");
  py::enum_<BaseJoint>(m, "BaseJoint", "Boundary condition at the follicle (spec §2.1).")
      .value("elastic", BaseJoint::elastic, "the base joint has a spring (the paper's choice)")
      .value("rigid", BaseJoint::rigid, "the first link is clamped in the follicle");

  py::class_<Pose>(m, "Pose",
                   "Placement of the whisker frame B in the world W: R_WB = Rz(theta)·Ry(-phi)·Rx(zeta), base "
                   "point p_W_base [m]. theta: protraction about world +z [rad]; phi: elevation toward +z "
                   "[rad]; zeta: roll about the whisker's own x axis [rad].")
      .def(py::init([](const py::object& base, double theta, double phi, double zeta) {
             Pose p;
             p.p_W_base = vec3(base, "pose.base");
             p.theta = theta;
             p.phi = phi;
             p.zeta = zeta;
             validate(p);
             warn_all(pose_warnings(p, "Pose"));
             return p;
           }),
           py::kw_only(), py::arg("base") = py::make_tuple(0.0, 0.0, 0.0), py::arg("theta") = 0.0,
           py::arg("phi") = 0.0, py::arg("zeta") = 0.0,
           "Pose(*, base=(0, 0, 0) [m], theta=0 [rad], phi=0 [rad], zeta=0 [rad]).")
      .def_property(
          "base", [](const Pose& p) { return to_array(p.p_W_base); },
          [](Pose& p, const py::object& v) { p.p_W_base = vec3(v, "pose.base"); }, "Base point in world [m], shape (3,).")
      .def_property(
          "p_W_base", [](const Pose& p) { return to_array(p.p_W_base); },
          [](Pose& p, const py::object& v) { p.p_W_base = vec3(v, "pose.base"); }, "Alias of `base` [m].")
      .def_readwrite("theta", &Pose::theta, "Protraction (azimuth) about world +z [rad].")
      .def_readwrite("phi", &Pose::phi, "Elevation, positive toward world +z [rad].")
      .def_readwrite("zeta", &Pose::zeta, "Roll about the whisker's x axis [rad].")
      .def_property_readonly(
          "R_WB", [](const Pose& p) { return to_array(rotation_from_angles(p.theta, p.phi, p.zeta)); },
          "Rotation taking whisker-frame vectors to world, shape (3, 3).")
      .def("__repr__", &pose_repr)
      .def(py::pickle(
          [](const Pose& p) { return py::make_tuple(to_array(p.p_W_base), p.theta, p.phi, p.zeta); },
          [](const py::tuple& t) {
            Pose p;
            p.p_W_base = vec3(t[0], "pose.base");
            p.theta = t[1].cast<double>();
            p.phi = t[2].cast<double>();
            p.zeta = t[3].cast<double>();
            return p;
          }));

  m.def(
      "rotation_from_angles",
      [](double theta, double phi, double zeta) { return to_array(rotation_from_angles(theta, phi, zeta)); },
      py::arg("theta"), py::arg("phi"), py::arg("zeta"),
      "R_WB = Rz(theta)·Ry(-phi)·Rx(zeta) from the pose angles [rad], shape (3, 3).");
  m.def(
      "pose_from_rotation",
      [](const py::object& R_WB, const py::object& p_W_base) {
        const DoubleArray a = as_double_array(R_WB, "R_WB");
        if (a.ndim() != 2 || a.shape(0) != 3 || a.shape(1) != 3)
          throw py::value_error("R_WB must have shape (3, 3), got " + shape_string(a));
        Eigen::Matrix3d R;
        for (py::ssize_t i = 0; i < 3; ++i)
          for (py::ssize_t j = 0; j < 3; ++j) R(i, j) = a.at(i, j);
        return pose_from_rotation(R, vec3(p_W_base, "p_W_base"));
      },
      py::arg("R_WB"), py::arg("p_W_base") = py::make_tuple(0.0, 0.0, 0.0),
      "The pose angles of a rotation R_WB (inverse of rotation_from_angles; phi in [-pi/2, pi/2]).");

  py::class_<WhiskerProperties>(m, "WhiskerProperties",
                                "Everything about a whisker except its rest shape; defaults are the spec's (§2.1).")
      .def(py::init([](int links, double base_radius, double taper_ratio, const py::object& radii,
                       double youngs_modulus, const py::object& youngs_moduli, double poisson_ratio,
                       const py::object& base, const py::object& base_stiffness, const py::object& scheme) {
             WhiskerProperties p;
             p.links = links;
             p.base_radius = base_radius;
             p.taper_ratio = taper_ratio;
             // A list given is a list used: [] is an error like a list of one (as in case JSON), never the defaults.
             auto given_list = [](const py::object& v, const char* field) {
               std::vector<double> out = vector1(v, field);
               if (out.size() < 2)
                 throw py::value_error(std::string(field) + " needs at least 2 values, got " + std::to_string(out.size()) +
                                       " (leave it out, or None, for the default)");
               return out;
             };
             if (!radii.is_none()) p.radii = given_list(radii, "whisker.radii");
             p.youngs_modulus = youngs_modulus;
             if (!youngs_moduli.is_none()) p.youngs_moduli = given_list(youngs_moduli, "whisker.youngs_moduli");
             p.poisson_ratio = poisson_ratio;
             p.base = base_joint_arg(base);
             p.base_stiffness = optional_double(base_stiffness);
             p.scheme = scheme_arg(scheme);
             validate(p);
             return p;
           }),
           py::kw_only(), py::arg("links") = 100, py::arg("base_radius") = 100e-6, py::arg("taper_ratio") = 15.0,
           py::arg("radii") = py::none(), py::arg("youngs_modulus") = 3.3e9, py::arg("youngs_moduli") = py::none(),
           py::arg("poisson_ratio") = 0.38, py::arg("base") = "elastic", py::arg("base_stiffness") = py::none(),
           py::arg("scheme") = "second_order",
           "Keyword-only. links: N rigid links; base_radius [m]; taper_ratio: base/tip radius (linear taper); "
           "radii: optional per-node radii [m] base to tip (overrides base_radius/taper_ratio); "
           "youngs_modulus [Pa]; youngs_moduli: optional per-node E [Pa]; poisson_ratio (G = E/(2(1+nu))); "
           "base: 'elastic' | 'rigid'; base_stiffness: optional follicle spring [N·m/rad]; "
           "scheme: 'second_order' | 'paper'. Raises ValueError naming the field.")
      .def_readwrite("links", &WhiskerProperties::links, "N, number of rigid links.")
      .def_readwrite("base_radius", &WhiskerProperties::base_radius, "[m]")
      .def_readwrite("taper_ratio", &WhiskerProperties::taper_ratio, "base radius / tip radius")
      .def_property(
          "radii", [](const WhiskerProperties& p) { return to_array(p.radii); },
          [](WhiskerProperties& p, const py::object& v) {
            p.radii = v.is_none() ? std::vector<double>{} : vector1(v, "whisker.radii");
          },
          "Per-node radii [m], base to tip, equally spaced in arc length (empty: use base_radius/taper_ratio).")
      .def_readwrite("youngs_modulus", &WhiskerProperties::youngs_modulus, "[Pa]")
      .def_property(
          "youngs_moduli", [](const WhiskerProperties& p) { return to_array(p.youngs_moduli); },
          [](WhiskerProperties& p, const py::object& v) {
            p.youngs_moduli = v.is_none() ? std::vector<double>{} : vector1(v, "whisker.youngs_moduli");
          },
          "Per-node Young's modulus [Pa], base to tip (empty: use youngs_modulus).")
      .def_readwrite("poisson_ratio", &WhiskerProperties::poisson_ratio)
      .def_property(
          "base", [](const WhiskerProperties& p) { return p.base; },
          [](WhiskerProperties& p, const py::object& v) { p.base = base_joint_arg(v); }, "BaseJoint (or its name).")
      .def_readwrite("base_stiffness", &WhiskerProperties::base_stiffness, "Follicle spring [N·m/rad] or None.")
      .def_property(
          "scheme", [](const WhiskerProperties& p) { return p.scheme; },
          [](WhiskerProperties& p, const py::object& v) { p.scheme = scheme_arg(v); }, "Scheme (or its name).")
      .def("validate", [](const WhiskerProperties& p) { validate(p); }, "Raises ValueError naming the bad field.")
      .def("__repr__", [](const WhiskerProperties& p) {
        std::string s = "WhiskerProperties(links=" + std::to_string(p.links);
        if (p.radii.empty())
          s += ", base_radius=" + fmt(p.base_radius) + ", taper_ratio=" + fmt(p.taper_ratio);
        else
          s += ", radii=<" + std::to_string(p.radii.size()) + " values>";
        s += p.youngs_moduli.empty() ? ", youngs_modulus=" + fmt(p.youngs_modulus)
                                     : ", youngs_moduli=<" + std::to_string(p.youngs_moduli.size()) + " values>";
        s += ", poisson_ratio=" + fmt(p.poisson_ratio) + ", base='" + base_name(p.base) + "'";
        if (p.base_stiffness) s += ", base_stiffness=" + fmt(*p.base_stiffness);
        return s + ", scheme='" + scheme_name(p.scheme) + "')";
      });

  py::class_<Whisker>(m, "Whisker",
                      "An intrinsically curved, tapered whisker: N rigid links joined by bending/torsion springs "
                      "(spec §2.1). Immutable; build one with from_points, from_parabola or from_cubic.")
      .def_static(
          "from_points",
          [](const py::object& points, const py::object& properties, const py::object& pose) {
            const auto pts = points3(points, "whisker.points");
            const WhiskerProperties props = properties.is_none() ? WhiskerProperties{} : properties.cast<WhiskerProperties>();
            const std::optional<Pose> placement = pose.is_none() ? std::nullopt : std::optional<Pose>(pose_arg(pose));
            Whisker w = Whisker::from_points(pts, props, placement);
            warn_all(plausibility_warnings(w));
            return w;
          },
          py::arg("points"), py::kw_only(), py::arg("properties") = py::none(), py::arg("pose") = py::none(),
          "Rest shape from an (M, 3) array of points [m], base first (M >= 3), resampled into "
          "properties.links equal links. Without a pose the points are world coordinates and fix the placement; "
          "with a pose only their shape is used and the pose places the whisker frame.")
      .def_static(
          "from_parabola",
          [](double length, double curvature, const py::object& properties, const py::object& pose) {
            const WhiskerProperties props = properties.is_none() ? WhiskerProperties{} : properties.cast<WhiskerProperties>();
            Whisker w = Whisker::from_parabola(length, curvature, props, pose_arg(pose));
            warn_all(plausibility_warnings(w));
            return w;
          },
          py::arg("length"), py::arg("curvature"), py::kw_only(), py::arg("properties") = py::none(),
          py::arg("pose") = py::none(),
          "Planar rest shape y = curvature·x^2 in the whisker frame: arc length `length` [m], curvature "
          "coefficient [1/m].")
      .def_static(
          "from_cubic",
          [](double length, double A, double B, const py::object& properties, const py::object& pose) {
            const WhiskerProperties props = properties.is_none() ? WhiskerProperties{} : properties.cast<WhiskerProperties>();
            Whisker w = Whisker::from_cubic(length, A, B, props, pose_arg(pose));
            warn_all(plausibility_warnings(w));
            return w;
          },
          py::arg("length"), py::arg("A"), py::arg("B"), py::kw_only(), py::arg("properties") = py::none(),
          py::arg("pose") = py::none(),
          "Planar rest shape y = A·x^3 + B·x^2 in the whisker frame: A [1/m^2], B [1/m], arc length [m].")
      .def("placed", [](const Whisker& w, const Pose& pose) { return w.with_placement(Placement(pose)); },
           py::arg("pose"),
           "A copy of the whisker whose default pose is `pose` (the rest shape in B is unchanged). Per-frame "
           "code passes `pose=` to the solves (or pose_base/pose_angles to the batches) instead of copying.")
      .def_property_readonly("links", &Whisker::links, "N, number of links.")
      .def_property_readonly("length", &Whisker::length, "Arc length [m].")
      .def_property_readonly("rest_nodes_B", [](const Whisker& w) { return to_array(w.rest_nodes_B()); },
                             "Rest nodes in the whisker frame B [m], shape (N+1, 3), base first.")
      .def_property_readonly(
          "rest_nodes_W",
          [](const Whisker& w) {
            std::vector<Eigen::Vector3d> nodes = w.rest_nodes_B();
            for (auto& p : nodes) p = w.placement().to_world(p);
            return to_array(nodes);
          },
          "Rest nodes in world [m], shape (N+1, 3), base first.")
      .def_property_readonly("link_lengths", [](const Whisker& w) { return to_array(w.link_lengths()); },
                             "Length of each link [m], shape (N,).")
      .def_property_readonly("node_arc_lengths", [](const Whisker& w) { return to_array(w.node_arc_lengths()); },
                             "Arc length of each node from the base [m], shape (N+1,).")
      .def_property_readonly("node_radii", [](const Whisker& w) { return to_array(w.node_radii()); },
                             "Radius at each node [m], shape (N+1,).")
      .def_property_readonly("node_youngs_moduli", [](const Whisker& w) { return to_array(w.node_youngs_moduli()); },
                             "Young's modulus at each node [Pa], shape (N+1,).")
      .def_property_readonly("bending_compliance", [](const Whisker& w) { return to_array(w.bending_compliance()); },
                             "1/(E I) at each joint [1/(N·m^2)].")
      .def_property_readonly("torsion_compliance", [](const Whisker& w) { return to_array(w.torsion_compliance()); },
                             "1/(G J) at each joint [1/(N·m^2)].")
      .def_property_readonly("base_bending_stiffness", &Whisker::base_bending_stiffness, "E I at the base [N·m^2].")
      .def_property_readonly("properties", &Whisker::properties, "The WhiskerProperties it was built with (a copy).")
      .def_property_readonly("R_WB", [](const Whisker& w) { return to_array(w.placement().R_WB); },
                             "Rotation whisker frame -> world, shape (3, 3).")
      .def_property_readonly("p_W_base", [](const Whisker& w) { return to_array(w.placement().p_W_base); },
                             "Base point in world [m], shape (3,).")
      .def_property_readonly(
          "pose", [](const Whisker& w) { return w.placement().pose(); },
          "The Pose it was built with (where solves place it when given no pose=).")
      .def(
          "locate",
          [](const Whisker& w, double s) {
            int link = 0;
            double h = 0.0;
            w.locate(s, link, h);
            return py::make_tuple(link, h);
          },
          py::arg("s"), "(link, h): the link holding arc length s [m] and the distance h [m] past its first node.")
      .def("rest_point_B", [](const Whisker& w, double s) { return to_array(w.rest_point_B(s)); }, py::arg("s"), "Rest point at arc length s [m], whisker frame [m].")
      .def("rest_point_W", [](const Whisker& w, double s) { return to_array(w.placement().to_world(w.rest_point_B(s))); }, py::arg("s"), "Rest point at arc length s [m], world [m].")
      .def(
          "to_world",
          [](const Whisker& w, const py::object& p_B) {
            return map_points(p_B, "p_B", [&](const Eigen::Vector3d& p) { return w.placement().to_world(p); });
          },
          py::arg("p_B"), "Whisker-frame point(s) [m], shape (3,) or (M, 3), to world [m].")
      .def(
          "to_body",
          [](const Whisker& w, const py::object& p_W) {
            return map_points(p_W, "p_W", [&](const Eigen::Vector3d& p) { return w.placement().to_body(p); });
          },
          py::arg("p_W"), "World point(s) [m], shape (3,) or (M, 3), to the whisker frame [m].")
      .def("__repr__", [](const Whisker& w) {
        return "Whisker(links=" + std::to_string(w.links()) + ", length=" + fmt(w.length()) +
               " m, pose=" + pose_repr(w.placement().pose()) + ")";
      });
}

}  // namespace vibrissa::python
