// The compiled half of the `vibrissa` Python package (docs/python.md). The pure-Python layer in
// python/vibrissa/ re-exports everything defined here and adds conveniences.
#include "bindings.hpp"

#ifndef VIBRISSA_VERSION
#define VIBRISSA_VERSION "unknown"
#endif

PYBIND11_MODULE(_vibrissa, m) {
  m.doc() =
      "Quasi-static 3D mechanics of rat whiskers (Huet & Hartmann 2016): compiled core. Import `vibrissa`, "
      "not this module. SI units throughout: m, N, N·m, Pa, rad.";
  m.attr("__version__") = VIBRISSA_VERSION;
  vibrissa::python::bind_core(m);
  vibrissa::python::bind_solve(m);
  vibrissa::python::bind_objects(m);
  vibrissa::python::bind_contact(m);
  vibrissa::python::bind_batch(m);
  vibrissa::python::bind_inverse(m);
  vibrissa::python::bind_case(m);
  vibrissa::python::bind_trial(m);
  vibrissa::python::bind_array(m);
  vibrissa::python::bind_recon(m);
  vibrissa::python::bind_dynamics(m);
}
