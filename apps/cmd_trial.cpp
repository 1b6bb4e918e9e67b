// `vibrissa trial TRIAL... [--out DIR]`: pre-process a tracked trial, solve every contact frame in
// contact-point, edge (and, with --mu, frictional edge) mode, run the paper's analyses and write
// frames.csv, frames.h5, summary.json and figures (docs/trials.md). The work is trial::run_trial and
// io::write_trial_outputs, shared with vibrissa.analyze_trial in Python. Several trials (e.g. the per-whisker
// trials of `vibrissa reconstruct --whisker`) are analysed one after the other, with one summary table.
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <sstream>
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
  std::vector<std::string> trials;
  std::string out;
  double mu = 0.0, mu_eq7 = 0.0;  ///< used only when given (trial::run_options checks them)
  trial::TrialFlags flags;
  bool no_figures = false;
  bool all_figures = false;    ///< figures: also the slower ones left out by default (trial_figures.py --all)
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
  if (a.all_figures) flags.emplace_back("--all");
  return flags;
}
/// One trial's line of the summary table.
struct SummaryRow {
  std::string trial, out;
  std::size_t frames = 0, periods = 0, contact_frames = 0, mu_frames = 0;
  double median_mu = 0.0;
  bool has_mu = false;
};

/// The output folder of each trial: --out itself for one trial; for several, --out/<name> (the trial's file name
/// without extension, or its folder's name when those repeat, as for the per-whisker trials of reconstruct), or
/// <trial name>_results next to each trial without --out.
std::vector<std::filesystem::path> output_folders(const std::vector<std::string>& trials, const std::string& out) {
  namespace fs = std::filesystem;
  std::vector<fs::path> folders;
  if (out.empty() || trials.size() == 1) {
    for (const std::string& t : trials) {
      const fs::path in(t);
      folders.push_back(out.empty() ? in.parent_path() / (in.stem().string() + "_results") : fs::path(out));
    }
    return folders;
  }
  const auto unique = [&](auto name_of) {
    std::map<std::string, int> count;
    for (const std::string& t : trials) ++count[name_of(fs::path(t))];
    return std::all_of(count.begin(), count.end(), [](const auto& c) { return c.second == 1 && !c.first.empty(); });
  };
  const auto by_stem = [](const fs::path& p) { return p.stem().string(); };
  const auto by_folder = [](const fs::path& p) { return fs::absolute(p).parent_path().filename().string(); };
  if (unique(by_stem)) {
    for (const std::string& t : trials) folders.push_back(fs::path(out) / by_stem(fs::path(t)));
  } else if (unique(by_folder)) {
    for (const std::string& t : trials) folders.push_back(fs::path(out) / by_folder(fs::path(t)));
  } else {
    throw std::invalid_argument("--out " + out + ": the trials' file names and folder names repeat, so their results "
                                "would share a folder: analyse them without --out (results next to each trial) or "
                                "one by one");
  }
  return folders;
}

/// The summary table of several trials (tab-separated, a header line).
std::string summary_table(const std::vector<SummaryRow>& rows) {
  std::ostringstream t;
  t << "trial\tframes\tcontact_periods\tcontact_frames\tmedian_mu\tmu_frames\tresults\n";
  for (const SummaryRow& r : rows) {
    t << r.trial << '\t' << r.frames << '\t' << r.periods << '\t' << r.contact_frames << '\t';
    if (r.has_mu)
      t << r.median_mu;
    else
      t << "nan";
    t << '\t' << r.mu_frames << '\t' << r.out << '\n';
  }
  return t.str();
}

