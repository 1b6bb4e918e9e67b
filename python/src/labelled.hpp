#pragma once
// Labelled outputs (io/labelled_data.hpp) for Python: the same variables as the HDF5 file, as NumPy arrays with
// their dimension names and attributes, from which python/vibrissa/labelled.py builds xarray Datasets.
#include <pybind11/pybind11.h>

#include "vibrissa/io/labelled_data.hpp"

namespace vibrissa::python {

namespace py = pybind11;

/// {path: array} of every variable (strings as a NumPy "U" array), in table order.
py::dict labelled_arrays(const io::LabelledData& data);
/// {"variables": [(path, dims, attrs, array), ...], "attributes": [(group, name, value), ...]}.
py::dict labelled_description(const io::LabelledData& data);

}  // namespace vibrissa::python
