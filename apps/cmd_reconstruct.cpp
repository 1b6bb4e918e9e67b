// `vibrissa reconstruct --view top=T --view front=F [--view side=S ...] --calibration C.json -o trial.h5` and
// `vibrissa calibrate`: from N >= 2 tracked, named views to a trial that `vibrissa trial` reads (docs/reconstruction.md).
#include <algorithm>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "progress.hpp"
#include "vibrissa/io/json_file.hpp"
#include "vibrissa/io/trial_io.hpp"
#include "vibrissa/recon/geometry.hpp"
#include "vibrissa/recon/reconstruct.hpp"
#include "vibrissa/recon/reconstruct_files.hpp"
#include "vibrissa/trial/plausibility.hpp"

namespace vibrissa::cli {

namespace {

struct ReconstructArgs {
  std::string top, front, out, report, calibration_unit;
  std::vector<std::string> calibrations, views, measurements, frame_offsets, whiskers;
  bool all_whiskers = false;
  std::string top_camera = "top", front_camera = "front";
  recon::TrackSelection top_sel, front_sel;
  std::string bodyparts;
  std::vector<double> pegs_mm, edges_mm;
  double contact_threshold_um = 300.0, base_jump_um = 1000.0;
  recon::ReconstructOptions options;
};

std::vector<std::string> split_list(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream ss(s);
  std::string item;
  while (std::getline(ss, item, ','))
    if (!item.empty()) out.push_back(item);
  return out;
}

/// NAME=VALUE of a repeatable option; throws naming the option and the argument.
std::pair<std::string, std::string> name_value(const std::string& spec, const std::string& option) {
  const auto eq = spec.find('=');
  if (eq == std::string::npos || eq == 0 || eq + 1 == spec.size())
    throw std::invalid_argument(option + " expects NAME=VALUE, got '" + spec + "'");
  return {spec.substr(0, eq), spec.substr(eq + 1)};
}

}  // namespace

void register_reconstruct(CLI::App& app) {
  auto* cmd = app.add_subcommand("reconstruct", "Reconstruct a trial from two or more tracked camera views (docs/reconstruction.md)");
  auto a = std::make_shared<ReconstructArgs>();
  auto& opt = a->options;
  cmd->add_option("--view", a->views, "NAME=FILE: the tracks of the view whose camera is NAME in the calibration: .csv "
                  "(plain or DeepLabCut), .h5 (DeepLabCut) or .whiskers; repeat per view (>= 2 views in all)");
  cmd->add_option("--top", a->top, "top-view tracks (shorthand for --view top=FILE)");
  cmd->add_option("--front", a->front, "front-view tracks (shorthand for --view front=FILE)");
  cmd->add_option("--calibration", a->calibrations,
                  "calibration: cameras.json (vibrissa), calibration.toml (anipose) or NAME=file.yml|.json (one camera, "
                  "OpenCV FileStorage); repeat to combine")->required();
  cmd->add_option("--calibration-unit", a->calibration_unit, "length unit of anipose / OpenCV calibrations: m, mm or um");
  cmd->add_option("-o,--out", a->out, "output trial file (.h5, .csv or .mat)")->required();
  cmd->add_option("--top-camera", a->top_camera, "name of the top view's camera in the calibration")->capture_default_str();
  cmd->add_option("--front-camera", a->front_camera, "name of the front view's camera")->capture_default_str();
  cmd->add_option("--measurements", a->measurements, "NAME=FILE: Janelia .measurements of view NAME's .whiskers; repeat per view");
  cmd->add_option("--top-measurements", a->top_sel.measurements, "Janelia .measurements of the top .whiskers");
  cmd->add_option("--front-measurements", a->front_sel.measurements, "Janelia .measurements of the front .whiskers");
  cmd->add_option("--whisker-id", a->top_sel.identity, "Janelia whisker identity (measurements 'state')")->capture_default_str();
  cmd->add_option("--bodyparts", a->bodyparts, "DeepLabCut keypoints base to tip, comma-separated (default: all)");
  cmd->add_option("--whisker", a->whiskers, "NAME=c2_0,c2_1,... (DeepLabCut keypoints base to tip) or NAME=LABEL (Janelia "
                  "label): one trial per whisker, in NAME/ beside -o and --report; repeat per whisker");
  cmd->add_flag("--all-whiskers", a->all_whiskers, "every labelled whisker of the first view's Janelia .measurements");
  cmd->add_option("--individual", a->top_sel.individual, "DeepLabCut individual (multi-animal files)");
  cmd->add_option("--peg-mm", a->pegs_mm, "vertical peg (along world z) through X Y Z [mm]; repeat for more")
      ->type_size(3)->expected(1, CLI::detail::expected_max_vector_size)->type_name("X Y Z")->allow_extra_args(false);
  cmd->add_option("--edge-mm", a->edges_mm, "edge: point X Y Z [mm] and direction DX DY DZ; repeat for more")
      ->type_size(6)->expected(1, CLI::detail::expected_max_vector_size)->type_name("X Y Z DX DY DZ")
      ->allow_extra_args(false);
  cmd->add_option("--frame-rate", opt.frame_rate, "frame rate [Hz]: time = frame / rate")->capture_default_str();
  cmd->add_option("--min-likelihood", opt.min_likelihood, "ignore points below this likelihood")->capture_default_str();
  cmd->add_option("--max-reprojection-px", opt.max_reprojection_px, "flag frames above this RMS reprojection error [px]")->capture_default_str();
  cmd->add_option("--contact-threshold-um", a->contact_threshold_um, "closest approach to an edge counted as contact [um]")->capture_default_str();
  cmd->add_option("--base-jump-um", a->base_jump_um, "flag frames whose base leaves the local median by more [um]")->capture_default_str();
  cmd->add_option("--fit-segments", opt.fit_segments, "knot intervals of the cubic B-spline 3D curve")->capture_default_str();
  cmd->add_option("--nodes", opt.nodes, "segments of the written 3D shape")->capture_default_str();
  cmd->add_option("--front-frame-offset", opt.front_frame_offset, "front frame f is top frame f + N (views out of step)")->capture_default_str();
  cmd->add_option("--frame-offset", a->frame_offsets, "NAME=N: view NAME's frame f is frame f + N of the others; repeat per view");
  cmd->add_option("--min-yield", opt.min_yield, "error if fewer of the frames tracked in both views are reconstructed (0: accept any)")->capture_default_str();
  cmd->add_option("--max-unpaired", opt.max_unpaired, "error if more of the frames are tracked in one view only")->capture_default_str();
  cmd->add_option("--max-epipolar-px", opt.max_epipolar_px, "error if the base points' median epipolar distance exceeds this and 4x the median reprojection error [px]")->capture_default_str();
  cmd->add_option("--report", a->report, "also write a JSON report (per-frame status, undeflected shapes)");
  cmd->callback([a] {
    auto& o = a->options;
    for (std::size_t k = 0; k + 2 < a->pegs_mm.size(); k += 3)
      o.edges.push_back({Eigen::Vector3d(a->pegs_mm[k], a->pegs_mm[k + 1], a->pegs_mm[k + 2]) * 1e-3, Eigen::Vector3d::UnitZ()});
    for (std::size_t k = 0; k + 5 < a->edges_mm.size(); k += 6)
      o.edges.push_back({Eigen::Vector3d(a->edges_mm[k], a->edges_mm[k + 1], a->edges_mm[k + 2]) * 1e-3,
                         Eigen::Vector3d(a->edges_mm[k + 3], a->edges_mm[k + 4], a->edges_mm[k + 5])});
    o.contact_threshold = a->contact_threshold_um * 1e-6;
    o.base_jump = a->base_jump_um * 1e-6;
    o.validate();  // every bound (--nodes included) before reading or allocating anything
    for (const std::string& spec : a->frame_offsets) {
      const auto [name, value] = name_value(spec, "--frame-offset");
      std::size_t used = 0;
      long long n = 0;
      try {
        n = std::stoll(value, &used);
      } catch (const std::exception&) {
        used = 0;
      }
      if (used != value.size()) throw std::invalid_argument("--frame-offset " + name + ": '" + value + "' is not an integer");
      o.frame_offsets[name] = n;
    }
    o.validate();
    recon::TrackSelection sel;
    sel.bodyparts = split_list(a->bodyparts);
    sel.identity = a->top_sel.identity;
    sel.individual = a->top_sel.individual;
    recon::ReconstructFiles files;
    if (!a->top.empty()) files.views.push_back({"top", a->top, a->top_camera, sel});
    if (!a->front.empty()) files.views.push_back({"front", a->front, a->front_camera, sel});
    for (const std::string& spec : a->views) {
      const auto [name, path] = name_value(spec, "--view");
      files.views.push_back({name, path, name == "top" ? a->top_camera : name == "front" ? a->front_camera : "", sel});
    }
    for (auto& v : files.views)
      if (v.name == "top") v.selection.measurements = a->top_sel.measurements;
      else if (v.name == "front") v.selection.measurements = a->front_sel.measurements;
    for (const std::string& spec : a->measurements) {
      const std::pair<std::string, std::string> given = name_value(spec, "--measurements");
      auto it = std::find_if(files.views.begin(), files.views.end(), [&](const auto& v) { return v.name == given.first; });
      if (it == files.views.end())
        throw std::invalid_argument("--measurements " + spec + ": no view named '" + given.first + "'");
      it->selection.measurements = given.second;
    }
    if (files.views.size() < 2)
      throw std::invalid_argument("reconstruct needs at least two views (--view NAME=FILE, --top, --front), got " +
                                  std::to_string(files.views.size()));
    files.calibration = a->calibrations.front();
    files.more_calibrations.assign(a->calibrations.begin() + 1, a->calibrations.end());
    files.calibration_unit = a->calibration_unit;
    std::optional<Progress> progress;  // created at the first report, when the frame count is known
    std::size_t shown = 0;
    RunControl control;
    control.progress = [&](std::size_t done, std::size_t all) {
      if (progress && done < shown) {  // the next whisker's frames
        progress->finish();
        progress.reset();
        shown = 0;
      }
      if (!progress) progress.emplace("reconstructing frames", all);
      progress->advance(done - shown);
      shown = done;
    };
    // One trial (and report) written, its summary printed; warnings to stderr and into the report.
    auto write = [&](const recon::ReconstructedTrial& result, const std::string& out, const std::string& report_path,
                     const std::string& label) {
      io::write_trial(result.trial, out);
      std::cout << "vibrissa reconstruct: " << label << recon::summary_line(result) << " -> " << out << "\n";
      const std::vector<std::string> warnings = trial::trial_warnings(result.trial);  // a peg out of reach, ...
      for (const std::string& w : warnings) std::cerr << "vibrissa reconstruct: " << label << "warning: " << w << "\n";
      if (!report_path.empty()) {
        nlohmann::json report = nlohmann::json::parse(recon::report_json(result.reconstruction));
        nlohmann::json& listed = report["warnings"];  // as vibrissa.reconstruct's report
        if (listed.is_null()) listed = nlohmann::json::array();
        for (const std::string& w : warnings) listed.push_back(w);
        io::write_json_file(report_path, report);
      }
    };
    std::vector<recon::WhiskerSelection> whiskers;
    for (const std::string& spec : a->whiskers) whiskers.push_back(recon::parse_whisker(spec));
    if (a->all_whiskers) {
      if (!whiskers.empty()) throw std::invalid_argument("--all-whiskers and --whisker: give one");
      const std::string& m = files.views.front().selection.measurements;
      if (m.empty())
        throw std::invalid_argument("--all-whiskers needs the Janelia .measurements of view '" + files.views.front().name +
                                    "' (--measurements " + files.views.front().name + "=FILE)");
      whiskers = recon::janelia_whiskers(m);
    }
    if (whiskers.empty()) {
      const recon::ReconstructedTrial result = recon::reconstruct_files(files, o, a->out, control);
      if (progress) progress->finish();
      write(result, a->out, a->report, "");
      return;
    }
    // Several whiskers: one trial per whisker in a folder named after it beside -o (and --report).
    namespace fs = std::filesystem;
    auto per_whisker = [](const std::string& path, const std::string& name) {
      const fs::path p(path);
      fs::create_directories(p.parent_path() / name);
      return (p.parent_path() / name / p.filename()).string();
    };
    const std::vector<recon::WhiskerTrial> results = recon::reconstruct_whiskers(files, whiskers, o, a->out, control);
    if (progress) progress->finish();
    std::string failed;
    std::cout << "whisker\tframes\treconstructed\tin contact\tcontact periods\treprojection median [px]\ttrial\n";
    for (const recon::WhiskerTrial& w : results) {
      if (!w.result) {
        failed += "\n  - whisker '" + w.name + "': " + w.error;
        std::cout << w.name << "\tfailed\t\t\t\t\t\n";
        continue;
      }
      const std::string out = per_whisker(a->out, w.name);
      write(*w.result, out, a->report.empty() ? "" : per_whisker(a->report, w.name), "whisker " + w.name + ": ");
      const auto& rec = w.result->reconstruction;
      std::vector<double> rep;
      std::size_t contact = 0;
      for (const auto& f : rec.frames)
        if (f.ok()) rep.push_back(f.reprojection_px);
      for (auto c : w.result->trial.contact) contact += c;
      std::sort(rep.begin(), rep.end());
      std::cout << w.name << "\t" << rec.frames.size() << "\t" << rep.size() << "\t" << contact << "\t"
                << rec.undeflected.size() << "\t" << (rep.empty() ? std::string("n/a") : std::to_string(rep[rep.size() / 2]))
                << "\t" << out << "\n";
    }
    if (!failed.empty())
      throw std::runtime_error("reconstruct: " + std::to_string(std::count_if(results.begin(), results.end(),
                                                                              [](const auto& w) { return !w.result; })) +
                               " of " + std::to_string(results.size()) + " whiskers failed (the others are written):" + failed);
  });
}

void register_calibrate(CLI::App& app) {
  auto* cmd = app.add_subcommand("calibrate", "DLT calibration from >= 6 known 3D-2D correspondences per camera (docs/reconstruction.md)");
  auto cameras = std::make_shared<std::vector<std::string>>();
  auto out = std::make_shared<std::string>();
  auto unit = std::make_shared<std::string>("mm");
  cmd->add_option("--camera", *cameras, "NAME=points.csv (columns x,y,z,u_px,v_px); repeat per camera")->required();
  cmd->add_option("--length-unit", *unit, "unit of x, y, z: m, mm or um")->capture_default_str();
  cmd->add_option("-o,--out", *out, "calibration JSON to write")->required();
  cmd->callback([cameras, out, unit] {
    std::map<std::string, recon::Camera> cams;
    std::map<std::string, double> rms;
    for (const std::string& spec : *cameras) {
      const auto eq = spec.find('=');
      if (eq == std::string::npos || eq == 0) throw std::invalid_argument("--camera expects NAME=FILE, got '" + spec + "'");
      const std::string name = spec.substr(0, eq), path = spec.substr(eq + 1);
      const recon::Correspondences c = recon::read_correspondences_csv(path, *unit);
      recon::Calibration cal;
      try {
        cal = recon::calibrate_dlt(c.points_W, c.pixels);
      } catch (const std::invalid_argument& e) {
        throw std::invalid_argument(path + ": " + e.what());
      }
      double worst = 0.0;
      for (double r : cal.residuals_px) worst = std::max(worst, r);
      std::cout << "camera " << name << ": " << c.pixels.size() << " points, RMS reprojection error "
                << cal.rms_px << " px (max " << worst << " px)\n";
      cams[name] = cal.camera;
      rms[name] = cal.rms_px;
    }
    recon::write_cameras_json(*out, cams, rms);
  });
}

}  // namespace vibrissa::cli
