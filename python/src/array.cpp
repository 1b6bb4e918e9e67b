// Array simulations from Python (docs/python.md, "Whisker arrays"): the configuration of `vibrissa array`
// (a dict, a file or the built-in default), the same config reader and simulation as the CLI, run through
// run_interruptible (GIL released, Ctrl-C, progress). The arrays handed to Python carry the names, shapes and
// dtypes of array.h5: both come from one table, io::array_data (python/tests/test_pipeline.py checks them
// against the file).
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <filesystem>

#include "bindings.hpp"
#include "convert.hpp"
#include "interruptible.hpp"
#include "labelled.hpp"
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

nlohmann::json parse_config(const std::string& text) { return io::parse_json_text(text, "array config", true); }

}  // namespace

void bind_array(py::module_& m) {
  py::class_<ArrayRun>(m, "_ArrayRun")
      .def("datasets", [](const ArrayRun& r) { return labelled_arrays(io::array_data(r.result, r.config)); })
      .def("labelled", [](const ArrayRun& r) { return labelled_description(io::array_data(r.result, r.config)); })
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

  m.def(
      "_check_array_config",
      [](const std::string& text) { (void)io::array_config_from_json(parse_config(text), std::filesystem::current_path()); },
      "Reads an array configuration as simulate_array would, without simulating: ValueError naming the field.");

  m.def(
      "_resolve_input_paths",
      [](const std::string& text, const std::string& base_dir) {
        return io::resolve_input_paths(io::parse_json_text(text, "configuration"), base_dir).dump();
      },
      py::arg("text"), py::arg("base_dir"),
      "The JSON text with the files it names (morphology table, meshes) made absolute against base_dir: the "
      "readers' one rule (io::resolve_input_paths, docs/formats.md \"Paths\").");

  m.def("default_array_config_json", [] { return io::default_array_config_json().dump(); },
        "The built-in configuration of `vibrissa array` as JSON text (= --print-default-config).");

  m.def(
      "_simulate_array",
      [](const std::optional<std::string>& config_text, const std::optional<std::string>& path,
         const py::object& threads, const py::object& progress, bool dynamics) {
        namespace fs = std::filesystem;
        ArrayRun run;
        fs::path base = fs::current_path();
        if (path) {
          run.config_json = io::read_array_config_json(*path);
          base = fs::path(*path).parent_path();
        } else {
          run.config_json = config_text ? parse_config(*config_text) : io::default_array_config_json();
        }
        // config.json (ArrayResult.write) names its files absolutely, as `vibrissa array` writes it
        run.config_json = io::resolve_input_paths(run.config_json, base);
        if (!threads.is_none()) {
          const int n = thread_count_arg(threads, 0);
          if (n > 0) run.config_json["threads"] = n;
        }
        if (dynamics && !run.config_json.contains("dynamics")) run.config_json["dynamics"] = nlohmann::json::object();
        run.config = io::array_config_from_json(run.config_json, base);
        run.result = run_interruptible(
            [&](const RunControl& control) { return array::simulate_array(run.config, control); }, progress);
        return run;
      },
      py::arg("config_text"), py::arg("path"), py::arg("threads"), py::arg("progress"), py::arg("dynamics") = false);
}

}  // namespace vibrissa::python
