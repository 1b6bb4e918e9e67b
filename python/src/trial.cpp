// Trials from Python (docs/python.md, "Trials"): the Trial class, reading and writing trial files, synthetic
// trials and the analysis of `vibrissa trial`. Every call goes through the same library functions as the CLI
// (io::read_trial / write_trial, trial::synth_options_from_parameters + synthesize_trial, trial::run_trial +
// io::trial_outputs / write_trial_outputs), so Python and the CLI give bit-identical numbers. The long calls
// run through run_interruptible (GIL released, Ctrl-C, progress). The pure-Python layer
// (python/vibrissa/pipeline.py) wraps the results.
#include <pybind11/stl.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include "bindings.hpp"
#include "convert.hpp"
#include "interruptible.hpp"
#include "labelled.hpp"
#include "vibrissa/io/trial_io.hpp"
#include "vibrissa/io/trial_outputs.hpp"
#include "vibrissa/io/trial_results.hpp"
#include "vibrissa/trial/plausibility.hpp"
#include "vibrissa/trial/synth_parameters.hpp"

namespace vibrissa::python {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// (n, K, 3) tracked shapes, NaN-padded to the longest frame (as in the HDF5 trial file).
py::array_t<double> shapes_array(const trial::Trial& t) {
  std::size_t k = 0;
  for (const auto& s : t.shape_W) k = std::max(k, s.size());
  py::array_t<double> a({t.shape_W.size(), k, std::size_t{3}});
  double* p = a.mutable_data();
  std::fill(p, p + a.size(), kNaN);
  for (std::size_t f = 0; f < t.shape_W.size(); ++f)
    for (std::size_t i = 0; i < t.shape_W[f].size(); ++i)
      for (int c = 0; c < 3; ++c) p[(f * k + i) * 3 + c] = t.shape_W[f][i][c];
  return a;
}

py::array_t<double> edges_array(const std::vector<Edge>& edges) {
  py::array_t<double> a({edges.size(), std::size_t{6}});
  double* p = a.mutable_data();
  for (std::size_t e = 0; e < edges.size(); ++e)
    for (int c = 0; c < 3; ++c) {
      p[6 * e + c] = edges[e].point[c];
      p[6 * e + 3 + c] = edges[e].direction[c];
    }
  return a;
}

py::object optional_array(bool present, const py::object& array) { return present ? array : py::object(py::none()); }

std::string trial_repr(const trial::Trial& t) {
  std::size_t periods = trial::contact_periods(t.contact).size();
  std::string r = "Trial(frames=" + std::to_string(t.frames()) + ", contact_frames=" +
                  std::to_string(trial::contact_frame_count(t)) + ", periods=" + std::to_string(periods);
  if (t.frames() > 1) {
    char buf[64];
    std::snprintf(buf, sizeof buf, ", duration=%.4g s", t.time.back() - t.time.front());
    r += buf;
  }
  r += std::string(", contact_point=") + (t.has_contact_point() ? "yes" : "no") +
       ", shapes=" + (t.has_shapes() ? "yes" : "no");
  if (!t.source.empty()) r += ", source='" + t.source + "'";
  return r + ")";
}

/// synthesize_trial keywords -> SynthOptions through the CLI's parameter table. Unknown keyword: TypeError.
trial::SynthOptions synth_options_from_kwargs(const py::dict& kwargs) {
  std::map<std::string, double> values;
  const std::map<std::string, double> defaults = trial::synth_parameter_defaults();
  std::optional<std::uint64_t> seed;
  bool shapes = false;
  for (auto item : kwargs) {
    const std::string name = py::str(item.first);
    if (name == "seed") {
      seed = item.second.cast<std::uint64_t>();
    } else if (name == "shapes") {
      shapes = item.second.cast<bool>();
    } else if (defaults.count(name) != 0) {
      values[name] = item.second.cast<double>();
    } else {
      throw py::type_error("synthesize_trial() got an unexpected keyword argument '" + name + "'");
    }
  }
  trial::SynthOptions o = trial::synth_options_from_parameters(values);
  if (seed) o.seed = *seed;
  o.shapes = shapes;
  return o;
}

/// The columns of frames.h5 (numeric: float64; status: str, int8 codes in the file) by name, in file order.
py::dict table_columns(const io::ResultTable& table) {
  py::dict out;
  for (const auto& c : table.numeric) out[py::str(c.name)] = to_array(c.values);
  py::module_ np = py::module_::import("numpy");
  for (const io::TextColumn& c : table.text) out[py::str(c.name)] = np.attr("array")(py::cast(c.values), "U");
  return out;
}

}  // namespace

