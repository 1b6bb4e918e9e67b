// `vibrissa trial TRIAL [--out DIR]`: pre-process a tracked trial, solve every contact frame in
// contact-point, edge (and, with --mu, frictional edge) mode, run the paper's analyses and write
// frames.csv, frames.h5, summary.json and figures (docs/trials.md). The work is trial::run_trial and
// io::write_trial_outputs, shared with vibrissa.analyze_trial in Python.
#include <algorithm>
#include <filesystem>
#include <iostream>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "commands.hpp"
#include "progress.hpp"
#include "run_python.hpp"
#include "vibrissa/io/figure_files.hpp"
#include "vibrissa/io/trial_io.hpp"
#include "vibrissa/io/trial_outputs.hpp"
#include "vibrissa/trial/plausibility.hpp"

namespace vibrissa::cli {

namespace {
struct TrialArgs {
  std::string trial, out;
  double mu = 0.0, mu_eq7 = 0.0;  ///< used only when given (trial::run_options checks them)
  trial::TrialFlags flags;
  bool no_figures = false;
  std::vector<double> window;  ///< figures: time series over [start, end] s
  int whisk = 0;               ///< figures: time series over contact period `whisk` (from 1)
  int figure_dpi = 0;          ///< figures: PNG resolution (0: the script's default)
};

/// Figure options for trial_figures.py, as its flags (one code path with TrialResult.figures in Python).
std::vector<std::string> figure_flags(const TrialArgs& a) {
  std::vector<std::string> flags;
  if (!a.window.empty())
    flags.insert(flags.end(), {"--window", std::to_string(a.window[0]) + ',' + std::to_string(a.window[1])});
  if (a.whisk > 0) flags.insert(flags.end(), {"--whisk", std::to_string(a.whisk)});
  if (a.figure_dpi > 0) flags.insert(flags.end(), {"--dpi", std::to_string(a.figure_dpi)});
  return flags;
}
}  // namespace

void register_trial(CLI::App& app) {
  auto* cmd = app.add_subcommand("trial", "Analyse a whisking trial against a peg (spec §2.3-§3.4; docs/trials.md)");
  auto a = std::make_shared<TrialArgs>();
  cmd->add_option("TRIAL", a->trial, "trial file (.csv, .h5/.hdf5, .mat)")->required()->check(CLI::ExistingFile);
  cmd->add_option("--out", a->out, "output directory (default: <trial name>_results next to the trial)")
      ->check(output_path());
  // Checked by trial::run_options (finite, >= 0) once given: nan is an error, never "not given".
  auto* mu_opt = cmd->add_option("--mu", a->mu, "also run frictional edge mode with this friction coefficient");
  auto* mu_eq7_opt =
      cmd->add_option("--mu-eq7", a->mu_eq7, "friction coefficient for eq. (7) (default: median mu of contact-point mode)");
  cmd->add_option("--cutoff", a->flags.cutoff, "low-pass cutoff [Hz] (spec §2.3: 85)");  // checked by run_options
  cmd->add_option("--filter-order", a->flags.filter_order, "Butterworth order per pass (2 or 4; filtfilt doubles it)")
      ->check(CLI::IsMember({2, 4}));
  cmd->add_flag("--no-filter", a->flags.no_filter, "do not low-pass filter the tracked signals");
  cmd->add_flag("--no-roll-fit", a->flags.no_roll_fit, "use the tracked zeta in contact frames instead of the theta fit");
  cmd->add_flag("--rest-shape-per-contact", a->flags.rest_shape_per_contact,
                "use the tracked shape at the end of each contact period as its undeflected shape (spec §2.3)");
  cmd->add_flag("--no-figures", a->no_figures, "skip the PNG figures (an older run's figures/ is removed)");
  auto* window = cmd->add_option("--window", a->window,
                                 "figures: draw the time series over START_S,END_S (seconds of the trial clock; "
                                 "default: whole trial up to 2 s, else the first second of contact)")
                     ->delimiter(',')
                     ->expected(2);
  cmd->add_option("--whisk", a->whisk, "figures: draw the time series over contact period N (from 1)")
      ->check(number_in(1, 1e6))
      ->excludes(window);
  cmd->add_option("--figure-dpi", a->figure_dpi, "figures: PNG resolution (default 150; 300 for print)")
      ->check(number_in(50, 1200));
  cmd->callback([a, mu_opt, mu_eq7_opt] {
    namespace fs = std::filesystem;
    const fs::path in(a->trial);
    const fs::path out = a->out.empty() ? in.parent_path() / (in.stem().string() + "_results") : fs::path(a->out);
    if (!a->window.empty() && !(a->window[0] < a->window[1]))
      throw std::invalid_argument("--window START_S,END_S: start must be before end");
    if (*mu_opt) a->flags.mu = a->mu;
    if (*mu_eq7_opt) a->flags.mu_eq7 = a->mu_eq7;
    const trial::TrialRunOptions run_opts = trial::run_options(a->flags);  // flag errors before reading
    const trial::Trial tr = io::read_trial(a->trial);
    for (const std::string& w : trial::trial_warnings(tr)) std::cerr << "vibrissa trial: warning: " << w << "\n";
    const std::size_t contact = trial::contact_frame_count(tr);
    Progress progress("solving contact frames", contact);
    RunControl control;
    std::size_t shown = 0;
    control.progress = [&](std::size_t done, std::size_t) {
      progress.advance(done - shown);
      shown = done;
    };
    const trial::TrialRun run = trial::run_trial(tr, run_opts, control);
    progress.finish();
    const io::TrialOutputs outputs = io::trial_outputs(run);
    io::write_trial_outputs(outputs, out);
    const trial::TrialAnalysis& analysis = run.analysis;
    const std::size_t shown_dropped = std::min<std::size_t>(run.dropped_frames.size(), 10);
    for (std::size_t k = 0; k < shown_dropped; ++k) {
      const trial::DroppedFrame& d = run.dropped_frames[k];
      std::cerr << "vibrissa trial: warning: frame " << d.frame << " (t = " << d.time << " s) dropped before filtering: "
                << d.reason << "\n";
    }
    if (run.dropped_frames.size() > shown_dropped)
      std::cerr << "vibrissa trial: warning: " << run.dropped_frames.size() - shown_dropped
                << " more frames dropped (summary.json: dropped_frames)\n";
    std::cout << "vibrissa trial: " << tr.frames() << " frames, " << run.result.pre.periods.size()
              << " contact periods, " << contact << " contact frames solved in " << run.pipeline_seconds << " s\n";
    if (analysis.friction) {
      const trial::FrictionAnalysis& f = *analysis.friction;
      std::cout << "  median mu (contact-point mode, F_N >= 0.1 mN): " << f.median << " over " << f.frames_used
                << " frames (" << (f.kind.empty() ? "none" : f.kind) << "; " << f.frames_slipping
                << " slipping, median over those " << f.median_slipping << ")\n";
      for (const std::string& w : f.warnings) std::cerr << "vibrissa trial: warning: " << w << "\n";
    }
    if (analysis.z_error && analysis.z_error->fit_eq6.all)
      std::cout << "  eq. (6) fit: slope " << analysis.z_error->fit_eq6.all->slope << ", r2 "
                << analysis.z_error->fit_eq6.all->r2 << "\n";
    std::cout << "  results in " << out.string() << "\n";
    if (!a->no_figures) {
      const fs::path figures = out / io::kTrialFiguresFolder;
      fs::create_directories(figures);
      std::vector<std::string> args = {(out / "frames.h5").string(), (out / "summary.json").string(),
                                       figures.string()};
      for (std::string& f : figure_flags(*a)) args.push_back(std::move(f));
      run_figure_script("trial_figures.py", args);
    }
  });
}

}  // namespace vibrissa::cli
