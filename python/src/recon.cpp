// Reconstruction from Python (docs/python.md, "Reconstruction"): vibrissa.reconstruct runs the library call of
// `vibrissa reconstruct` (recon::reconstruct_files) through run_interruptible (GIL released, Ctrl-C,
// progress), so Python and the CLI give the same trial.
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <tuple>
#include <stdexcept>

#include <pybind11/stl.h>

#include "bindings.hpp"
#include "convert.hpp"
#include "interruptible.hpp"
#include "vibrissa/recon/calibration_files.hpp"
#include "vibrissa/recon/reconstruct_files.hpp"

namespace vibrissa::python {

namespace {

/// (k, 3) points [m] or (k, 6) point + direction rows; a single row may be given flat.
std::vector<Edge> edges_arg(const py::object& obj, const char* name, bool vertical) {
  std::vector<Edge> out;
  if (obj.is_none()) return out;
  const std::size_t width = vertical ? 3 : 6;
  const DoubleArray a = as_double_array(obj, name);
  const bool flat = a.ndim() == 1 && a.shape(0) == py::ssize_t(width);
  if (!flat && !(a.ndim() == 2 && a.shape(1) == py::ssize_t(width)))
    throw py::value_error(std::string(name) + " must have shape (" + std::to_string(width) + ",) or (k, " +
                          std::to_string(width) + ") [m], got " + shape_string(a));
  const py::ssize_t rows = flat ? 1 : a.shape(0);
  const double* p = a.data();
  for (py::ssize_t r = 0; r < rows; ++r, p += width) {
    Edge e;
    e.point = Eigen::Vector3d(p[0], p[1], p[2]);
    e.direction = vertical ? Eigen::Vector3d::UnitZ() : Eigen::Vector3d(p[3], p[4], p[5]);
    out.push_back(e);
  }
  return out;
}

}  // namespace

void bind_recon(py::module_& m) {
  m.def(
      "_reconstruct",
      [](const std::vector<std::array<std::string, 4>>& views, const std::string& calibration, const py::object& peg,
         const py::object& edge, const std::vector<std::string>& bodyparts, const std::string& individual,
         int whisker_id, double min_likelihood, double max_reprojection_px, double contact_threshold,
         double base_jump, int fit_segments, int nodes, double frame_rate,
         std::int64_t front_frame_offset, const std::map<std::string, std::int64_t>& frame_offsets, double min_yield, double max_unpaired,
         double max_epipolar_px, const std::string& calibration_unit,
         const std::vector<std::tuple<std::string, std::vector<std::string>, int>>& whiskers,
         const std::string& source, const py::object& progress) -> py::object {
        recon::ReconstructOptions o;
        o.edges = edges_arg(peg, "peg", true);
        for (const Edge& e : edges_arg(edge, "edge", false)) o.edges.push_back(e);
        o.min_likelihood = min_likelihood;
        o.max_reprojection_px = max_reprojection_px;
        o.contact_threshold = contact_threshold;
        o.base_jump = base_jump;
        o.fit_segments = fit_segments;
        o.nodes = nodes;
        o.frame_rate = frame_rate;
        o.front_frame_offset = front_frame_offset;
        o.frame_offsets = frame_offsets;
        o.min_yield = min_yield;
        o.max_unpaired = max_unpaired;
        o.max_epipolar_px = max_epipolar_px;
        o.validate();
        recon::ReconstructFiles files;
        // Each view: (name, track file, camera name in the calibration, Janelia measurements).
        for (const auto& [name, path, camera, measurements] : views)
          files.views.push_back({name, path, camera, {measurements, whisker_id, bodyparts, individual}});
        files.calibration = calibration;
        files.calibration_unit = calibration_unit;
        if (!whiskers.empty()) {
          // Several whiskers: [(name, trial or None, report JSON or None, error)] (recon::reconstruct_whiskers).
          std::vector<recon::WhiskerSelection> selections;
          for (const auto& [name, bodyparts_of, identity] : whiskers) selections.push_back({name, bodyparts_of, identity});
          std::vector<recon::WhiskerTrial> rs = run_interruptible(
              [&](const RunControl& control) { return recon::reconstruct_whiskers(files, selections, o, source, control); },
              progress);
          py::list out;
          for (auto& w : rs) {
            if (w.result)
              out.append(py::make_tuple(w.name, std::move(w.result->trial), recon::report_json(w.result->reconstruction, -1),
                                        w.error));
            else
              out.append(py::make_tuple(w.name, py::none(), py::none(), w.error));
          }
          return py::object(std::move(out));
        }
        recon::ReconstructedTrial r = run_interruptible(
            [&](const RunControl& control) { return recon::reconstruct_files(files, o, source, control); }, progress);
        return py::make_tuple(std::move(r.trial), recon::report_json(r.reconstruction, -1));
      },
      py::arg("views"), py::arg("calibration"), py::arg("peg"), py::arg("edge"), py::arg("bodyparts"),
      py::arg("individual"), py::arg("whisker_id"), py::arg("min_likelihood"), py::arg("max_reprojection_px"),
      py::arg("contact_threshold"), py::arg("base_jump"), py::arg("fit_segments"), py::arg("nodes"),
      py::arg("frame_rate"), py::arg("front_frame_offset"), py::arg("frame_offsets"), py::arg("min_yield"), py::arg("max_unpaired"),
      py::arg("max_epipolar_px"), py::arg("calibration_unit"), py::arg("whiskers"), py::arg("source"), py::arg("progress"));
  // The pixels of world points [m] through one camera of a calibration (recon::read_calibration), with its
  // distortion: what the reconstruction assumes, checked against cv2.projectPoints in python/tests.
  m.def(
      "_project_points",
      [](const std::string& calibration, const std::string& camera, const std::vector<std::array<double, 3>>& points_W,
         const std::string& calibration_unit) {
        const auto cams = recon::read_calibration(calibration, calibration_unit);
        const auto it = cams.find(camera);
        if (it == cams.end()) throw std::invalid_argument(calibration + ": no camera named '" + camera + "'");
        std::vector<std::array<double, 2>> out;
        for (const auto& p : points_W) {
          const Eigen::Vector2d px = it->second.project(Eigen::Vector3d(p[0], p[1], p[2]));
          out.push_back({px.x(), px.y()});
        }
        return out;
      },
      py::arg("calibration"), py::arg("camera"), py::arg("points_W"), py::arg("calibration_unit"));
}

}  // namespace vibrissa::python
