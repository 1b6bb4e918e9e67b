#include "convert.hpp"

#include <cstring>
#include <sstream>

#include "vibrissa/core/limits.hpp"

namespace vibrissa::python {

std::string shape_string(const py::array& a) {
  std::ostringstream os;
  os << '(';
  for (py::ssize_t i = 0; i < a.ndim(); ++i) {
    if (i) os << ", ";
    os << a.shape(i);
  }
  if (a.ndim() == 1) os << ',';
  os << ')';
  return os.str();
}

DoubleArray as_double_array(py::handle obj, const char* name) {
  if (obj.is_none()) throw py::value_error(std::string(name) + " must be an array of numbers, got None");
  if (const py::array raw = py::array::ensure(obj); raw && raw.dtype().kind() == 'c')
    throw py::value_error(std::string(name) + " must be real, got complex values (dtype " +
                          std::string(py::str(raw.dtype())) + ")");
  DoubleArray a = DoubleArray::ensure(obj);  // null (error cleared) when not convertible
  if (!a)
    throw py::value_error(std::string(name) + " must be an array of real numbers, got " +
                          std::string(py::str(py::type::handle_of(obj).attr("__name__"))));
  return a;
}

Eigen::Vector3d vec3(py::handle obj, const char* name) {
  const DoubleArray a = as_double_array(obj, name);
  if (a.ndim() != 1 || a.shape(0) != 3)
    throw py::value_error(std::string(name) + " must have shape (3,), got " + shape_string(a));
  return {a.at(0), a.at(1), a.at(2)};
}

std::optional<Eigen::Vector3d> optional_vec3(const py::object& obj, const char* name) {
  if (obj.is_none()) return std::nullopt;
  return vec3(obj, name);
}

std::vector<Eigen::Vector3d> points3(py::handle obj, const char* name) {
  const DoubleArray a = as_double_array(obj, name);
  if (a.ndim() != 2 || a.shape(1) != 3)
    throw py::value_error(std::string(name) + " must have shape (N, 3), got " + shape_string(a));
  std::vector<Eigen::Vector3d> out(static_cast<std::size_t>(a.shape(0)));
  const double* p = a.data();
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = Eigen::Vector3d(p[3 * i], p[3 * i + 1], p[3 * i + 2]);
  return out;
}

std::vector<double> vector1(py::handle obj, const char* name) {
  const DoubleArray a = as_double_array(obj, name);
  if (a.ndim() != 1) throw py::value_error(std::string(name) + " must be 1-D, got shape " + shape_string(a));
  return {a.data(), a.data() + a.shape(0)};
}

int thread_count_arg(const py::handle& threads, int min_value) {
  PyObject* index = py::isinstance<py::bool_>(threads) ? nullptr : PyNumber_Index(threads.ptr());  // int, numpy ints
  if (!index) {
    PyErr_Clear();
    throw py::value_error("threads must be an int or None, got " +
                          std::string(py::str(py::type::handle_of(threads).attr("__name__"))));
  }
  int overflow = 0;
  const long long n = PyLong_AsLongLongAndOverflow(index, &overflow);
  Py_DECREF(index);
  if (overflow != 0 || n < min_value || n > limits::max_threads)
    throw py::value_error("threads must lie in [" + std::to_string(min_value) + ", " +
                          std::to_string(limits::max_threads) + "], got " +
                          (overflow ? std::string(py::str(threads)) : std::to_string(n)));
  return static_cast<int>(n);
}

py::array_t<double> to_array(const Eigen::Vector3d& v) {
  py::array_t<double> out(3);
  std::memcpy(out.mutable_data(), v.data(), 3 * sizeof(double));
  return out;
}

py::array_t<double> to_array(const Eigen::Matrix3d& m) {
  py::array_t<double> out({py::ssize_t{3}, py::ssize_t{3}});
  auto r = out.mutable_unchecked<2>();
  for (py::ssize_t i = 0; i < 3; ++i)
    for (py::ssize_t j = 0; j < 3; ++j) r(i, j) = m(i, j);
  return out;
}

py::array_t<double> to_array(const std::vector<Eigen::Vector3d>& rows) {
  py::array_t<double> out({static_cast<py::ssize_t>(rows.size()), py::ssize_t{3}});
  double* p = out.mutable_data();
  for (std::size_t i = 0; i < rows.size(); ++i) std::memcpy(p + 3 * i, rows[i].data(), 3 * sizeof(double));
  return out;
}

py::array_t<double> to_array(const std::vector<double>& values) {
  py::array_t<double> out(static_cast<py::ssize_t>(values.size()));
  if (!values.empty()) std::memcpy(out.mutable_data(), values.data(), values.size() * sizeof(double));
  return out;
}

void warn_all(const std::vector<std::string>& messages) {
  for (const std::string& m : messages)
    if (PyErr_WarnEx(PyExc_UserWarning, m.c_str(), 1) != 0) throw py::error_already_set();
}

}  // namespace vibrissa::python
