#include "labelled.hpp"

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <cstring>

namespace vibrissa::python {

namespace {

py::object values_array(const io::LabelledVariable& v) {
  const std::vector<py::ssize_t> shape(v.shape.begin(), v.shape.end());
  return std::visit(
      [&](const auto& values) -> py::object {
        using T = typename std::decay_t<decltype(values)>::value_type;
        if constexpr (std::is_same_v<T, std::string>) {
          return py::module_::import("numpy").attr("array")(py::cast(std::vector<std::string>(values.begin(), values.end())),
                                                            "U");
        } else {
          py::array_t<T> a(shape);
          if (!values.empty()) std::memcpy(a.mutable_data(), values.data(), values.size() * sizeof(T));
          return a;
        }
      },
      v.values);
}

}  // namespace

py::dict labelled_arrays(const io::LabelledData& data) {
  py::dict out;
  for (const io::LabelledVariable& v : data.variables) out[py::str(v.name)] = values_array(v);
  return out;
}

py::dict labelled_description(const io::LabelledData& data) {
  py::list variables, attributes;
  for (const io::LabelledVariable& v : data.variables) {
    py::dict attrs;
    attrs["units"] = v.units;
    if (!v.long_name.empty()) attrs["long_name"] = v.long_name;
    if (!v.codes.empty()) attrs["codes"] = v.codes;
    variables.append(py::make_tuple(v.name, py::tuple(py::cast(v.dims)), attrs, values_array(v)));
  }
  for (const io::LabelledAttribute& a : data.attributes)
    attributes.append(py::make_tuple(a.group, a.name, std::visit([](const auto& x) { return py::cast(x); }, a.value)));
  py::dict out;
  out["variables"] = variables;
  out["attributes"] = attributes;
  return out;
}

}  // namespace vibrissa::python
