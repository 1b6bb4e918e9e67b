// HDF5 trial files (docs/trials.md): one dataset per array at the root, units and metadata as root attributes;
// written labelled (io/labelled_data.hpp): dimensions time, component, node, rest_node, edge, edge_component.
#include <algorithm>
#include <map>
#include <stdexcept>

#include "h5_file.hpp"
#include "vibrissa/core/checks.hpp"
#include "trial_arrays.hpp"
#include "vibrissa/io/atomic_file.hpp"
#include "vibrissa/io/labelled_data.hpp"
#include "vibrissa/io/trial_io.hpp"

namespace vibrissa::io {

namespace {

// Coordinate variables of the dimensions a written trial file labels its arrays with; the reader skips them.
constexpr const char* kCoordinateNames[] = {"component", "node", "rest_node", "edge", "edge_component"};

struct ArrayLabels {
  std::vector<std::string> dims;
  const char* long_name;
};

// Dimensions and description of every array a trial file may hold (trial_array_names).
const std::map<std::string, ArrayLabels>& array_labels() {
  static const std::map<std::string, ArrayLabels> labels = {
      {"time", {{"time"}, "time of the frame"}},
      {"base", {{"time", "component"}, "whisker base point, world frame"}},
      {"theta", {{"time"}, "protraction angle theta"}},
      {"phi", {{"time"}, "elevation angle phi"}},
      {"zeta", {{"time"}, "roll angle zeta"}},
      {"contact", {{"time"}, "1 while the whisker touches the object, else 0"}},
      {"contact_point", {{"time", "component"}, "tracked contact point, world frame"}},
      {"shape", {{"time", "node", "component"}, "tracked whisker shape, base first, world frame (NaN-padded)"}},
      {"rest_shape", {{"rest_node", "component"}, "rest shape of the whisker, base first"}},
      {"edges", {{"edge", "edge_component"}, "object edges: a point [m] and a unit direction"}},
      {"reconstructed", {{"time"}, "1 where the frame was reconstructed from the camera views, else 0"}},
      {"reprojection_px", {{"time"}, "RMS reprojection error of the tracked points used"}},
      {"likelihood", {{"time"}, "mean tracker likelihood of the points used"}}};
  return labels;
}

LabelledData trial_file_data(const TrialArrays& arrays) {
  LabelledData d;
  for (const auto& [name, a] : arrays.arrays) {
    const ArrayLabels& labels = array_labels().at(name);
    d.variables.push_back({.name = name, .dims = labels.dims, .shape = a.dims, .values = std::span(a.data),
                           .units = a.units, .long_name = labels.long_name});
  }
  d.add_component_coordinate();
  for (const LabelledVariable& v : std::vector<LabelledVariable>(d.variables))
    for (std::size_t i = 0; i < v.dims.size(); ++i) {
      const bool listed = std::any_of(d.variables.begin(), d.variables.end(),
                                      [&](const LabelledVariable& c) { return c.name == v.dims[i]; });
      if (listed) continue;
      if (v.dims[i] == "edge_component")
        d.add_owned({.name = "edge_component", .dims = {"edge_component"}, .shape = {6}, .units = "text",
                     .long_name = "column of an edge: its point (x, y, z) and its direction (x, y, z)"},
                    std::vector<std::string>{"point_x", "point_y", "point_z", "direction_x", "direction_y",
                                             "direction_z"});
      else
        d.add_index_coordinate("", v.dims[i], v.shape[i],
                               v.dims[i] == "edge" ? "object edge" : "point of the shape (0: base)");
    }
  for (const auto& [name, text] : arrays.texts) d.attributes.push_back({"", name, text});
  for (const auto& [name, value] : arrays.numbers) d.attributes.push_back({"", name, value});
  return d;
}

}  // namespace

trial::Trial read_trial_h5(const std::string& path) {
  h5::QuietErrors quiet;
  h5::Handle file = h5::open_file_read(path);
  const hid_t root = file.get();
  for (const std::string& name : h5::member_names(root)) {
    bool known = false;
    for (const char* k : trial_array_names) known = known || name == k;
    for (const char* k : kCoordinateNames) known = known || name == k;
    if (!known) {
      std::string expected;
      for (const char* k : trial_array_names) expected += std::string(expected.empty() ? "" : ", ") + k;
      throw std::invalid_argument(
          trial::located_message(path, 0, quote_text(name), "unknown dataset (expected one of " + expected + ")"));
    }
  }
  ArrayReader r;
  r.source = path;
  r.array = [&](const std::string& name) -> std::optional<NamedArray> {
    if (!h5::has_dataset(root, name)) return std::nullopt;
    std::vector<hsize_t> dims;
    NamedArray a;
    a.data = h5::read_doubles(root, name, dims, path);
    for (hsize_t d : dims) a.dims.push_back(static_cast<std::size_t>(d));
    return a;
  };
  r.text = [&](const std::string& name) { return h5::read_string_attribute(root, name, path); };
  r.number = [&](const std::string& name) { return h5::read_double_attribute(root, name, path); };
  return assemble_trial(r);
}

void write_trial_h5(const trial::Trial& t, const std::string& path) {
  const TrialArrays arrays = disassemble_trial(t);
  LabelledData data = trial_file_data(arrays);
  data.attributes.insert(data.attributes.begin(), {{"", "format", "vibrissa-trial"}, {"", "format_version", 2.0}});
  write_atomically(path, [&](const std::string& tmp) { write_labelled_h5(data, tmp); });
}

}  // namespace vibrissa::io
