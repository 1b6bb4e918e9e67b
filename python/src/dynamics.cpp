// Dynamics from Python (docs/dynamics.md, docs/python.md): the modes and a simulation of one whisker, parsed and
// written by the same io code as `vibrissa modes` and `vibrissa dynamics` (settings as the case's JSON text, the
// whisker given).
#include <cstddef>
#include <memory>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include "bindings.hpp"
#include "labelled.hpp"
#include "vibrissa/io/dynamics_case.hpp"
#include "vibrissa/io/json_input.hpp"
#include "vibrissa/objects/shape.hpp"

namespace vibrissa::python {
namespace {

struct DynamicsRun {
  dynamics::TimeSeries series;
  dynamics::Modes modes;
  nlohmann::json summary;
};

io::DynamicsCase settings(const Whisker& w, const std::string& text) {
  return io::dynamics_case_from_json(io::parse_json_text(text, "dynamics settings"), w);
}

}  // namespace

void bind_dynamics(py::module_& m) {
  py::class_<dynamics::Modes>(m, "Modes", "Natural modes of a whisker about its rest shape (docs/dynamics.md)")
      .def_readonly("omega", &dynamics::Modes::omega, "undamped angular frequencies [rad/s], ascending")
      .def_readonly("frequency", &dynamics::Modes::frequency_hz, "undamped natural frequencies [Hz]")
      .def_readonly("damped_frequency", &dynamics::Modes::damped_frequency_hz, "damped frequencies [Hz]")
      .def_readonly("damping_ratio", &dynamics::Modes::damping_ratio, "damping ratio of each mode")
      .def_readonly("torsion_fraction", &dynamics::Modes::torsion_fraction,
                    "fraction of each mode's elastic energy in twist (0: bending, 1: torsion)")
      .def_readonly("joint_shapes", &dynamics::Modes::joint_shapes,
                    "(3N, modes) joint rotation vectors in B, mass-normalised")
      .def_readonly("node_shapes_flat", &dynamics::Modes::node_shapes,
                    "(3(N+1), modes) node displacements in B, largest node displacement 1")
      .def_readonly("joint_damping_time", &dynamics::Modes::damping_time, "beta [s] of the joint dampers")
      .def("__len__", &dynamics::Modes::count);
  m.def(
      "_modes",
      [](const Whisker& w, const std::string& text, int count) {
        const io::DynamicsCase c = settings(w, text);
        io::CaseModes cm;
        {
          py::gil_scoped_release release;
          cm = io::case_modes(c, count > 0 ? count : c.mode_count);
        }
        return py::make_tuple(cm.modes, cm.deflected ? io::equilibrium_to_json(cm, w).dump() : std::string());
      },
      py::arg("whisker"), py::arg("settings_json"), py::arg("count"));
  py::class_<DynamicsRun>(m, "_DynamicsRun")
      .def_property_readonly("status", [](const DynamicsRun& r) { return std::string(to_string(r.series.status)); })
      .def_property_readonly("steps", [](const DynamicsRun& r) { return r.series.steps; })
      .def_property_readonly("rejected_steps", [](const DynamicsRun& r) { return r.series.rejected_steps; })
      .def_property_readonly("modes", [](const DynamicsRun& r) { return r.modes; })
      .def("summary_json", [](const DynamicsRun& r) { return r.summary.dump(2); })
      .def("datasets", [](const DynamicsRun& r) { return labelled_arrays(io::dynamics_data(r.series)); })
      .def("labelled", [](const DynamicsRun& r) { return labelled_description(io::dynamics_data(r.series)); })
      .def(
          "write", [](const DynamicsRun& r, const std::string& dir) { io::write_dynamics_outputs(r.series, r.summary, dir); },
          py::arg("folder"));
  m.def(
      "_simulate_dynamics",
      [](const Whisker& w, const std::string& text,
         const std::vector<std::tuple<std::size_t, std::shared_ptr<Shape>, bool, double>>& shapes) {
        io::DynamicsCase c = settings(w, text);
        // Shapes given as objects (vibrissa.Sphere(...), Mesh.from_file(...)), at their places in the list (in
        // increasing order; the JSON text has the others).
        for (const auto& [index, shape, thickness, mu] : shapes) {
          if (!shape) throw std::invalid_argument("objects[" + std::to_string(index) + "]: no shape given");
          if (index > c.options.objects.size())
            throw std::invalid_argument("objects[" + std::to_string(index) + "]: out of order");
          try {
            c.options.objects.insert(c.options.objects.begin() + static_cast<std::ptrdiff_t>(index),
                                     dynamics::obstacle(shape, ObjectPose{}, thickness, mu));
          } catch (const std::invalid_argument& e) {
            throw std::invalid_argument("objects[" + std::to_string(index) + "]: " + e.what());
          }
        }
        py::gil_scoped_release release;
        const dynamics::LinearModel model = dynamics::linear_model(c.whisker, c.properties);
        DynamicsRun run{{}, dynamics::modes(model, c.whisker), {}};
        run.series = dynamics::simulate(c.whisker, model, run.modes, io::base_trajectory(c), c.properties.gravity_W,
                                        c.options, io::initial_state(c, model), io::external_load(c));
        run.summary = io::dynamics_summary(run.series, run.modes, c);
        return run;
      },
      py::arg("whisker"), py::arg("settings_json"),
      py::arg("shapes") = std::vector<std::tuple<std::size_t, std::shared_ptr<Shape>, bool, double>>{});
}

}  // namespace vibrissa::python
