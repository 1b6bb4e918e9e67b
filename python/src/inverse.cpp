// The base-wrench inverse from Python (docs/inverse.md, docs/python.md): one solve returning a
// BaseWrenchResult, and a batch over time series (warm-started within a series; series in parallel with the
// GIL released, interruptible, with progress).
#include <omp.h>

#include <atomic>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>
#include <tuple>
#include <utility>

#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include "bindings.hpp"
#include "deprecated.hpp"
#include "convert.hpp"
#include "interruptible.hpp"
#include "vibrissa/io/case_json.hpp"
#include "vibrissa/solve/base_wrench.hpp"

namespace vibrissa::python {

namespace {

/// "all", "bending", "Fx,My,Mz" or a sequence of signal names.
SignalSet signals_arg(const py::handle& obj) {
  if (py::isinstance<py::str>(obj)) return SignalSet::parse(obj.cast<std::string>(), "signals");
  if (py::isinstance<py::sequence>(obj)) {
    std::vector<std::string> names;
    for (const auto& item : obj.cast<py::sequence>()) {
      if (!py::isinstance<py::str>(item)) throw py::value_error("signals: expected signal names (Fx ... Mz)");
      names.push_back(item.cast<std::string>());
    }
    return SignalSet::from_names(names, "signals");
  }
  throw py::value_error("signals must be a preset name or a sequence of signal names");
}

/// noise: None, m standard deviations (m,), or an (m, m) covariance, SI, in signal order.
BaseWrenchOptions options_from(const py::handle& signals, const py::object& noise, int starts,
                               const py::object& options) {
  BaseWrenchOptions o;
  o.signals = signals_arg(signals);
  o.starts = starts;
  o.solve = options_arg(options);
  if (!noise.is_none()) {
    const DoubleArray a = as_double_array(noise, "noise");
    const int m = o.signals.size();
    if (a.ndim() == 1 && a.shape(0) == m) {
      o.noise_covariance = Eigen::MatrixXd::Zero(m, m);
      for (int i = 0; i < m; ++i) {
        if (!(a.at(i) > 0.0)) throw py::value_error("noise[" + std::to_string(i) + "] must be positive");
        o.noise_covariance(i, i) = a.at(i) * a.at(i);
      }
    } else if (a.ndim() == 2 && a.shape(0) == m && a.shape(1) == m) {
      o.noise_covariance.resize(m, m);
      for (int i = 0; i < m; ++i)
        for (int k = 0; k < m; ++k) o.noise_covariance(i, k) = a.at(i, k);
    } else {
      throw py::value_error("noise must have shape (" + std::to_string(m) + ",) or (" + std::to_string(m) + ", " +
                            std::to_string(m) + ") for signals " + o.signals.name() + ", got " + shape_string(a));
    }
  }
  validate(o);
  return o;
}

/// Series of base wrenches: (F, 3) or (S, F, 3) -> rows[s][f].
std::vector<std::vector<Eigen::Vector3d>> series_arg(const py::object& obj, const char* name) {
  const DoubleArray a = as_double_array(obj, name);
  if (!((a.ndim() == 2 || a.ndim() == 3) && a.shape(a.ndim() - 1) == 3))
    throw py::value_error(std::string(name) + " must have shape (F, 3) or (S, F, 3), got " + shape_string(a));
  const py::ssize_t S = a.ndim() == 3 ? a.shape(0) : 1, F = a.shape(a.ndim() - 2);
  std::vector<std::vector<Eigen::Vector3d>> out(static_cast<std::size_t>(S));
  const double* p = a.data();
  for (py::ssize_t s = 0; s < S; ++s)
    for (py::ssize_t f = 0; f < F; ++f, p += 3) out[static_cast<std::size_t>(s)].emplace_back(p[0], p[1], p[2]);
  return out;
}

}  // namespace

void bind_inverse(py::module_& m) {
  py::class_<BaseWrenchRoot>(m, "BaseWrenchRoot", "One fit of the base signals (a candidate contact), SI units.")
      .def_readonly("arc_length", &BaseWrenchRoot::arc_length, "s [m]")
      .def_readonly("force_magnitude", &BaseWrenchRoot::force_magnitude, "f [N]")
      .def_readonly("angle", &BaseWrenchRoot::angle, "zeta = atan2(F_z, F_y) of the loaded link [rad]")
      .def_property_readonly("contact_point_W", [](const BaseWrenchRoot& r) { return to_array(r.contact_point_W); },
                             "world [m]")
      .def_property_readonly("contact_point", deprecated_alias("BaseWrenchRoot.contact_point", "contact_point_W"),
                             "Deprecated alias of contact_point_W (DeprecationWarning; removed in 0.2.0).")
      .def_readonly("chi2", &BaseWrenchRoot::chi2, "whitened squared residual")
      .def_readonly("state", &BaseWrenchRoot::state, "the fitted unknowns (a LoadState)")
      .def("__repr__", [](const BaseWrenchRoot& r) {
        return "BaseWrenchRoot(arc_length=" + std::to_string(r.arc_length) +
               ", force_magnitude=" + std::to_string(r.force_magnitude) + ", angle=" + std::to_string(r.angle) +
               ", chi2=" + std::to_string(r.chi2) + ")";
      });

  py::class_<BaseWrenchIdentifiability>(m, "BaseWrenchIdentifiability",
                                        "Whether the chosen signals determine (s, f, zeta), linearised at the fit.")
      .def_readonly("signals", &BaseWrenchIdentifiability::signals, "number of equations m")
      .def_readonly("identifiable", &BaseWrenchIdentifiability::identifiable)
      .def_readonly("condition_number", &BaseWrenchIdentifiability::condition_number,
                    "of the Jacobian in natural units (inf when rank-deficient)")
      .def_property_readonly("null_direction",
                             [](const BaseWrenchIdentifiability& i) { return to_array(i.null_direction); },
                             "unit (ds/L, df/(E I0/L^2), dzeta) the signals cannot see; zeros when identifiable")
      .def_property_readonly("covariance", [](const BaseWrenchIdentifiability& i) { return to_array(i.covariance); },
                             "(3, 3) covariance of (s [m], f [N], zeta [rad])")
      .def_property_readonly(
          "contact_point_covariance",
          [](const BaseWrenchIdentifiability& i) { return to_array(i.contact_point_covariance_W); },
          "(3, 3) covariance of the contact point, world [m^2]");

  py::class_<BaseWrenchResult>(m, "BaseWrenchResult",
                               "Result of solve_base_wrench: the returned fit as a Solution, chi2, every fit that "
                               "explains the signals (roots, best first) and the identifiability.")
      .def_readonly("solution", &BaseWrenchResult::solution)
      .def_readonly("chi2", &BaseWrenchResult::chi2)
      .def_readonly("roots", &BaseWrenchResult::roots)
      .def_readonly("identifiability", &BaseWrenchResult::identifiability)
      .def_property_readonly("signals", [](const BaseWrenchResult& r) { return r.signals.name(); })
      .def_property_readonly("warnings", &base_wrench_warnings,
                             "What to read before the numbers: for Status.underdetermined, why the fit is not the "
                             "contact (also raised with warnings.warn by solve_base_wrench)")
      .def(
          "to_json", [](const BaseWrenchResult& r, int indent) { return base_wrench_to_json(r).dump(indent); },
          py::arg("indent") = 2, "The result JSON of `vibrissa solve` in base_wrench mode.")
      .def("__repr__", [](const BaseWrenchResult& r) {
        return "BaseWrenchResult(status=" + std::string(to_string(r.solution.status)) +
               ", arc_length=" + std::to_string(r.solution.arc_length) +
               ", force_magnitude=" + std::to_string(r.solution.force_magnitude) +
               ", roots=" + std::to_string(r.roots.size()) + ", signals=" + r.signals.name() + ")";
      });

  m.def(
      "solve_base_wrench",
      [](const Whisker& w, const py::object& force_W, const py::object& moment_W, const py::object& pose,
         const py::object& signals, const py::object& noise, int starts, const py::object& warm,
         const py::object& options) {
        const Placement X = placement_arg(pose, w);
        const Eigen::Vector3d F = vec3(force_W, "force_W"), M = vec3(moment_W, "moment_W");
        const BaseWrenchOptions o = options_from(signals, noise, starts, options);
        const std::optional<LoadState> ws = warm_arg(warm);
        BaseWrenchResult r;
        {
          py::gil_scoped_release release;
          r = solve_base_wrench(w, X, F, M, o, ws ? &*ws : nullptr);
        }
        warn_all(base_wrench_warnings(r));
        return r;
      },
      py::arg("whisker"), py::arg("force_W"), py::arg("moment_W"), py::kw_only(), py::arg("pose") = py::none(),
      py::arg("signals") = "all", py::arg("noise") = py::none(), py::arg("starts") = 16, py::arg("warm") = py::none(),
      py::arg("options") = py::none(),
      "The contact (s, f, zeta) that explains the base force and moment (world frame, moment about the base), "
      "fitted over `signals` (a preset: all, bending, bending_axial, moments, moments_axial; or names Fx..Mz "
      "in the whisker frame) with `noise` (m standard deviations or an m x m covariance, SI). docs/inverse.md.");

  m.def(
      "_solve_base_wrench_series",
      [](const Whisker& w, const py::object& force_W, const py::object& moment_W, const py::object& pose,
         const py::object& signals, const py::object& noise, int starts, const py::object& options,
         const py::object& threads, const py::object& progress) {
        const Placement X = placement_arg(pose, w);
        const auto F = series_arg(force_W, "force_W"), M = series_arg(moment_W, "moment_W");
        if (F.size() != M.size() || F.front().size() != M.front().size())
          throw py::value_error("force_W and moment_W must have the same shape");
        BaseWrenchOptions o = options_from(signals, noise, starts, options);
        o.solve.compute_shape = false;
        const int nt = threads.is_none() ? omp_get_max_threads() : std::max(1, threads.cast<int>());
        return run_interruptible(
            [&](const RunControl& control) {
              ProgressCounter counter(control, F.size() * F.front().size());
              RunControl per_series;  // series poll the caller's cancel flag, progress counts frames
              per_series.cancel = control.cancel;
              // A frame whose input is refused (std::invalid_argument) does not stop the batch: its series is
              // solved again frame by frame (each frame cold), the refused frame is None with its message in
              // `errors` ((series, frame, message)); vibrissa.inverse raises the first for on_error="raise".
              std::vector<std::vector<std::optional<BaseWrenchResult>>> out(F.size());
              std::vector<std::vector<std::pair<std::size_t, std::string>>> refused(F.size());
              std::exception_ptr error;
              const auto S = static_cast<std::ptrdiff_t>(F.size());
#pragma omp parallel for schedule(dynamic, 1) num_threads(nt)
              for (std::ptrdiff_t s = 0; s < S; ++s) {
                try {
                  const auto k = static_cast<std::size_t>(s);
                  try {
                    for (auto& r : solve_base_wrench_series(w, X, F[k], M[k], o, per_series)) out[k].emplace_back(std::move(r));
                  } catch (const std::invalid_argument&) {
                    out[k].assign(F[k].size(), std::nullopt);
                    for (std::size_t f = 0; f < F[k].size(); ++f) {
                      try {
                        out[k][f] = std::move(solve_base_wrench_series(w, X, {F[k][f]}, {M[k][f]}, o, per_series).front());
                      } catch (const std::invalid_argument& e) {
                        refused[k].emplace_back(f, e.what());
                      }
                    }
                  }
                  counter.advance(F[k].size());
                } catch (...) {
#pragma omp critical(vibrissa_inverse_error)
                  if (!error) error = std::current_exception();
                }
              }
              if (error) std::rethrow_exception(error);
              std::vector<std::tuple<std::size_t, std::size_t, std::string>> errors;
              for (std::size_t k = 0; k < refused.size(); ++k)
                for (auto& [f, message] : refused[k]) errors.emplace_back(k, f, std::move(message));
              return std::make_pair(std::move(out), std::move(errors));
            },
            progress);
      },
      py::arg("whisker"), py::arg("force_W"), py::arg("moment_W"), py::arg("pose"), py::arg("signals"),
      py::arg("noise"), py::arg("starts"), py::arg("options"), py::arg("threads"), py::arg("progress"),
      "Internal: the C++ side of vibrissa.solve_base_wrench_batch (a list per series of BaseWrenchResult).");
}

}  // namespace vibrissa::python
