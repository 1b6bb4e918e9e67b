// The contact tracker from Python (docs/python.md, "Contact tracking"): the same per-frame loop as trials,
// synthetic trials, arrays and batches, stepped one frame at a time by the caller.
#include <pybind11/stl.h>

#include <memory>
#include <vector>

#include "bindings.hpp"
#include "convert.hpp"
#include "vibrissa/contact/tracker.hpp"

namespace vibrissa::python {

namespace {

/// A tracker and the whisker it reads (kept alive by the Python object).
struct PyTracker {
  std::shared_ptr<const Whisker> whisker;
  ContactTracker tracker;
  PyTracker(const Whisker& w, const TrackerOptions& o)
      : whisker(std::make_shared<const Whisker>(w)), tracker(*whisker, o) {}
};

std::vector<EdgeSegment> segments_arg(const py::object& edges) {
  std::vector<EdgeSegment> out;
  if (py::isinstance<Edge>(edges)) {
    out.push_back(infinite_segment(edges.cast<Edge>()));
    return out;
  }
  if (!py::isinstance<py::sequence>(edges) || py::isinstance<py::str>(edges))
    throw py::value_error("edges must be a vibrissa.Edge or a sequence of them");
  const py::sequence seq = edges.cast<py::sequence>();
  for (std::size_t i = 0; i < seq.size(); ++i) {
    if (!py::isinstance<Edge>(seq[i]))
      throw py::value_error("edges[" + std::to_string(i) + "] must be a vibrissa.Edge");
    out.push_back(infinite_segment(seq[i].cast<Edge>()));
  }
  return out;
}

py::dict frame_dict(const TrackedFrame& f) {
  py::dict d;
  d["state"] = f.state;
  d["edge"] = f.edge;
  d["onset"] = f.onset;
  d["solved"] = f.solved;
  d["edge_coordinate"] = f.edge_coordinate;
  d["onset_edge_coordinate"] = f.onset_edge_coordinate;
  d["approach_W"] = to_array(f.approach_W);
  d["solution"] = f.solution;
  return d;
}

}  // namespace

void bind_contact(py::module_& m) {
  py::enum_<ContactMode>(m, "ContactMode", "Which equations hold a tracked contact (spec §2.1).")
      .value("contact_point", ContactMode::contact_point, "through the tracked contact point")
      .value("edge", ContactMode::edge, "frictionless slip along the edge")
      .value("frictional_edge", ContactMode::frictional_edge, "Coulomb friction along the edge")
      .def_property_readonly("label", [](ContactMode c) { return std::string(to_string(c)); }, "Its name.");

  py::class_<PyTracker>(m, "ContactTracker",
                        "One whisker's contact across frames, with the policy of docs/conventions.md (\"Contact "
                        "tracking\"): the loop under trials, synthetic trials, arrays and batches.")
      .def(py::init([](const Whisker& w, const py::object& mode, double mu, const py::object& options) {
             TrackerOptions o;
             o.mode = py::isinstance<ContactMode>(mode)
                          ? mode.cast<ContactMode>()
                          : contact_mode_from_string(py::str(mode).cast<std::string>(), "mode");
             o.mu = mu;
             o.solve = options_arg(options);
             return std::make_unique<PyTracker>(w, o);
           }),
           py::arg("whisker"), py::arg("mode") = "edge", py::kw_only(), py::arg("mu") = 0.0,
           py::arg("options") = py::none(),
           "ContactTracker(whisker, mode='edge' | 'frictional_edge' | 'contact_point', *, mu=0, options=None).")
      .def(
          "step",
          [](PyTracker& t, const py::object& pose, const py::object& edges) {
            const Placement X = placement_arg(pose, *t.whisker);
            const std::vector<EdgeSegment> segs = segments_arg(edges);
            py::gil_scoped_release release;
            const TrackedFrame& f = t.tracker.step(X, segs);
            py::gil_scoped_acquire acquire;
            return frame_dict(f);
          },
          py::arg("pose"), py::arg("edges"),
          "A simulated frame: the whisker at `pose` (a Pose), the scene's edges (an Edge or a list, the same "
          "every frame, world, this frame). Onset when the rest whisker crosses an edge since the last frame. "
          "Returns a dict: state (ContactState), edge, onset, solved, edge_coordinate [m], "
          "onset_edge_coordinate [m], approach_W, solution (Solution).")
      .def(
          "step_tracked",
          [](PyTracker& t, const py::object& pose, const py::object& edge, bool in_contact,
             const py::object& contact_point_W, const py::object& arc_length_hint, const py::object& approach_W,
             const py::object& initial_contact_W) {
            const Placement X = placement_arg(pose, *t.whisker);
            std::optional<EdgeSegment> seg;
            if (!edge.is_none()) seg = segments_arg(edge).at(0);
            TrackedInput in;
            in.in_contact = in_contact;
            in.p_W_contact = optional_vec3(contact_point_W, "contact_point_W");
            if (!arc_length_hint.is_none()) in.arc_length_hint = arc_length_hint.cast<double>();
            in.approach_W = optional_vec3(approach_W, "approach_W");
            in.initial_contact_W = optional_vec3(initial_contact_W, "initial_contact_W");
            py::gil_scoped_release release;
            const TrackedFrame& f = t.tracker.step_tracked(X, seg ? &*seg : nullptr, in);
            py::gil_scoped_acquire acquire;
            return frame_dict(f);
          },
          py::arg("pose"), py::arg("edge") = py::none(), py::kw_only(), py::arg("in_contact") = true,
          py::arg("contact_point_W") = py::none(), py::arg("arc_length_hint") = py::none(),
          py::arg("approach_W") = py::none(), py::arg("initial_contact_W") = py::none(),
          "A tracked frame: contact when `in_contact` (the data say so). `edge` is required in the edge modes; "
          "`contact_point_W` in contact_point mode. Returns the same dict as step().")
      .def("reset", [](PyTracker& t) { t.tracker.reset(); }, "Forget all history.")
      .def_property_readonly("state", [](const PyTracker& t) { return t.tracker.state(); }, "ContactState now.")
      .def_property_readonly("solves", [](const PyTracker& t) { return t.tracker.solves(); }, "Solves run so far.");
}

}  // namespace vibrissa::python