/// Analyses one trial into `out` (outputs, figures) and prints its summary; returns its row of the table.
SummaryRow analyse(const TrialArgs& a, const std::string& trial_path, const std::filesystem::path& out,
                   const trial::TrialRunOptions& run_opts) {
  namespace fs = std::filesystem;
  // The figure script starts now and waits: Python's start-up overlaps the solve (docs/performance.md).
  std::unique_ptr<EarlyFigureScript> figure_script;
  if (!a.no_figures) {
    std::vector<std::string> args = {(out / "frames.h5").string(), (out / "summary.json").string(),
                                     (out / io::kTrialFiguresFolder).string()};
    for (std::string& f : figure_flags(a)) args.push_back(std::move(f));
    figure_script = std::make_unique<EarlyFigureScript>("trial_figures.py", args);
  }
  const trial::Trial tr = io::read_trial(trial_path);
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
  SummaryRow row{trial_path, out.string(), tr.frames(), run.result.pre.periods.size(), contact, 0, 0.0, false};
  if (analysis.friction) {
    const trial::FrictionAnalysis& f = *analysis.friction;
    std::cout << "  median mu (contact-point mode, F_N >= 0.1 mN): " << f.median << " over " << f.frames_used
              << " frames (" << (f.kind.empty() ? "none" : f.kind) << "; " << f.frames_slipping
              << " slipping, median over those " << f.median_slipping << ")\n";
    for (const std::string& w : f.warnings) std::cerr << "vibrissa trial: warning: " << w << "\n";
    row.mu_frames = f.frames_used;
    row.has_mu = f.frames_used > 0;
    row.median_mu = f.median;
  }
  if (analysis.z_error && analysis.z_error->fit_eq6.all)
    std::cout << "  eq. (6) fit: slope " << analysis.z_error->fit_eq6.all->slope << ", r2 "
              << analysis.z_error->fit_eq6.all->r2 << "\n";
  std::cout << "  results in " << out.string() << "\n";
  if (figure_script) {
    fs::create_directories(out / io::kTrialFiguresFolder);
    figure_script->run();
  }
  return row;
}
}  // namespace

void register_trial(CLI::App& app) {
  auto* cmd = app.add_subcommand("trial", "Analyse a whisking trial against a peg (spec §2.3-§3.4; docs/trials.md)");
  auto a = std::make_shared<TrialArgs>();
  cmd->add_option("TRIAL", a->trials,
                  "trial file (.csv, .h5/.hdf5, .mat); several: each analysed, then one summary table")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("--out", a->out,
                  "output directory (default: <trial name>_results next to the trial; several trials: one folder "
                  "each inside it, named after the trial, or after its folder when the trials' names repeat)")
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
  auto* no_figures =
      cmd->add_flag("--no-figures", a->no_figures, "skip the PNG figures (an older run's figures/ is removed)");
  cmd->add_flag("--all-figures", a->all_figures,
                "figures: also draw fig3a_world_signals.png and fig2bcd_shape_height_arclength.png (left out by "
                "default to keep the figures fast; docs/trials.md)")
      ->excludes(no_figures);
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
    if (!a->window.empty() && !(a->window[0] < a->window[1]))
      throw std::invalid_argument("--window START_S,END_S: start must be before end");
    if (*mu_opt) a->flags.mu = a->mu;
    if (*mu_eq7_opt) a->flags.mu_eq7 = a->mu_eq7;
    const trial::TrialRunOptions run_opts = trial::run_options(a->flags);  // flag errors before reading
    const std::vector<fs::path> outs = output_folders(a->trials, a->out);
    if (a->trials.size() == 1) {
      analyse(*a, a->trials[0], outs[0], run_opts);
      return;
    }
    // Several trials: each analysed and written on its own; one that fails does not stop the others.
    std::vector<SummaryRow> rows;
    std::vector<std::string> failed;
    for (std::size_t k = 0; k < a->trials.size(); ++k) {
      std::cout << "== " << a->trials[k] << "\n";
      try {
        rows.push_back(analyse(*a, a->trials[k], outs[k], run_opts));
      } catch (const std::exception& e) {
        const std::string what = e.what();  // readers' messages name the file already
        failed.push_back(what.rfind(a->trials[k], 0) == 0 ? what : a->trials[k] + ": " + what);
        std::cerr << "vibrissa trial: error: " << a->trials[k] << ": " << e.what() << "\n";
      }
    }
    const std::string table = summary_table(rows);
    std::cout << "\n" << table;
    if (!a->out.empty()) {
      const fs::path path = fs::path(a->out) / "trials_summary.tsv";
      std::ofstream(path) << table;
      std::cout << "summary table in " << path.string() << "\n";
    }
    if (!failed.empty()) {
      std::string message = std::to_string(failed.size()) + " of " + std::to_string(a->trials.size()) +
                            " trials failed (the others are written):";
      for (const std::string& f : failed) message += "\n  - " + f;
      throw std::runtime_error(message);
    }
  });
}

}  // namespace vibrissa::cli
