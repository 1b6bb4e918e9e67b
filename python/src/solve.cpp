// Bindings of the solve layer (spec §2.1, §2.4): the four load modes and what they report. Each solve
// releases the GIL while it runs, so Python threads can solve concurrently.
#include <pybind11/stl.h>

#include "bindings.hpp"
#include "deprecated.hpp"
#include "convert.hpp"
#include "vibrissa/contact/contact_geometry.hpp"
#include "vibrissa/solve/solvers.hpp"
#include "vibrissa/solve/status.hpp"

namespace vibrissa::python {

namespace {

std::optional<double> optional_double(const py::object& obj, const char* name) {
  if (obj.is_none()) return std::nullopt;
  try {
    return obj.cast<double>();
  } catch (const py::cast_error&) {
    throw py::value_error(std::string(name) + " must be a number or None, got " +
                          std::string(py::str(py::type::handle_of(obj).attr("__name__"))));
  }
}

Edge edge_arg(py::handle obj) {
  if (!py::isinstance<Edge>(obj))
    throw py::value_error("edge must be a vibrissa.Edge, got " +
                          std::string(py::str(py::type::handle_of(obj).attr("__name__"))));
  return obj.cast<Edge>();
}

}  // namespace

SolveOptions options_arg(py::handle obj) {
  if (obj.is_none()) return SolveOptions{};
  if (!py::isinstance<SolveOptions>(obj))
    throw py::value_error("options must be a vibrissa.SolveOptions or None, got " +
                          std::string(py::str(py::type::handle_of(obj).attr("__name__"))));
  return obj.cast<SolveOptions>();
}

std::optional<LoadState> warm_arg(py::handle obj) {
  if (obj.is_none()) return std::nullopt;
  if (py::isinstance<LoadState>(obj)) return obj.cast<LoadState>();
  if (py::isinstance<Solution>(obj)) return obj.cast<const Solution&>().state;
  throw py::value_error("warm must be a LoadState, a Solution or None, got " +
                        std::string(py::str(py::type::handle_of(obj).attr("__name__"))));
}

void bind_solve(py::module_& m) {
  py::enum_<Status>(m, "Status", "Outcome of a solve; anything but `converged` comes with a message, never NaN.")
      .value("converged", Status::converged, "equations satisfied to the requested tolerance")
      .value("no_contact", Status::no_contact, "the object is out of reach, or the whisker is not pressed against it")
      .value("slipped_off", Status::slipped_off, "equilibrium would need the contact beyond the tip")
      .value("not_converged", Status::not_converged, "the iteration limit was reached or the solver stalled")
      .value("second_contact", Status::second_contact,
             "object modes: another part of the whisker would be inside the object (second_contact_arc_length)")
      .value("underdetermined", Status::underdetermined,
             "base-wrench inverse: the fit explains the signals, but they cannot determine the contact (a family "
             "of fits along identifiability.null_direction)")
      .def_property_readonly("label", [](Status s) { return std::string(to_string(s)); },
                             "The name used in JSON results (\"converged\", ...).");
  py::enum_<ContactState>(m, "ContactState", "Whether the whisker touches its object (same codes in every file).")
      .value("free", ContactState::free, "not touching")
      .value("contact", ContactState::contact, "touching, in equilibrium")
      .value("pushed_past", ContactState::pushed_past, "slipped off the tip / snapped past: beyond the object")
      .def_property_readonly("label", [](ContactState s) { return std::string(to_string(s)); }, "Its name.");
  py::enum_<FrictionState>(m, "FrictionState", "Coulomb friction state of a contact (frictional edge mode).")
      .value("none", FrictionState::none, "no friction state (other modes, or no contact)")
      .value("stick", FrictionState::stick, "the contact held its previous point")
      .value("slip", FrictionState::slip, "the contact slid along the edge with |F_edge| = mu F_N")
      .def_property_readonly("label", [](FrictionState s) { return std::string(to_string(s)); }, "Its name.");
  m.def("status_from_string", [](const std::string& name) { return status_from_string(name); }, py::arg("name"),
        "Status from its JSON name; ValueError for an unknown name.");

  py::class_<SolveOptions>(m, "SolveOptions", "Options of every solve.")
      .def(py::init([](double tolerance, int max_iterations, bool compute_shape, bool find_other_roots) {
             SolveOptions o;
             o.tolerance = tolerance;
             o.max_iterations = max_iterations;
             o.compute_shape = compute_shape;
             o.find_other_roots = find_other_roots;
             return o;
           }),
           py::kw_only(), py::arg("tolerance") = 1e-12, py::arg("max_iterations") = 100,
           py::arg("compute_shape") = true, py::arg("find_other_roots") = false)
      .def_readwrite("tolerance", &SolveOptions::tolerance, "Contact residual to reach [m].")
      .def_readwrite("max_iterations", &SolveOptions::max_iterations, "Levenberg-Marquardt iterations per attempt.")
      .def_readwrite("compute_shape", &SolveOptions::compute_shape, "Fill Solution.shape (one extra O(N) pass).")
      .def_readwrite("find_other_roots", &SolveOptions::find_other_roots,
                     "Probe for a second root and report it (about 2 extra solves).")
      .def("__repr__", [](const SolveOptions& o) {
        return "SolveOptions(tolerance=" + std::string(py::str(py::float_(o.tolerance))) +
               ", max_iterations=" + std::to_string(o.max_iterations) +
               ", compute_shape=" + (o.compute_shape ? "True" : "False") +
               ", find_other_roots=" + (o.find_other_roots ? "True" : "False") + ")";
      });

  py::class_<Edge>(m, "Edge", "A straight edge: the infinite line through `point` along `direction` (world). A peg is one edge.")
      .def(py::init([](const py::object& point, const py::object& direction) {
             Edge e;
             e.point = vec3(point, "edge.point");
             e.direction = vec3(direction, "edge.direction");
             validate(e);
             return e;
           }),
           py::arg("point"), py::arg("direction") = py::make_tuple(0.0, 0.0, 1.0),
           "Edge(point [m], direction=(0, 0, 1) (any non-zero length)).")
      .def_property(
          "point", [](const Edge& e) { return to_array(e.point); },
          [](Edge& e, const py::object& v) { e.point = vec3(v, "edge.point"); }, "A point on the edge, world [m].")
      .def_property(
          "direction", [](const Edge& e) { return to_array(e.direction); },
          [](Edge& e, const py::object& v) { e.direction = vec3(v, "edge.direction"); }, "Edge direction, world.")
      .def("__repr__", [](const Edge& e) {
        return "Edge(point=" + std::string(py::repr(to_array(e.point).attr("tolist")())) +
               ", direction=" + std::string(py::repr(to_array(e.direction).attr("tolist")())) + ")";
      });

  py::class_<LoadState>(m, "LoadState",
                        "Unknowns of a contact solve (force in the loaded link's frame [N], contact arc length [m]); "
                        "pass a previous solution's state (or the solution itself) as `warm` to warm-start. A "
                        "solution's state also carries what its solve learned (the next warm start's first step "
                        "then needs no Jacobian); a LoadState built from numbers does not: the same root, to within "
                        "the tolerance.")
      .def(py::init([](double fx, double fy, double fz, double s) {
             LoadState state;
             state.force_x = fx;
             state.force_y = fy;
             state.force_z = fz;
             state.arc_length = s;
             return state;
           }),
           py::kw_only(), py::arg("force_x") = 0.0, py::arg("force_y") = 0.0, py::arg("force_z") = 0.0,
           py::arg("arc_length") = 0.0)
      .def_readwrite("force_x", &LoadState::force_x, "Axial component [N].")
      .def_readwrite("force_y", &LoadState::force_y, "[N]")
      .def_readwrite("force_z", &LoadState::force_z, "[N]")
      .def_readwrite("arc_length", &LoadState::arc_length, "[m]")
      .def("__repr__", [](const LoadState& s) {
        return "LoadState(force_x=" + std::string(py::str(py::float_(s.force_x))) +
               ", force_y=" + std::string(py::str(py::float_(s.force_y))) +
               ", force_z=" + std::string(py::str(py::float_(s.force_z))) +
               ", arc_length=" + std::string(py::str(py::float_(s.arc_length))) + ")";
      });

  py::class_<WhiskerFrameSignals>(m, "WhiskerFrameSignals", "Base signals in the whisker-centred frame (spec §2.4).")
      .def_property_readonly("force", [](const WhiskerFrameSignals& w) { return to_array(w.force); },
                             "(Fx, Fy, Fz) [N], shape (3,).")
      .def_property_readonly("moment", [](const WhiskerFrameSignals& w) { return to_array(w.moment); },
                             "(Mx, My, Mz) [N·m], shape (3,).")
      .def_property_readonly("Fx", [](const WhiskerFrameSignals& w) { return w.force.x(); },
                             "Axial force, force[0] [N].")
      .def_property_readonly("Mx", [](const WhiskerFrameSignals& w) { return w.moment.x(); },
                             "Twisting moment about the whisker axis, moment[0] [N·m].")
      .def_readonly("FT", &WhiskerFrameSignals::FT, "Transverse force sqrt(Fy^2 + Fz^2) [N].")
      .def_readonly("MB", &WhiskerFrameSignals::MB, "Bending moment sqrt(My^2 + Mz^2) [N·m].")
      .def_readonly("FD", &WhiskerFrameSignals::FD, "Force direction atan2(Fz, Fy) [rad].")
      .def_readonly("MD", &WhiskerFrameSignals::MD, "Moment direction atan2(Mz, My) [rad].")
      .def("__repr__", [](const WhiskerFrameSignals& w) {
        return "WhiskerFrameSignals(FT=" + std::string(py::str(py::float_(w.FT))) +
               ", MB=" + std::string(py::str(py::float_(w.MB))) + ", FD=" + std::string(py::str(py::float_(w.FD))) +
               ", MD=" + std::string(py::str(py::float_(w.MD))) + ")";
      });

  py::class_<Solution>(m, "Solution",
                       "Everything a solve reports (spec §2.4); names follow the JSON result of `vibrissa solve`. "
                       "World frame unless the name says otherwise.")
      .def_readonly("status", &Solution::status, "Status of the solve.")
      .def_readonly("message", &Solution::message, "Why it stopped, in words (decide from the typed fields).")
      .def_readonly("contact_state", &Solution::contact_state, "ContactState after the solve.")
      .def_readonly("friction", &Solution::friction, "FrictionState: stick / slip (frictional edge mode), else none.")
      .def_readonly("fold", &Solution::fold,
                    "True when slipped_off because the equilibrium branch ends in a fold (push-past), not at the tip.")
      .def_property_readonly("converged", [](const Solution& s) { return s.status == Status::converged; },
                             "True when status is Status.converged.")
      .def_readonly("force_magnitude", &Solution::force_magnitude, "|F| [N].")
      .def_readonly("arc_length", &Solution::arc_length, "Arc length of contact s [m].")
      .def_readonly("angle", &Solution::angle, "Direction of F about the loaded link's axis, atan2(Fz, Fy) [rad].")
      .def_property_readonly("contact_point_W", [](const Solution& s) { return to_array(s.contact_point_W); },
                             "Contact point, world [m], shape (3,).")
      .def_property_readonly("force_W", [](const Solution& s) { return to_array(s.force_W); },
                             "Force transmitted to the follicle (the contact force), world [N], shape (3,).")
      .def_property_readonly("moment_W", [](const Solution& s) { return to_array(s.moment_W); },
                             "Moment of the contact force about the base, world [N·m], shape (3,).")
      .def_property_readonly(
          "contact_point", deprecated_alias("Solution.contact_point", "contact_point_W"),
          "Deprecated alias of contact_point_W (DeprecationWarning; removed in 0.2.0).")
      .def_property_readonly("force", deprecated_alias("Solution.force", "force_W"),
                             "Deprecated alias of force_W (DeprecationWarning; removed in 0.2.0).")
      .def_property_readonly("moment", deprecated_alias("Solution.moment", "moment_W"),
                             "Deprecated alias of moment_W (DeprecationWarning; removed in 0.2.0).")
      .def_readonly("whisker_frame", &Solution::whisker_frame, "Base signals in the whisker frame (spec §2.4).")
      .def_readonly("normal_force", &Solution::normal_force, "Component of F normal to the edge [N] (edge modes) or None.")
      .def_readonly("edge_force", &Solution::edge_force, "Component of F along the edge [N] (edge modes) or None.")
      .def_readonly("residual", &Solution::residual, "Final residual [m].")
      .def_readonly("iterations", &Solution::iterations, "Solver iterations.")
      .def_property_readonly("shape", deprecated_alias("Solution.shape", "shape_W"),
                             "Deprecated alias of shape_W (DeprecationWarning; removed in 0.2.0).")
      .def_property_readonly(
          "shape_W",
          [](const Solution& s) { return to_array(s.shape_W); },
          "Deflected nodes, world [m], shape (N+1, 3), base first; (0, 3) when options.compute_shape is False.")
      .def_property_readonly(
          "surface",
          [](const Solution& s) -> py::object {
            if (!s.surface) return py::none();
            const SurfaceContact& c = *s.surface;
            py::dict d;
            d["normal_W"] = to_array(c.normal_W);
            d["friction_direction_W"] = to_array(c.friction_direction_W);
            d["tip"] = c.tip;
            d["feature"] = std::string(to_string(c.feature));
            d["friction_force"] = c.friction_force;
            d["clearance"] = c.clearance;
            d["clearance_arc_length"] = c.clearance_arc_length;
            return d;
          },
          "Object modes: a dict with normal_W (the object's outward normal at the contact), friction_direction_W, "
          "tip (contact at the tip), feature ('face', 'edge', 'vertex'), friction_force [N], clearance [m] (the "
          "smallest gap over the whisker) and clearance_arc_length [m]; None otherwise.")
      .def_readonly("second_contact_arc_length", &Solution::second_contact_arc_length,
                    "Status.second_contact: where the whisker would enter the object [m], else None.")
      .def_property_readonly(
          "second_contact",
          [](const Solution& s) -> py::object {
            if (!s.second_contact) return py::none();
            const SecondContact& c = *s.second_contact;
            py::dict d;
            d["arc_length"] = c.arc_length;
            d["contact_point_W"] = to_array(c.contact_point_W);
            d["force_W"] = to_array(c.force_W);
            d["normal_W"] = to_array(c.normal_W);
            d["normal_force"] = c.normal_force;
            d["feature"] = std::string(to_string(c.feature));
            return d;
          },
          "Object modes: a second contact solved with the first (a dict: arc_length [m], contact_point_W, force_W "
          "(its own force [N]), normal_W, normal_force [N], feature); force_W, moment_W and the whisker-frame "
          "signals are then the totals at the base. None otherwise.")
      .def_readonly("other_root_arc_length", &Solution::other_root_arc_length,
                    "Arc length [m] of another root, when options.find_other_roots found one, else None.")
      .def_property_readonly(
          "roots",
          [](const Solution& s) {
            py::list out;
            for (const Root& r : s.roots) {
              py::dict d;
              d["arc_length"] = r.arc_length;
              d["force"] = r.force_magnitude;
              d["residual"] = r.residual;
              out.append(d);
            }
            return out;
          },
          "Every distinct root found (point mode with a hint or find_other_roots): dicts with arc_length [m], "
          "force [N], residual [m], by arc length.")
      .def_readonly("state", &Solution::state, "The solved unknowns, for warm starts.")
      .def("to_dict", &solution_to_dict,
           "The result as the JSON contract of `vibrissa solve` names it (vectors and shape as NumPy arrays).")
      .def("to_json", &solution_json_text, py::arg("indent") = 2,
           "The result JSON text exactly as `vibrissa solve` writes it (indent=-1: one line).")
      .def("__repr__", [](const Solution& s) {
        return "Solution(status=" + std::string(to_string(s.status)) +
               ", force_magnitude=" + std::string(py::str(py::float_(s.force_magnitude))) +
               " N, arc_length=" + std::string(py::str(py::float_(s.arc_length))) + " m, message='" + std::string(s.message) + "')";
      });
  py::implicitly_convertible<Solution, LoadState>();

  m.def(
      "solve_force",
      [](const Whisker& w, double force, double arc_length, double angle, const py::object& options,
         const py::object& pose) {
        const SolveOptions o = options_arg(options);
        const Placement X = placement_arg(pose, w);
        py::gil_scoped_release release;
        return solve_force(w, X, force, arc_length, angle, o);
      },
      py::arg("whisker"), py::arg("force"), py::arg("arc_length"), py::arg("angle") = 0.0, py::kw_only(),
      py::arg("options") = py::none(), py::arg("pose") = py::none(),
      "Force mode: a follower force of magnitude `force` [N] normal to the whisker at `arc_length` [m], at "
      "`angle` [rad] about the whisker axis (second_order: 0 = +y of the loaded link, toward the concave side, pi/2 = +z; paper: Elastica3D's zeta, docs/conventions.md). "
      "Explicit, O(N).");
  m.def(
      "solve_dead_load",
      [](const Whisker& w, const py::object& force_W, double arc_length, const py::object& options,
         const py::object& warm, const py::object& pose) {
        const Eigen::Vector3d f = vec3(force_W, "load.force_W");
        const SolveOptions o = options_arg(options);
        const std::optional<LoadState> st = warm_arg(warm);
        const Placement X = placement_arg(pose, w);
        py::gil_scoped_release release;
        return solve_dead_load(w, X, f, arc_length, o, st ? &*st : nullptr);
      },
      py::arg("whisker"), py::arg("force_W"), py::arg("arc_length"), py::kw_only(), py::arg("options") = py::none(),
      py::arg("warm") = py::none(), py::arg("pose") = py::none(),
      "Dead load: a force with fixed world direction `force_W` [N], shape (3,), applied at `arc_length` [m].");
  m.def(
      "solve_point",
      [](const Whisker& w, const py::object& point_W, const py::object& hint, const py::object& options,
         const py::object& warm, const py::object& edge_direction_W, const py::object& pose) {
        const Eigen::Vector3d p = vec3(point_W, "load.point");
        const std::optional<double> h = optional_double(hint, "load.arc_length_hint");
        const SolveOptions o = options_arg(options);
        const std::optional<LoadState> st = warm_arg(warm);
        const std::optional<Eigen::Vector3d> d = optional_vec3(edge_direction_W, "load.edge_direction");
        const Placement X = placement_arg(pose, w);
        py::gil_scoped_release release;
        return solve_point(w, X, p, h, o, st ? &*st : nullptr, d);
      },
      py::arg("whisker"), py::arg("point_W"), py::arg("arc_length_hint") = py::none(), py::kw_only(),
      py::arg("options") = py::none(), py::arg("warm") = py::none(), py::arg("edge_direction_W") = py::none(),
      py::arg("pose") = py::none(),
      "Contact-point mode: the deflected whisker passes through `point_W` [m] (world, shape (3,)) with the "
      "force normal to it there. Root choice: `warm` (a LoadState or previous Solution) -> the continuous root; "
      "else the root nearest `arc_length_hint` [m]; else the arc length at the target's distance. "
      "`edge_direction_W`, if given, splits the force into normal_force / edge_force.");
  m.def(
      "solve_edge",
      [](const Whisker& w, const py::object& edge, const py::object& hint, const py::object& options,
         const py::object& warm, const py::object& approach_W, const py::object& pose) {
        const Edge e = edge_arg(edge);
        const std::optional<double> h = optional_double(hint, "load.arc_length_hint");
        const SolveOptions o = options_arg(options);
        const std::optional<LoadState> st = warm_arg(warm);
        const std::optional<Eigen::Vector3d> a = optional_vec3(approach_W, "load.approach");
        const Placement X = placement_arg(pose, w);
        py::gil_scoped_release release;
        return solve_edge(w, X, e, h, o, st ? &*st : nullptr, a);
      },
      py::arg("whisker"), py::arg("edge"), py::arg("arc_length_hint") = py::none(), py::kw_only(),
      py::arg("options") = py::none(), py::arg("warm") = py::none(), py::arg("approach_W") = py::none(),
      py::arg("pose") = py::none(),
      "Edge mode (frictionless slip, spec §2.1): the contact lies on the edge and the force is normal to both "
      "whisker and edge. `approach_W` (world, shape (3,)), if given, is the direction the whisker moved into "
      "the edge; the edge must push against it, else Status.no_contact.");
  m.def(
      "solve_frictional_edge",
      [](const Whisker& w, const py::object& edge, double mu, const py::object& previous_contact_W,
         const py::object& options, const py::object& warm, const py::object& approach_W, const py::object& pose) {
        const Edge e = edge_arg(edge);
        const Eigen::Vector3d q = vec3(previous_contact_W, "previous_contact");
        const SolveOptions o = options_arg(options);
        const std::optional<LoadState> st = warm_arg(warm);
        const std::optional<Eigen::Vector3d> a = optional_vec3(approach_W, "load.approach");
        const Placement X = placement_arg(pose, w);
        py::gil_scoped_release release;
        return solve_frictional_edge(w, X, e, mu, q, o, st ? &*st : nullptr, a);
      },
      py::arg("whisker"), py::arg("edge"), py::arg("mu"), py::arg("previous_contact_W"), py::kw_only(),
      py::arg("options") = py::none(), py::arg("warm") = py::none(), py::arg("approach_W") = py::none(),
      py::arg("pose") = py::none(),
      "Frictional edge mode (Coulomb coefficient `mu`, with contact history): the contact sticks at "
      "`previous_contact_W` [m] while |edge force| <= mu·F_N, else slips along the edge. mu = 0 is solve_edge.");
  m.def(
      "nearest_rest_point",
      [](const Whisker& w, const py::object& edge, const py::object& pose) {
        const Edge e = edge_arg(edge);
        validate(e);
        const NearestOnWhisker n = nearest_rest_point(w, placement_arg(pose, w), e);
        py::dict d;
        d["arc_length"] = n.arc_length;
        d["on_whisker_W"] = to_array(n.on_whisker_W);
        d["on_edge_W"] = to_array(n.on_edge_W);
        d["distance"] = n.distance;
        return d;
      },
      py::arg("whisker"), py::arg("edge"), py::kw_only(), py::arg("pose") = py::none(),
      "Nearest approach of the rest whisker (at `pose`, default its own) to the edge line: a dict with "
      "arc_length [m], on_whisker_W and on_edge_W [m] (shape (3,)) and distance [m]. on_edge_W is where a "
      "frictional contact starts at onset (docs/conventions.md, \"Contact tracking\").");
}

}  // namespace vibrissa::python
