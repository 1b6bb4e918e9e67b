// `vibrissa reconstruct --top T --front F --calibration C.json -o trial.h5` and `vibrissa calibrate`: from
// two tracked views to a trial that `vibrissa trial` reads (docs/reconstruction.md).
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
  std::vector<std::string> calibrations;
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

}  // namespace

void register_reconstruct(CLI::App& app) {
  auto* cmd = app.add_subcommand("reconstruct", "Reconstruct a trial from two tracked camera views (docs/reconstruction.md)");
  auto a = std::make_shared<ReconstructArgs>();
  auto& opt = a->options;
  cmd->add_option("--top", a->top, "top-view tracks: .csv (plain or DeepLabCut), .h5 (DeepLabCut) or .whiskers")->required();
  cmd->add_option("--front", a->front, "front-view tracks, same formats")->required();
  cmd->add_option("--calibration", a->calibrations,
                  "calibration: cameras.json (vibrissa), calibration.toml (anipose) or NAME=file.yml|.json (one camera, "
                  "OpenCV FileStorage); repeat to combine")->required();
  cmd->add_option("--calibration-unit", a->calibration_unit, "length unit of anipose / OpenCV calibrations: m, mm or um");
  cmd->add_option("-o,--out", a->out, "output trial file (.h5, .csv or .mat)")->required()->check(output_path());
  cmd->add_option("--top-camera", a->top_camera, "name of the top camera in the calibration")->capture_default_str();
  cmd->add_option("--front-camera", a->front_camera, "name of the front camera")->capture_default_str();
  cmd->add_option("--top-measurements", a->top_sel.measurements, "Janelia .measurements of the top .whiskers");
  cmd->add_option("--front-measurements", a->front_sel.measurements, "Janelia .measurements of the front .whiskers");
  cmd->add_option("--whisker-id", a->top_sel.identity, "Janelia whisker identity (measurements 'state')")->capture_default_str();
  cmd->add_option("--bodyparts", a->bodyparts, "DeepLabCut keypoints base to tip, comma-separated (default: all)");
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
  cmd->add_option("--min-yield", opt.min_yield, "error if fewer of the frames tracked in both views are reconstructed (0: accept any)")->capture_default_str();
  cmd->add_option("--max-unpaired", opt.max_unpaired, "error if more of the frames are tracked in one view only")->capture_default_str();
  cmd->add_option("--max-epipolar-px", opt.max_epipolar_px, "error if the base points' median epipolar distance exceeds this and 4x the median reprojection error [px]")->capture_default_str();
  cmd->add_option("--report", a->report, "also write a JSON report (per-frame status, undeflected shapes)")
      ->check(output_path());
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
    a->top_sel.bodyparts = split_list(a->bodyparts);
    a->front_sel.bodyparts = a->top_sel.bodyparts;
    a->front_sel.identity = a->top_sel.identity;
    a->front_sel.individual = a->top_sel.individual;
    recon::ReconstructFiles files;
    files.top = a->top;
    files.front = a->front;
    files.calibration = a->calibrations.front();
    files.more_calibrations.assign(a->calibrations.begin() + 1, a->calibrations.end());
    files.calibration_unit = a->calibration_unit;
    files.top_camera = a->top_camera;
    files.front_camera = a->front_camera;
    files.top_selection = a->top_sel;
    files.front_selection = a->front_sel;
    std::optional<Progress> progress;  // created at the first report, when the frame count is known
    std::size_t shown = 0;
    RunControl control;
    control.progress = [&](std::size_t done, std::size_t all) {
      if (!progress) progress.emplace("reconstructing frames", all);
      progress->advance(done - shown);
      shown = done;
    };
    const recon::ReconstructedTrial result = recon::reconstruct_files(files, o, a->out, control);
    if (progress) progress->finish();
    io::write_trial(result.trial, a->out);
    std::cout << "vibrissa reconstruct: " << recon::summary_line(result) << " -> " << a->out << "\n";
    const std::vector<std::string> warnings = trial::trial_warnings(result.trial);  // a peg out of reach, ...
    for (const std::string& w : warnings) std::cerr << "vibrissa reconstruct: warning: " << w << "\n";
    if (!a->report.empty()) {
      nlohmann::json report = nlohmann::json::parse(recon::report_json(result.reconstruction));
      nlohmann::json& listed = report["warnings"];  // as vibrissa.reconstruct's report
      if (listed.is_null()) listed = nlohmann::json::array();
      for (const std::string& w : warnings) listed.push_back(w);
      io::write_json_file(a->report, report);
    }
  });
}

void register_calibrate(CLI::App& app) {
  auto* cmd = app.add_subcommand("calibrate", "DLT calibration from >= 6 known 3D-2D correspondences per camera (docs/reconstruction.md)");
  auto cameras = std::make_shared<std::vector<std::string>>();
  auto out = std::make_shared<std::string>();
  auto unit = std::make_shared<std::string>("mm");
  cmd->add_option("--camera", *cameras, "NAME=points.csv (columns x,y,z,u_px,v_px); repeat per camera")->required();
  cmd->add_option("--length-unit", *unit, "unit of x, y, z: m, mm or um")->capture_default_str();
  cmd->add_option("-o,--out", *out, "calibration JSON to write")->required()->check(output_path());
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
