#pragma once
// NumPy <-> Eigen conversions for the bindings. Every input goes through one of these helpers so that any
// array-like (list, tuple, float32, non-contiguous view) is accepted and a wrong shape raises ValueError
// naming the argument and the shape it got.
#include <optional>
#include <string>
#include <vector>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <Eigen/Core>

namespace vibrissa::python {

namespace py = pybind11;

/// Row-major float64 array, converted (copied) from anything array-like.
using DoubleArray = py::array_t<double, py::array::c_style | py::array::forcecast>;

/// "(5, 2)" for an array of that shape.
std::string shape_string(const py::array& a);

/// Converts `obj` to a C-contiguous float64 array; ValueError naming `name` if it cannot be (complex data
/// included: the imaginary part is never dropped silently).
DoubleArray as_double_array(py::handle obj, const char* name);

/// A 3-vector [x, y, z]; ValueError naming `name` unless `obj` has shape (3,).
Eigen::Vector3d vec3(py::handle obj, const char* name);
std::optional<Eigen::Vector3d> optional_vec3(const py::object& obj, const char* name);

/// Rows of an (N, 3) array; ValueError naming `name` for any other shape.
std::vector<Eigen::Vector3d> points3(py::handle obj, const char* name);

/// A 1-D array of floats; ValueError naming `name` for any other shape.
std::vector<double> vector1(py::handle obj, const char* name);

/// A thread count: a Python int in [min_value, limits::max_threads]; ValueError naming "threads" otherwise.
int thread_count_arg(const py::handle& threads, int min_value);

/// Raises each message with Python's warnings.warn (UserWarning, attributed to the caller); an exception
/// (the warning filter set to "error") propagates as py::error_already_set. Needs the GIL.
void warn_all(const std::vector<std::string>& messages);

/// New NumPy arrays (they own their memory).
py::array_t<double> to_array(const Eigen::Vector3d& v);
py::array_t<double> to_array(const Eigen::Matrix3d& m);
py::array_t<double> to_array(const std::vector<Eigen::Vector3d>& rows);
py::array_t<double> to_array(const std::vector<double>& values);

}  // namespace vibrissa::python
