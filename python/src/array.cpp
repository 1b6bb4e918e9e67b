// Array simulations from Python (docs/python.md, "Whisker arrays"): the configuration of `vibrissa array`
// (a dict, a file or the built-in default), the same config reader and simulation as the CLI, run through
// run_interruptible (GIL released, Ctrl-C, progress). The arrays handed to Python carry the names, shapes and
// dtypes of array.h5 (io/array_outputs.hpp; python/tests/test_pipeline.py checks them against the file).
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <cstring>
#include <filesystem>

#include "bindings.hpp"
#include "convert.hpp"
#include "interruptible.hpp"
#include "vibrissa/io/array_config.hpp"
#include "vibrissa/io/array_outputs.hpp"
#include "vibrissa/io/json_input.hpp"

namespace vibrissa::python {

namespace {

struct ArrayRun {
  nlohmann::json config_json;  ///< the configuration used (config.json)
  array::SimulationConfig config;
  array::ArrayResult result;
};

template <class T>
py::array_t<T> shaped(const std::vector<T>& v, std::vector<py::ssize_t> shape) {
  py::array_t<T> a(shape);
  if (!v.empty()) std::memcpy(a.mutable_data(), v.data(), v.size() * sizeof(T));
  return a;
}

/// The datasets of array.h5 by name ("render/..." for the render group), [pitch][whisker][frame] layout.
py::dict array_datasets(const ArrayRun& run) {
  const array::ArrayResult& r = run.result;
  const auto P = static_cast<py::ssize_t>(r.n_pitches), W = static_cast<py::ssize_t>(r.n_whiskers),
             F = static_cast<py::ssize_t>(r.n_frames), N = static_cast<py::ssize_t>(r.n_nodes),
             R = static_cast<py::ssize_t>(r.render_frames.size()), E = static_cast<py::ssize_t>(r.n_edges);
  std::vector<std::int8_t> side, row, column;
  for (const array::WhiskerSpec& s : run.config.morphology.whiskers) {
    side.push_back(s.side == array::Side::right ? 1 : -1);
    row.push_back(static_cast<std::int8_t>(s.row));
    column.push_back(static_cast<std::int8_t>(s.column));
  }
  py::dict d;
  d["time"] = shaped(r.times, {F});
  d["pitch"] = shaped(r.pitches, {P});
  d["whisker"] = py::module_::import("numpy").attr("array")(py::cast(r.labels), "U");
  d["side"] = shaped(side, {W});
  d["row"] = shaped(row, {W});
  d["column"] = shaped(column, {W});
  d["state"] = shaped(r.state, {P, W, F});
  d["solver_status"] = shaped(r.solver_status, {P, W, F});
  d["edge_index"] = shaped(r.edge, {P, W, F});
  d["s_applied"] = shaped(r.s_applied, {P, W, F});
  d["contact_point_W"] = shaped(r.contact_W, {P, W, F, 3});
  d["force_W"] = shaped(r.force_W, {P, W, F, 3});
  d["moment_W"] = shaped(r.moment_W, {P, W, F, 3});
  d["force_B"] = shaped(r.force_B, {P, W, F, 3});
  d["moment_B"] = shaped(r.moment_B, {P, W, F, 3});
  d["FT"] = shaped(r.FT, {P, W, F});
  d["MB"] = shaped(r.MB, {P, W, F});
  d["FD"] = shaped(r.FD, {P, W, F});
  d["MD"] = shaped(r.MD, {P, W, F});
  d["normal_force"] = shaped(r.normal_force, {P, W, F});
  d["edge_force"] = shaped(r.edge_force, {P, W, F});
  d["z_edge"] = shaped(r.z_edge, {P, W, F});
  d["z_error"] = shaped(r.z_error, {P, W, F});
  d["base_W"] = shaped(r.base_W, {P, W, F, 3});
  d["theta"] = shaped(r.theta, {W, F});
  d["phi"] = shaped(r.phi, {W, F});
  d["zeta"] = shaped(r.zeta, {W, F});
  d["render/frame"] = shaped(r.render_frames, {R});
  d["render/rest"] = shaped(r.rest_shapes, {R, W, N, 3});
  d["render/deflected"] = shaped(r.deflected_shapes, {R, W, N, 3});
  d["render/edges"] = shaped(r.render_edges, {R, E, 2, 3});
  d["render/object_poses"] = shaped(r.render_object_poses, {R, static_cast<py::ssize_t>(r.n_objects), 12});
  return d;
}

nlohmann::json parse_config(const std::string& text) { return io::parse_json_text(text, "array config", true); }

}  // namespace

void bind_array(py::module_& m) {
  py::class_<ArrayRun>(m, "_ArrayRun")
      .def("datasets", &array_datasets)
      .def("summary_json", [](const ArrayRun& r) { return io::array_summary_json(r.result, r.config).dump(); })
      .def("config_json", [](const ArrayRun& r) { return r.config_json.dump(); })
      .def_property_readonly("wall_seconds", [](const ArrayRun& r) { return r.result.wall_seconds; })
      .def_property_readonly("solves", [](const ArrayRun& r) { return r.result.solves; })
      .def(
          "write",
          [](const ArrayRun& r, const std::string& dir, bool csv) {
            py::gil_scoped_release release;
            io::write_array_outputs(r.result, r.config, r.config_json, dir, io::ArrayOutputOptions{csv});
          },
          py::arg("dir"), py::arg("csv") = false);

  m.def("default_array_config_json", [] { return io::default_array_config_json().dump(); },
        "The built-in configuration of `vibrissa array` as JSON text (= --print-default-config).");

  m.def(
      "_simulate_array",
      [](const std::optional<std::string>& config_text, const std::optional<std::string>& path,
         const py::object& threads, const py::object& progress) {
        namespace fs = std::filesystem;
        ArrayRun run;
        fs::path base = fs::current_path();
        if (path) {
          run.config_json = io::read_array_config_json(*path);
          base = fs::path(*path).parent_path();
        } else {
          run.config_json = config_text ? parse_config(*config_text) : io::default_array_config_json();
        }
        if (!threads.is_none()) {
          const int n = thread_count_arg(threads, 0);
          if (n > 0) run.config_json["threads"] = n;
        }
        run.config = io::array_config_from_json(run.config_json, base);
        run.result = run_interruptible(
            [&](const RunControl& control) { return array::simulate_array(run.config, control); }, progress);
        return run;
      },
      py::arg("config_text"), py::arg("path"), py::arg("threads"), py::arg("progress"));
}

}  // namespace vibrissa::python
