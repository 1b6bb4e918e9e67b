#include "vibrissa/recon/reconstruct_files.hpp"

#include <cmath>
#include <set>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "vibrissa/io/nan_reasons.hpp"
#include "vibrissa/recon/calibration_files.hpp"
#include "vibrissa/recon/camera.hpp"

namespace vibrissa::recon {

namespace {

Camera named_camera(const std::map<std::string, Camera>& cams, const ViewFile& view, const std::string& path) {
  auto it = cams.find(view.camera_name());
  if (it != cams.end()) return it->second;
  std::string names;
  for (const auto& [name, cam] : cams) names += (names.empty() ? "'" : ", '") + name + "'";
  throw std::invalid_argument(path + ": field 'cameras." + view.camera_name() + "': no camera of that name for view '" +
                              view.name + "' (" + view.path + "); the calibration has " + names);
}

using io::finite_or_null;

}  // namespace

ReconstructedTrial reconstruct_files(const ReconstructFiles& files, const ReconstructOptions& options,
                                     const std::string& source, const RunControl& control) {
  auto cams = read_calibration(files.calibration, files.calibration_unit);
  for (const std::string& spec : files.more_calibrations)
    for (auto& [name, cam] : read_calibration(spec, files.calibration_unit))
      if (!cams.emplace(name, cam).second)
        throw std::invalid_argument(spec + ": camera '" + name + "' is already given by another calibration");
  if (files.views.size() < 2)
    throw std::invalid_argument("views: at least two camera views are needed (--view NAME=FILE, --top, --front), got " +
                                std::to_string(files.views.size()));
  std::vector<View> views;
  for (const ViewFile& v : files.views) {
    for (const View& w : views)
      if (w.name == v.name) throw std::invalid_argument("views: the view '" + v.name + "' is given twice");
    views.push_back({v.name, {}, named_camera(cams, v, files.calibration)});
  }
  for (std::size_t k = 0; k < files.views.size(); ++k) views[k].tracks = read_tracks(files.views[k].path, files.views[k].selection);
  ReconstructedTrial out;
  out.reconstruction = reconstruct(views, options, control);
  out.trial = to_trial(out.reconstruction, options, {}, source);
  if (!out.reconstruction.problems.empty()) {
    std::string inputs;
    for (const ViewFile& v : files.views) inputs += v.name + "=" + v.path + ", ";
    std::string msg = "inconsistent inputs (" + inputs + files.calibration + "): " + summary_line(out);
    for (const auto& p : out.reconstruction.problems) msg += "\n  - " + p;
    throw InconsistentViews(msg);
  }
  return out;
}

WhiskerSelection parse_whisker(const std::string& spec) {
  const auto eq = spec.find('=');
  if (eq == std::string::npos || eq == 0 || eq + 1 == spec.size())
    throw std::invalid_argument("--whisker expects NAME=KEYPOINTS (c2_0,c2_1,...) or NAME=LABEL (Janelia), got '" + spec + "'");
  WhiskerSelection w;
  w.name = spec.substr(0, eq);
  const std::string value = spec.substr(eq + 1);
  if (value.find_first_not_of("0123456789") == std::string::npos && value.size() < 10) {
    w.identity = std::stoi(value);
    return w;
  }
  std::size_t start = 0;
  while (start <= value.size()) {
    const std::size_t comma = std::min(value.find(',', start), value.size());
    if (comma > start) w.bodyparts.push_back(value.substr(start, comma - start));
    start = comma + 1;
  }
  if (w.bodyparts.size() < 2)
    throw std::invalid_argument("--whisker " + w.name + ": '" + value + "' names " + std::to_string(w.bodyparts.size()) +
                                " keypoint; a whisker needs at least two, base to tip (or a Janelia label)");
  return w;
}

std::vector<WhiskerSelection> janelia_whiskers(const std::string& measurements_path) {
  std::set<int> labels;
  for (const MeasurementRow& r : read_measurements(measurements_path))
    if (r.identity >= 0) labels.insert(r.identity);
  std::vector<WhiskerSelection> out;
  for (int label : labels) out.push_back({std::to_string(label), {}, label});
  if (out.empty()) throw std::invalid_argument(measurements_path + ": field 'state': no whisker is labelled (every segment has state -1)");
  return out;
}

std::vector<WhiskerTrial> reconstruct_whiskers(const ReconstructFiles& files,
                                               const std::vector<WhiskerSelection>& whiskers,
                                               const ReconstructOptions& options, const std::string& source,
                                               const RunControl& control) {
  std::set<std::string> names;
  for (const auto& w : whiskers)
    if (w.name.empty() || !names.insert(w.name).second)
      throw std::invalid_argument("whiskers: the name '" + w.name + "' is empty or given twice");
  std::vector<WhiskerTrial> out;
  for (const auto& w : whiskers) {
    ReconstructFiles one = files;
    for (ViewFile& v : one.views) {
      if (w.identity >= 0)
        v.selection.identity = w.identity;
      else
        v.selection.bodyparts = w.bodyparts;
    }
    WhiskerTrial t;
    t.name = w.name;
    try {
      t.result = reconstruct_files(one, options, source + " [whisker " + w.name + "]", control);
    } catch (const Cancelled&) {
      throw;
    } catch (const std::exception& e) {
      t.error = e.what();
    }
    out.push_back(std::move(t));
  }
  return out;
}

std::string report_json(const Reconstruction& rec, int indent) {
  nlohmann::json j;
  auto& frames = j["frames"];
  frames = nlohmann::json::array();
  for (const auto& f : rec.frames) {
    nlohmann::json per_view = nlohmann::json::object(), per_point = nlohmann::json::object();
    for (std::size_t v = 0; v < rec.view_names.size(); ++v) {
      if (v < f.view_reprojection_px.size()) per_view[rec.view_names[v]] = finite_or_null(f.view_reprojection_px[v]);
      if (v < f.point_reprojection_px.size()) {
        nlohmann::json d = nlohmann::json::array();
        for (double x : f.point_reprojection_px[v]) d.push_back(finite_or_null(x));
        per_point[rec.view_names[v]] = d;
      }
    }
    frames.push_back({{"frame", f.frame}, {"status", frame_status_name(f.status)}, {"points_used", f.points_used},
                      {"reprojection_px", finite_or_null(f.reprojection_px)}, {"view_reprojection_px", per_view},
                      {"point_reprojection_px", per_point}, {"outliers", f.outliers},
                      {"approach_m", finite_or_null(f.approach)}, {"contact_s_m", finite_or_null(f.contact_s)}});
  }
  j["checks"] = {{"frames", rec.frames.size()}, {"frames_in_both_views", rec.frames_in_both},
                  {"reconstructed", rec.count(FrameStatus::ok)},
                  {"base_epipolar_px_median", finite_or_null(rec.base_epipolar_px)},
                  {"swapped_base_epipolar_px_median", finite_or_null(rec.swapped_epipolar_px)},
                  {"problems", rec.problems}};
  nlohmann::json pairs = nlohmann::json::array(), view_median = nlohmann::json::object();
  for (const auto& c : rec.view_pairs)
    pairs.push_back({{"views", {rec.view_names[c.a], rec.view_names[c.b]}},
                     {"base_epipolar_px_median", finite_or_null(c.base_epipolar_px)},
                     {"swapped_base_epipolar_px_median", finite_or_null(c.swapped_epipolar_px)}});
  for (std::size_t v = 0; v < rec.view_names.size() && v < rec.view_reprojection_px_median.size(); ++v)
    view_median[rec.view_names[v]] = finite_or_null(rec.view_reprojection_px_median[v]);
  j["checks"]["view_pairs"] = pairs;
  j["checks"]["view_reprojection_px_median"] = view_median;
  j["views"] = rec.view_names;
  auto& periods = j["contact_periods"];
  periods = nlohmann::json::array();
  for (const auto& u : rec.undeflected) {
    nlohmann::json shape = nlohmann::json::array();
    for (const auto& p : u.shape_W) shape.push_back({p.x(), p.y(), p.z()});
    periods.push_back({{"first_frame", u.first_frame}, {"last_frame", u.last_frame},
                       {"undeflected_from_frame", u.source_frame}, {"undeflected_frames_averaged", u.frames_averaged},
                       {"undeflected_shape_m", shape}});
  }
  // Each null's reason (io/nan_reasons.hpp): a flagged frame has no numbers; an unflagged one lacks a contact
  // arc length when it does not touch, and an approach when the trial has no object edge.
  io::NanReasons why;
  for (std::size_t i = 0; i < rec.frames.size(); ++i) {
    const auto& f = rec.frames[i];
    const std::string at = "/frames/" + std::to_string(i);
    if (f.status != FrameStatus::ok) {
      why.explain(at, std::string("frame flagged '") + frame_status_name(f.status) + "' (docs/reconstruction.md)");
      continue;
    }
    why.explain(at + "/point_reprojection_px", "the point is not tracked or its likelihood is below --min-likelihood");
    why.explain(at + "/view_reprojection_px", "every tracked point of this view is an outlier or below --min-likelihood");
    why.explain(at + "/contact_s_m", "not in contact: the whisker stays farther than the contact threshold from every edge");
    why.explain(at + "/approach_m", "the trial has no object edge to approach");
  }
  why.explain("/checks", "no frame has the base point (point 0) tracked in both views (of the pair)");
  why.attach(j);
  return j.dump(indent);
}

std::string summary_line(const ReconstructedTrial& r) {
  const Reconstruction& rec = r.reconstruction;
  std::size_t contact = 0;
  for (auto c : r.trial.contact) contact += c;
  return std::to_string(rec.frames.size()) + " frames (" + std::to_string(rec.frames_in_both) +
         (rec.view_names.size() > 2 ? " tracked in at least two of " + std::to_string(rec.view_names.size()) + " views), "
                                    : std::string(" tracked in both views), ")) + std::to_string(rec.count(FrameStatus::ok)) + " reconstructed (" +
         std::to_string(contact) + " in contact, " + std::to_string(rec.undeflected.size()) +
         " contact periods); not reconstructed: " + std::to_string(rec.count(FrameStatus::missing_view)) +
         (rec.view_names.size() > 2 ? " seen by fewer than two views, " : " missing a view, ") +
         std::to_string(rec.count(FrameStatus::too_few_points)) + " too few points, " +
         std::to_string(rec.count(FrameStatus::reprojection)) + " reprojection, " +
         std::to_string(rec.count(FrameStatus::inconsistent_base)) + " inconsistent base, " +
         std::to_string(rec.count(FrameStatus::base_not_reached)) + " base not reached; " +
         (rec.view_pairs.size() > 1 ? "largest median base epipolar distance of a pair of views " : "median base epipolar distance ") +
         (std::isfinite(rec.base_epipolar_px) ? std::to_string(rec.base_epipolar_px).substr(0, 6) + " px" : "n/a");
}

}  // namespace vibrissa::recon
