// `vibrissa synth OUT [options]`: write a synthetic whisking trial simulated with the frictional edge mode
// (docs/trials.md, "Synthetic trials"). The numeric flags come from trial::synth_parameters(), the table
// vibrissa.synthesize_trial uses too, so both give the same trial bit for bit.
#include <algorithm>
#include <iostream>
#include <map>
#include <memory>

#include "commands.hpp"
#include "progress.hpp"
#include "vibrissa/io/trial_io.hpp"
#include "vibrissa/trial/synth_parameters.hpp"

namespace vibrissa::cli {

namespace {
struct SynthArgs {
  std::string out;
  std::map<std::string, double> values = trial::synth_parameter_defaults();  ///< in the flags' units
  std::uint64_t seed = trial::SynthOptions{}.seed;
  bool shapes = false;
};
}  // namespace

void register_synth(CLI::App& app) {
  auto* cmd = app.add_subcommand("synth", "Write a synthetic trial: whisking against a peg with friction (docs/trials.md)");
  auto a = std::make_shared<SynthArgs>();
  cmd->add_option("OUT", a->out, "output trial file (.csv, .h5/.hdf5 or .mat)")->required()->check(output_path());
  for (const trial::SynthParameter& p : trial::synth_parameters()) {
    std::string flag = "--" + p.name;
    std::replace(flag.begin(), flag.end(), '_', '-');
    cmd->add_option(flag, a->values.at(p.name), p.help)->capture_default_str();
  }
  cmd->add_option("--seed", a->seed, "random seed for the noise")->capture_default_str();
  cmd->add_flag("--shapes", a->shapes, "also write tracked 3D whisker shapes");
  cmd->callback([a] {
    trial::SynthOptions o = trial::synth_options_from_parameters(a->values);
    o.seed = a->seed;
    o.shapes = a->shapes;
    trial::validate_synth_options(o);  // before the frame count below is used
    Progress progress("simulating frames", static_cast<std::size_t>(o.duration * o.frame_rate));
    trial::SynthStats st;
    RunControl control;
    std::size_t shown = 0;
    control.progress = [&](std::size_t done, std::size_t) {
      progress.advance(done - shown);
      shown = done;
    };
    const trial::Trial t = trial::synthesize_trial(o, &st, control);
    progress.finish();
    io::write_trial(t, a->out);
    std::cout << "vibrissa synth: " << st.frames << " frames, " << st.periods << " contact periods, "
              << st.contact_frames << " contact frames (" << st.slip_frames << " slipping, " << st.stick_frames
              << " sticking), " << st.slip_offs << " slip-offs, " << st.releases << " releases, " << st.failures
              << " solver failures; mu = " << o.mu << " -> " << a->out << "\n";
  });
}

}  // namespace vibrissa::cli