void bind_trial(py::module_& m) {
  py::class_<trial::Trial>(m, "Trial",
                           "A tracked (or synthetic) whisking trial (docs/trials.md), SI units, world frame. Read one "
                           "with vibrissa.read_trial, make one with vibrissa.synthesize_trial, or build one from "
                           "your own arrays with Trial(time=..., base_W=..., ...).")
      .def(py::init([](const py::object& time, const py::object& base_W, const py::object& theta,
                       const py::object& phi, const py::object& contact, const py::object& rest_shape,
                       const py::object& edges, const py::object& zeta, const py::object& contact_W,
                       const py::object& shape_W, const py::object& reconstructed,
                       const py::object& reprojection_px, const py::object& likelihood, double youngs_modulus_Pa, double poisson_ratio,
                       double base_radius, double taper_ratio, int links, double frame_rate_Hz,
                       const std::string& source) {
             trial::Trial t;
             t.source = source;
             t.time = vector1(time, "time");
             t.base_W = points3(base_W, "base_W");
             t.theta = vector1(theta, "theta");
             t.phi = vector1(phi, "phi");
             if (!zeta.is_none()) t.zeta = vector1(zeta, "zeta");
             for (double c : vector1(contact, "contact")) {
               if (c != 0.0 && c != 1.0)
                 throw py::value_error("contact must hold only 0 and 1, got " + py::repr(py::float_(c)).cast<std::string>());
               t.contact.push_back(static_cast<std::uint8_t>(c));
             }
             if (!contact_W.is_none()) t.contact_W = points3(contact_W, "contact_W");
             if (!shape_W.is_none()) {
               const DoubleArray s = as_double_array(shape_W, "shape_W");
               if (s.ndim() != 3 || s.shape(2) != 3)
                 throw py::value_error("shape_W must have shape (n, K, 3), got " + shape_string(s));
               const double* d = s.data();
               for (py::ssize_t i = 0; i < s.shape(0); ++i) {  // NaN rows pad shorter shapes
                 std::vector<Eigen::Vector3d> frame;
                 for (py::ssize_t k = 0; k < s.shape(1); ++k, d += 3)
                   if (std::isfinite(d[0]) && std::isfinite(d[1]) && std::isfinite(d[2])) frame.emplace_back(d[0], d[1], d[2]);
                 t.shape_W.push_back(std::move(frame));
               }
             }
             if (!reconstructed.is_none())
               for (double r : vector1(reconstructed, "reconstructed")) {
                 if (r != 0.0 && r != 1.0)
                   throw py::value_error("reconstructed must hold only 0 and 1, got " +
                                         py::repr(py::float_(r)).cast<std::string>());
                 t.reconstructed.push_back(static_cast<std::uint8_t>(r));
               }
             if (!reprojection_px.is_none()) t.reprojection_px = vector1(reprojection_px, "reprojection_px");
             if (!likelihood.is_none()) t.likelihood = vector1(likelihood, "likelihood");
             t.meta.rest_shape = points3(rest_shape, "rest_shape");
             const DoubleArray e = as_double_array(edges, "edges");
             if (!((e.ndim() == 2 && e.shape(1) == 6) || (e.ndim() == 1 && e.shape(0) == 6)))
               throw py::value_error("edges must have shape (6,) or (m, 6) (point x, y, z, direction x, y, z), got " +
                                     shape_string(e));
             for (py::ssize_t k = 0; k < e.size() / 6; ++k) {
               const double* r = e.data() + 6 * k;
               t.meta.edges.push_back(Edge{{r[0], r[1], r[2]}, {r[3], r[4], r[5]}});
             }
             t.meta.material = trial::TrialMaterial{youngs_modulus_Pa, poisson_ratio, base_radius, taper_ratio, links};
             t.meta.frame_rate = frame_rate_Hz;
             trial::validate(t);
             return t;
           }),
           py::kw_only(), py::arg("time"), py::arg("base_W"), py::arg("theta"), py::arg("phi"), py::arg("contact"),
           py::arg("rest_shape"), py::arg("edges"), py::arg("zeta") = py::none(), py::arg("contact_W") = py::none(),
           py::arg("shape_W") = py::none(), py::arg("reconstructed") = py::none(),
           py::arg("reprojection_px") = py::none(), py::arg("likelihood") = py::none(),
           py::arg("youngs_modulus_Pa") = 3.3e9, py::arg("poisson_ratio") = 0.38,
           py::arg("base_radius") = 100e-6, py::arg("taper_ratio") = 15.0, py::arg("links") = 100,
           py::arg("frame_rate_Hz") = 1000.0, py::arg("source") = "python",
           "A trial from arrays in SI units (docs/trials.md): time (n,) [s], base_W (n, 3) [m], theta, phi and "
           "optional zeta (n,) [rad], contact (n,) 0/1, rest_shape (K, 3) [m], edges (m, 6); optional contact_W "
           "(n, 3) [m] (NaN outside contact) and shape_W (n, K, 3) [m] (NaN-padded); optional reconstruction "
           "columns reconstructed (n,) 0/1, reprojection_px and likelihood (n,). Validated like a file: "
           "ValueError naming the row and column.")
      .def_property_readonly("time", [](const trial::Trial& t) { return to_array(t.time); }, "(n,) time stamps [s]")
      .def_property_readonly("base_W", [](const trial::Trial& t) { return to_array(t.base_W); },
                             "(n, 3) whisker base point, world [m]")
      .def_property_readonly("theta", [](const trial::Trial& t) { return to_array(t.theta); }, "(n,) protraction [rad]")
      .def_property_readonly("phi", [](const trial::Trial& t) { return to_array(t.phi); }, "(n,) elevation [rad]")
      .def_property_readonly(
          "zeta", [](const trial::Trial& t) { return optional_array(t.has_zeta(), to_array(t.zeta)); },
          "(n,) roll [rad], or None if not tracked")
      .def_property_readonly(
          "contact",
          [](const trial::Trial& t) {
            py::array_t<std::uint8_t> a(static_cast<py::ssize_t>(t.contact.size()));
            if (!t.contact.empty()) std::memcpy(a.mutable_data(), t.contact.data(), t.contact.size());
            return a;
          },
          "(n,) uint8, 1 while the whisker touches the object")
      .def_property_readonly(
          "contact_W",
          [](const trial::Trial& t) { return optional_array(t.has_contact_point(), to_array(t.contact_W)); },
          "(n, 3) tracked contact point, world [m] (NaN outside contact), or None if not tracked")
      .def_property_readonly(
          "shape_W", [](const trial::Trial& t) { return optional_array(t.has_shapes(), shapes_array(t)); },
          "(n, K, 3) tracked whisker shapes, world [m], base first, NaN-padded; None if not tracked")
      .def_property_readonly(
          "reconstructed",
          [](const trial::Trial& t) -> py::object {
            if (t.reconstructed.empty()) return py::none();
            py::array_t<std::uint8_t> a(static_cast<py::ssize_t>(t.reconstructed.size()));
            std::memcpy(a.mutable_data(), t.reconstructed.data(), t.reconstructed.size());
            return py::object(std::move(a));
          },
          "(n,) uint8, 0 where `vibrissa reconstruct` could not reconstruct the frame (its pose is NaN and the "
          "analysis skips it); None if the trial was not reconstructed")
      .def_property_readonly(
          "reprojection_px",
          [](const trial::Trial& t) { return optional_array(!t.reprojection_px.empty(), to_array(t.reprojection_px)); },
          "(n,) RMS reprojection error of the tracked points used [px], or None")
      .def_property_readonly(
          "likelihood", [](const trial::Trial& t) { return optional_array(!t.likelihood.empty(), to_array(t.likelihood)); },
          "(n,) mean tracker likelihood of the points used, in [0, 1], or None")
      .def_property_readonly("rest_shape", [](const trial::Trial& t) { return to_array(t.meta.rest_shape); },
                             "(K, 3) undeflected shape, base first [m] (the pose places it)")
      .def_property_readonly("edges", [](const trial::Trial& t) { return edges_array(t.meta.edges); },
                             "(m, 6) the object's edges: point x, y, z [m], direction x, y, z (as in the HDF5 file)")
      .def_property_readonly(
          "material",
          [](const trial::Trial& t) {
            const trial::TrialMaterial& mt = t.meta.material;
            py::dict d;
            d["youngs_modulus_Pa"] = mt.youngs_modulus;
            d["poisson_ratio"] = mt.poisson_ratio;
            d["base_radius"] = mt.base_radius;
            d["taper_ratio"] = mt.taper_ratio;
            d["links"] = mt.links;
            return d;
          },
          "dict: youngs_modulus_Pa, poisson_ratio, base_radius [m], taper_ratio, links")
      .def_property_readonly("frame_rate_Hz", [](const trial::Trial& t) { return t.meta.frame_rate; },
                             "frame rate [Hz] (informational; the time stamps are authoritative)")
      .def_readonly("source", &trial::Trial::source, "the file it was read from ('synthetic' for synthesize_trial)")
      .def(
          "write", [](const trial::Trial& t, const std::string& path) { io::write_trial(t, path); }, py::arg("path"),
          "Writes the trial as `vibrissa synth` does, format by extension (.csv, .h5/.hdf5, .mat), atomically.")
      .def("__len__", &trial::Trial::frames)
      .def_property_readonly("warnings", &trial::trial_warnings,
                             "Likely unit slips (docs/conventions.md, \"Plausible ranges\"): the whisker's size, "
                             "the angle series, edges out of reach; as `vibrissa trial` prints them.")
      .def("__repr__", &trial_repr);

  m.def(
      "read_trial",
      [](const std::string& path) {
        trial::Trial t = io::read_trial(path);
        warn_all(trial::trial_warnings(t));
        return t;
      },
      py::arg("path"),
      "Reads a trial file (.csv, .h5/.hdf5, .mat) as `vibrissa trial` does; ValueError naming file, row and "
      "column for invalid data; likely unit slips (Trial.warnings) are raised with warnings.warn.");

  m.def(
      "_synthesize_trial",
      [](const py::dict& kwargs, const py::object& progress) {
        const trial::SynthOptions options = synth_options_from_kwargs(kwargs);
        return run_interruptible(
            [&](const RunControl& control) { return trial::synthesize_trial(options, nullptr, control); }, progress);
      },
      py::arg("options"), py::arg("progress") = py::none());
  m.def("_synth_parameter_defaults", &trial::synth_parameter_defaults,
        "The numeric options of synthesize_trial / `vibrissa synth` with their defaults, in the units their names "
        "state.");

  py::class_<io::TrialOutputs>(m, "_TrialOutputs")
      .def("columns", [](const io::TrialOutputs& o) { return table_columns(o.table); })
      .def("labelled", [](const io::TrialOutputs& o) { return labelled_description(io::trial_results_data(o.table)); })
      .def("summary_json", [](const io::TrialOutputs& o) { return o.summary.dump(); })
      .def(
          "write",
          [](const io::TrialOutputs& o, const std::string& dir) {
            py::gil_scoped_release release;
            io::write_trial_outputs(o, dir);
          },
          py::arg("dir"));

  m.def(
      "_analyze_trial",
      [](const trial::Trial& t, std::optional<double> mu, std::optional<double> mu_eq7, double cutoff,
         int filter_order, bool no_filter, bool no_roll_fit, bool rest_shape_per_contact, const py::object& progress) {
        trial::TrialFlags flags;
        flags.mu = mu;
        flags.mu_eq7 = mu_eq7;
        flags.cutoff = cutoff;
        flags.filter_order = filter_order;
        flags.no_filter = no_filter;
        flags.no_roll_fit = no_roll_fit;
        flags.rest_shape_per_contact = rest_shape_per_contact;
        const trial::TrialRunOptions options = trial::run_options(flags);
        return run_interruptible(
            [&](const RunControl& control) { return io::trial_outputs(trial::run_trial(t, options, control)); },
            progress);
      },
      py::arg("trial"), py::arg("mu"), py::arg("mu_eq7"), py::arg("cutoff"), py::arg("filter_order"),
      py::arg("no_filter"), py::arg("no_roll_fit"), py::arg("rest_shape_per_contact"), py::arg("progress"));
}

}  // namespace vibrissa::python
