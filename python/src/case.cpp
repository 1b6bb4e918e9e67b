// Case JSON round trip (docs/formats.md): the same reader, solver and writer as `vibrissa solve`, so a case
// solved from Python gives the CLI's result exactly. Python passes JSON text (json.dumps of a dict) and
// receives JSON text back; the pure-Python layer turns it into dicts and arrays.
#include <pybind11/stl.h>

#include <filesystem>

#include "bindings.hpp"
#include "vibrissa/io/object_json.hpp"
#include "convert.hpp"
#include "vibrissa/core/plausibility.hpp"
#include "vibrissa/io/case_json.hpp"
#include "vibrissa/io/json_input.hpp"

namespace vibrissa::python {

namespace {

nlohmann::json parse(const std::string& text, const char* what) { return io::parse_json_text(text, what); }

/// Converts arrays of numbers in a JSON-derived Python dict to NumPy arrays (recursively).
py::object arrays_in(const py::object& obj) {
  static const char* vector_keys[] = {"contact_point_W", "force_W", "moment_W", "shape_W",
                                      "contact_point",   "force",   "moment",   "shape"};
  if (!py::isinstance<py::dict>(obj)) return obj;
  py::dict d = obj.cast<py::dict>();
  py::dict out;
  py::module_ np = py::module_::import("numpy");
  for (auto item : d) {
    const std::string key = item.first.cast<std::string>();
    py::object value = py::reinterpret_borrow<py::object>(item.second);
    if (py::isinstance<py::dict>(value)) {
      out[item.first] = arrays_in(value);
      continue;
    }
    bool is_vector = false;
    for (const char* k : vector_keys) is_vector = is_vector || key == k;
    if (is_vector && py::isinstance<py::list>(value)) {
      py::object a = np.attr("asarray")(value, py::arg("dtype") = "float64");
      if (key == "shape" || key == "shape_W") a = a.attr("reshape")(-1, 3);
      out[item.first] = a;
    } else {
      out[item.first] = value;
    }
  }
  return out;
}

py::dict load_to_dict(const Load& load) {
  py::dict d;
  std::visit(
      [&](const auto& l) {
        using T = std::decay_t<decltype(l)>;
        auto opt3 = [](const std::optional<Eigen::Vector3d>& v) {
          return v ? py::object(to_array(*v)) : py::object(py::none());
        };
        if constexpr (std::is_same_v<T, ForceLoad>) {
          d["mode"] = "force";
          d["force"] = l.force;
          d["arc_length"] = l.arc_length;
          d["angle"] = l.angle;
        } else if constexpr (std::is_same_v<T, DeadLoad>) {
          d["mode"] = "dead_load";
          d["force"] = to_array(l.force);
          d["arc_length"] = l.arc_length;
        } else if constexpr (std::is_same_v<T, PointLoad>) {
          d["mode"] = "point";
          d["point"] = to_array(l.point);
          d["arc_length_hint"] = l.arc_length_hint;
          d["edge_direction"] = opt3(l.edge_direction);
        } else if constexpr (std::is_same_v<T, EdgeLoad>) {
          d["mode"] = "edge";
          d["point"] = to_array(l.edge.point);
          d["direction"] = to_array(l.edge.direction);
          d["arc_length_hint"] = l.arc_length_hint;
          d["approach"] = opt3(l.approach);
        } else if constexpr (std::is_same_v<T, BaseWrenchLoad>) {
          d["mode"] = "base_wrench";
          d["force"] = to_array(l.force);
          d["moment"] = to_array(l.moment);
          d["signals"] = l.signals.name();
        } else if constexpr (std::is_same_v<T, ObjectLoad>) {
          d["mode"] = "object";
          d["object"] = py::module_::import("json").attr("loads")(io::shape_to_json(*l.shape).dump());
          d["thickness"] = l.thickness;
          d["friction_coefficient"] = l.friction_coefficient;
          d["previous_contact"] = opt3(l.previous_contact);
          d["arc_length_hint"] = l.arc_length_hint;
          d["approach"] = opt3(l.approach);
        } else {
          d["mode"] = "frictional_edge";
          d["point"] = to_array(l.edge.point);
          d["direction"] = to_array(l.edge.direction);
          d["friction_coefficient"] = l.friction_coefficient;
          d["previous_contact"] = to_array(l.previous_contact);
          d["approach"] = opt3(l.approach);
        }
      },
      load);
  return d;
}

}  // namespace

std::string solution_json_text(const Solution& s, int indent) { return solution_to_json(s).dump(indent); }

py::dict solution_to_dict(const Solution& s) {
  py::object loaded = py::module_::import("json").attr("loads")(solution_to_json(s).dump());
  return arrays_in(loaded).cast<py::dict>();
}

void bind_case(py::module_& m) {
  py::class_<Case>(m, "Case",
                   "A case of `vibrissa solve` (docs/formats.md): a whisker, a load and solve options, read by the "
                   "same code as the CLI. Build one with Case.from_json / Case.from_file or vibrissa.load_case (path, JSON text or dict).")
      .def_static(
          "from_json", [](const std::string& text) { return case_from_json(parse(text, "case")); }, py::arg("text"),
          "Parses a case from JSON text; ValueError naming the field for an invalid case.")
      .def_static(
          "from_file",
          [](const std::string& path) {
            return case_from_json(io::resolve_input_paths(read_json_file(path), std::filesystem::path(path).parent_path()));
          },
          py::arg("path"),
          "Reads a case file (JSON); errors name the file or the field.")
      .def_readonly("whisker", &Case::whisker, "The Whisker of the case.")
      .def_readwrite("options", &Case::options, "SolveOptions (find_other_roots defaults to True for cases).")
      .def_property_readonly(
          "mode",
          [](const Case& c) { return load_to_dict(c.load)["mode"].cast<std::string>(); },
          "The load mode: force, dead_load, point, edge or frictional_edge.")
      .def_property_readonly("load", [](const Case& c) { return load_to_dict(c.load); },
                             "The load as a dict with the JSON field names (vectors as arrays).")
      .def(
          "solve",
          [](const Case& c) {
            py::gil_scoped_release release;
            return solve_case(c);
          },
          "Solves the case exactly as `vibrissa solve` does.")
      .def_property_readonly(
          "warnings", [](const Case& c) { return case_warnings(c); },
          "Plausibility warnings of the case (a likely unit slip of the whisker, pose or load; docs/conventions.md), "
          "as `vibrissa solve` prints them.")
      .def("__repr__", [](const Case& c) {
        return "Case(mode=" + load_to_dict(c.load)["mode"].cast<std::string>() +
               ", links=" + std::to_string(c.whisker.links()) + ")";
      });

  m.def(
      "solve_case", [](const Case& c) {
        py::gil_scoped_release release;
        return solve_case(c);
      },
      py::arg("case"), "Solves a Case exactly as `vibrissa solve` does.");
  m.def(
      "whisker_from_json",
      [](const std::string& text) {
        std::vector<std::string> warnings;
        Whisker w = whisker_from_json(parse(text, "whisker"), &warnings);
        std::vector<std::string> all = plausibility_warnings(w);
        all.insert(all.end(), warnings.begin(), warnings.end());
        warn_all(all);
        return w;
      },
      py::arg("text"),
      "A Whisker from the JSON text of a case's \"whisker\" object (docs/formats.md); plausibility warnings "
      "(a likely unit slip) are raised with warnings.warn.");
  m.def(
      "solution_to_json", &solution_json_text,
      py::arg("solution"), py::arg("indent") = 2,
      "The result JSON text of `vibrissa solve` for this solution (indent=-1: one line).");
  m.def(
      "write_result", [](const std::string& path, const Solution& s) { write_json_file(path, solution_to_json(s)); },
      py::arg("path"), py::arg("solution"),
      "Writes the Solution's JSON (without the case's warnings) atomically.");
  m.def(
      "write_case_result",
      [](const std::string& path, const Case& c, const Solution& s) { write_json_file(path, case_result_to_json(c, s)); },
      py::arg("path"), py::arg("case"), py::arg("solution"),
      "Writes the result file exactly as `vibrissa solve -o PATH` does (atomically, with \"warnings\").");
}

}  // namespace vibrissa::python
