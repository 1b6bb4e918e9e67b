#pragma once
// Names kept for one release after a rename (docs/python.md, "Deprecated names"): the old name still works and
// emits a DeprecationWarning naming its replacement.
#include <string>

#include <pybind11/pybind11.h>

namespace vibrissa::python {

namespace py = pybind11;

/// The release that removes every deprecated name.
inline constexpr const char* kDeprecatedNamesRemovedIn = "0.2.0";

/// Emits a DeprecationWarning: "`old_name` is deprecated ...; use `new_name`".
inline void warn_deprecated(const std::string& old_name, const std::string& new_name) {
  const std::string msg = old_name + " is deprecated and will be removed in vibrissa " +
                          kDeprecatedNamesRemovedIn + "; use " + new_name;
  if (PyErr_WarnEx(PyExc_DeprecationWarning, msg.c_str(), 1) != 0) throw py::error_already_set();
}

/// A read-only property getter returning attribute `new_name` of self after warning that `old_name` is deprecated.
/// Both arguments must be string literals (they are kept by pointer).
inline py::cpp_function deprecated_alias(const char* old_name, const char* new_name) {
  return py::cpp_function([old_name, new_name](const py::object& self) -> py::object {
    warn_deprecated(old_name, new_name);
    return self.attr(new_name);
  });
}

}  // namespace vibrissa::python
