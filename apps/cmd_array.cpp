// `vibrissa array [CONFIG] [--out DIR] [--csv] [--no-figures]`: the full rat array whisking against edges,
// pegs or prisms for one or more head pitches (spec §3.4, §4.4, Fig. 4a; docs/array.md). Writes array.h5,
// summary.json, pitch_summary.csv, config.json, optional array.csv (io::write_array_outputs), and figures.
#include <chrono>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include "commands.hpp"
#include "progress.hpp"
#include "run_python.hpp"
#include "vibrissa/array/sweep.hpp"
#include "vibrissa/core/limits.hpp"
#include "vibrissa/io/array_config.hpp"
#include "vibrissa/io/json_input.hpp"
#include "vibrissa/io/array_outputs.hpp"
#include "vibrissa/io/figure_files.hpp"

namespace vibrissa::cli {

namespace {
struct ArrayArgs {
  std::string config, out = "array_results", pitches;
  bool csv = false, no_figures = false, gif = false, animation = false, print_default = false, dynamics = false;
  int threads = 0;
  int frames = -1;     ///< animation: rendered frames (output.render_count); -1: the config's
  double fps = 0.0;    ///< animation: frames per second (0: the script's default)
  int figure_dpi = 0;  ///< figures: resolution (0: the scripts' default)
};

std::vector<double> parse_pitch_list(const std::string& text) {
  std::vector<double> out;
  std::stringstream in(text);
  std::string cell;
  while (std::getline(in, cell, ',')) {
    try {
      std::size_t used = 0;
      out.push_back(std::stod(cell, &used) * std::numbers::pi / 180.0);
      if (used != cell.size() || !std::isfinite(out.back())) throw std::invalid_argument(cell);
    } catch (const std::exception&) {
      throw std::invalid_argument("--pitches must be a comma-separated list of angles in degrees, got '" + text + "'");
    }
  }
  return out;
}
}  // namespace

void register_array(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "array", "Simulate the rat whisker array whisking against objects, over head pitches (Fig. 4a; docs/array.md)");
  auto a = std::make_shared<ArrayArgs>();
  cmd->add_option("CONFIG", a->config, "JSON configuration (default: built-in right-side whisk against a peg)")
      ->check(CLI::ExistingFile);
  cmd->add_option("--out", a->out, "output directory")->capture_default_str()->check(output_path());
  cmd->add_option("--pitches", a->pitches, "override head.pitches_deg, e.g. -20,-10,0,10,20");
  cmd->add_option("--threads", a->threads, "OpenMP threads (default: all cores)")
      ->check(number_in(0, limits::max_threads));
  cmd->add_flag("--dynamics", a->dynamics,
                "drive every whisker through the dynamics integrator (in air: the objects are not touched; the "
                "config's \"dynamics\" sets density, damping, air drag); see docs/dynamics.md");
  cmd->add_flag("--csv", a->csv, "also write array.csv (one row per pitch, whisker and frame)");
  cmd->add_flag("--animation", a->animation,
                "also write the MP4 animation and its still (the interactive view.html is written by default)");
  cmd->add_flag("--gif", a->gif, "write the animation, as GIF instead of MP4 (implies --animation)");
  cmd->add_option("--frames", a->frames, "animation: number of rendered frames (overrides output.render_count)")
      ->check(number_in(0, double(limits::max_array_frames)));
  cmd->add_option("--fps", a->fps, "animation: frames per second (default 12)")->check(number_in(1e-3, 1000.0));
  cmd->add_option("--figure-dpi", a->figure_dpi, "figures and animation: resolution (default 150; 300 for print)")
      ->check(number_in(50, 1200));
  cmd->add_flag("--no-figures", a->no_figures, "skip the animation and PNG figures (an older run's are removed)");
  cmd->add_flag("--print-default-config", a->print_default, "print the built-in configuration and exit");
  cmd->callback([a] {
    namespace fs = std::filesystem;
    if (a->print_default) {
      std::cout << std::setw(2) << io::default_array_config_json() << "\n";
      return;
    }
    nlohmann::json j = a->config.empty() ? io::default_array_config_json() : io::read_array_config_json(a->config);
    if (!a->pitches.empty()) {
      nlohmann::json list = nlohmann::json::array();
      for (double p : parse_pitch_list(a->pitches)) list.push_back(p * 180.0 / std::numbers::pi);
      j["head"]["pitches_deg"] = list;
    }
    if (a->threads > 0) j["threads"] = a->threads;
    if (a->dynamics && !j.contains("dynamics")) j["dynamics"] = nlohmann::json::object();
    if (a->frames >= 0) j["output"]["render_count"] = a->frames;
    const fs::path base = a->config.empty() ? fs::current_path() : fs::path(a->config).parent_path();
    j = io::resolve_input_paths(j, base);  // config.json names its files absolutely: it means the same anywhere
    const array::SimulationConfig config = io::array_config_from_json(j, base);
    const fs::path out(a->out);
    const std::size_t total = config.pitches.size() * config.morphology.whiskers.size() * config.times.size();
    std::cout << "vibrissa array: " << config.morphology.whiskers.size() << " whiskers (" << config.morphology.source
              << ") x " << config.times.size() << " frames x " << config.pitches.size() << " head pitch(es)\n";
    array::ArrayResult result;
    {
      Progress progress("simulating", total);
      std::size_t shown = 0;
      RunControl control;
      control.progress = [&](std::size_t done, std::size_t) {
        if (done > shown) progress.advance(done - shown);
        shown = done;
      };
      result = array::simulate_array(config, control);
    }
    std::cout << "simulated " << total << " whisker-frames in " << std::fixed << std::setprecision(2)
              << result.wall_seconds << " s (";
    if (config.dynamics) std::cout << "dynamics: " << result.dynamics_steps << " integrator steps, ";
    std::cout << result.solves << " edge solves";
    if (result.failed_solves) std::cout << ", " << result.failed_solves << " without equilibrium -> pushed past";
    std::cout << ")\n";
    for (const std::string& w : array::array_warnings(result)) std::cerr << "vibrissa: warning: " << w << "\n";
    io::write_array_outputs(result, config, j, out, {.csv = a->csv});
    std::cout << std::setprecision(3);
    std::cout << "pitch_deg  touching  pushed_past  peak_MB_uNm (whisker)  mean_peak_MB_uNm\n";
    for (const array::PitchSummary& s : array::summarize_pitches(result))
      std::cout << std::setw(9) << s.pitch * 180.0 / std::numbers::pi << std::setw(10) << s.whiskers_touching
                << std::setw(13) << s.whiskers_pushed_past << std::setw(13) << s.peak_MB * 1e6 << " ("
                << (s.peak_MB_whisker.empty() ? "-" : s.peak_MB_whisker) << ")" << std::setw(18)
                << s.mean_peak_MB * 1e6 << "\n";
    std::cout.flush();
    if (!a->no_figures) {
      const std::string h5 = (out / "array.h5").string();
      auto with_dpi = [&](std::vector<std::string> args) {
        if (a->figure_dpi > 0) args.insert(args.end(), {"--dpi", std::to_string(a->figure_dpi)});
        return args;
      };
      // The interactive viewer (docs/viewer.md) first: it takes longest. Then the PNGs; the animation only
      // when asked for (it took most of a default run's time).
      std::vector<FigureScript> scripts = {
          {.script = "vibrissa", .args = {"view", out.string(), "-o", (out / io::kArrayViewer).string()}, .module = true},
          {.script = "array_traces.py", .args = with_dpi({h5, (out / io::kArrayTracesFigure).string()})}};
      if (a->animation || a->gif) {
        std::vector<std::string> anim = {h5, (out / (a->gif ? io::kArrayAnimationGif : io::kArrayAnimationMp4)).string()};
        if (a->fps > 0.0) anim.insert(anim.end(), {"--fps", std::to_string(a->fps)});
        scripts.push_back({.script = "array_animation.py", .args = with_dpi(anim)});
      }
      if (config.pitches.size() > 1)
        scripts.push_back({.script = "array_pitch_sweep.py", .args = with_dpi({h5, (out / io::kArrayPitchSweepFigure).string()})});
      run_figure_scripts(scripts);  // side by side (separate Python processes)
    }
    std::cout << "wrote " << out.string() << "/{array.h5, summary.json, pitch_summary.csv"
              << (a->csv ? ", array.csv" : "") << (a->no_figures ? "" : ", view.html, figures") << "}\n";
  });
}

}  // namespace vibrissa::cli
