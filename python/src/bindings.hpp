#pragma once
// One function per binding file; module.cpp calls them in dependency order.
#include <string>

#include <pybind11/pybind11.h>

#include "vibrissa/core/whisker.hpp"
#include "vibrissa/solve/options.hpp"
#include "vibrissa/solve/solution.hpp"

namespace vibrissa::python {

namespace py = pybind11;

void bind_core(py::module_& m);   // core.cpp: Scheme, BaseJoint, Pose, WhiskerProperties, Whisker
void bind_solve(py::module_& m);  // solve.cpp: Status, SolveOptions, Edge, LoadState, Solution, solve_*
void bind_contact(py::module_& m);  // contact.cpp: ContactMode, ContactTracker
void bind_objects(py::module_& m);  // objects.cpp: Shape, Cylinder, Plane, Sphere, Box, Mesh, solve_object
void bind_batch(py::module_& m);  // batch.cpp: solve_*_batch (GIL released, OpenMP)
void bind_inverse(py::module_& m);  // inverse.cpp: solve_base_wrench, BaseWrenchResult, the series batch
void bind_case(py::module_& m);   // case.cpp: Case JSON round trip (same code as `vibrissa solve`)
void bind_trial(py::module_& m);  // trial.cpp: Trial, read_trial, synthesis and analysis (= `vibrissa synth/trial`)
void bind_array(py::module_& m);  // array.cpp: array simulation (= `vibrissa array`)
void bind_recon(py::module_& m);  // recon.cpp: reconstruct from two tracked views (= `vibrissa reconstruct`)
void bind_dynamics(py::module_& m);  // dynamics.cpp: Modes, modes and simulate_dynamics (= `vibrissa modes/dynamics`)

/// Enum arguments accept the enum or its JSON name ("paper", "rigid", ...); ValueError otherwise.
Scheme scheme_arg(py::handle obj);
BaseJoint base_joint_arg(py::handle obj);
/// Pose argument: a Pose, or None for the default pose.
Pose pose_arg(py::handle obj);
/// Where a solve places the whisker: a Pose, or None for the placement the whisker was built with.
Placement placement_arg(py::handle obj, const Whisker& whisker);
/// Options argument: a SolveOptions, or None for the defaults.
SolveOptions options_arg(py::handle obj);
/// Warm start: a LoadState, a Solution (its .state) or None.
std::optional<LoadState> warm_arg(py::handle obj);

/// A Solution's fields as the JSON result contract (docs/formats.md) names them; vectors as NumPy arrays.
py::dict solution_to_dict(const Solution& s);
/// The result JSON text of `vibrissa solve` (the CLI's writer).
std::string solution_json_text(const Solution& s, int indent);

}  // namespace vibrissa::python
