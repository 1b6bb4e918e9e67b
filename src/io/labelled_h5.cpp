// Labelled HDF5 outputs (io/labelled_data.hpp, docs/formats.md "Labelled HDF5 outputs"): netCDF-4's view of an
// HDF5 file is dimension scales (a coordinate variable per dimension, attached to every dataset using it) and
// variable-length strings; with both, xarray.open_dataset reads the file with either engine.
#include <map>
#include <type_traits>
#include <stdexcept>

#include "h5_file.hpp"
#include "vibrissa/core/checks.hpp"
#include "vibrissa/io/labelled_data.hpp"

namespace vibrissa::io {

void LabelledData::add_index_coordinate(const std::string& group, const std::string& name, std::size_t size,
                                        std::string long_name) {
  std::vector<int> index(size);
  for (std::size_t i = 0; i < size; ++i) index[i] = static_cast<int>(i);
  add_owned(LabelledVariable{.name = group.empty() ? name : group + "/" + name,
                             .dims = {name},
                             .shape = {size},
                             .values = {},
                             .units = "1",
                             .long_name = std::move(long_name)},
            std::move(index));
}

void LabelledData::add_component_coordinate(const std::string& name) {
  add_owned(LabelledVariable{.name = name,
                             .dims = {name},
                             .shape = {3},
                             .values = {},
                             .units = "text",
                             .long_name = "vector component (x, y, z axes of the frame the variable's name gives)"},
            std::vector<std::string>{"x", "y", "z"});
}

const LabelledVariable& LabelledData::variable(const std::string& name) const {
  for (const LabelledVariable& v : variables)
    if (v.name == name) return v;
  throw std::out_of_range("no labelled variable '" + name + "'");
}

namespace {

std::string base_name(const std::string& path) { return path.substr(path.rfind('/') + 1); }
std::string group_of(const std::string& path) {
  const std::size_t slash = path.rfind('/');
  return slash == std::string::npos ? std::string() : path.substr(0, slash);
}

// The open groups of the file by path ("" = the root, which the file handle is).
class Groups {
 public:
  explicit Groups(hid_t file) : file_(file) {}
  hid_t get(const std::string& path) {
    if (path.empty()) return file_;
    auto found = groups_.find(path);
    if (found == groups_.end()) found = groups_.emplace(path, h5::create_group(get(group_of(path)), base_name(path))).first;
    return found->second.get();
  }
  void close() { groups_.clear(); }

 private:
  hid_t file_;
  std::map<std::string, h5::Handle> groups_;
};

void write_values(hid_t group, const LabelledVariable& v) {
  const std::vector<hsize_t> dims(v.shape.begin(), v.shape.end());
  const h5::DatasetOptions options(v.units, v.compress, v.codes, v.long_name);
  const std::string name = base_name(v.name);
  std::visit(
      [&](const auto& values) {
        using T = typename std::decay_t<decltype(values)>::value_type;
        if constexpr (std::is_same_v<T, std::string>) h5::write_strings(group, name, values, options);
        else h5::write_dataset(group, name, values, dims, options);
      },
      v.values);
}

}  // namespace

void write_labelled_h5(const LabelledData& data, const std::string& path) {
  // Every dimension: one length and one coordinate variable (one-dimensional, named as the dimension).
  std::map<std::string, std::size_t> lengths;
  std::map<std::string, const LabelledVariable*> coordinates;
  for (const LabelledVariable& v : data.variables) {
    VIBRISSA_DEMAND(v.dims.size() == v.shape.size());
    std::size_t count = 1;
    for (std::size_t i = 0; i < v.dims.size(); ++i) {
      const auto [it, added] = lengths.emplace(v.dims[i], v.shape[i]);
      VIBRISSA_DEMAND(added || it->second == v.shape[i]);
      count *= v.shape[i];
    }
    VIBRISSA_DEMAND(std::visit([](const auto& values) { return values.size(); }, v.values) == count);
    if (v.dims.size() == 1 && v.dims[0] == base_name(v.name)) coordinates.emplace(v.dims[0], &v);
  }
  for (const auto& [dim, length] : lengths) VIBRISSA_DEMAND(coordinates.count(dim) == 1);

  h5::QuietErrors quiet;
  h5::Handle file = h5::create_file(path);
  {
    Groups groups(file.get());
    for (const LabelledVariable& v : data.variables) write_values(groups.get(group_of(v.name)), v);
    for (const auto& [dim, coordinate] : coordinates) h5::make_dimension_scale(file.get(), coordinate->name);
    for (const LabelledVariable& v : data.variables) {
      if (v.dims.empty() || coordinates.at(v.dims[0]) == &v) continue;  // a coordinate variable is its own scale
      for (std::size_t i = 0; i < v.dims.size(); ++i)
        h5::attach_dimension_scale(file.get(), v.name, static_cast<unsigned>(i), file.get(),
                                   coordinates.at(v.dims[i])->name);
    }
    for (const LabelledAttribute& a : data.attributes) {
      const hid_t group = groups.get(a.group);
      if (const auto* text = std::get_if<std::string>(&a.value)) h5::write_string_attribute(group, a.name, *text);
      else h5::write_double_attribute(group, a.name, std::get<double>(a.value));
    }
    groups.close();
  }
  h5::close_file(file, path);
}

}  // namespace vibrissa::io
