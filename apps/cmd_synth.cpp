// `vibrissa synth OUT [options]`: write a synthetic whisking trial simulated with the frictional edge mode
// (docs/trials.md, "Synthetic trials").
#include <array>
#include <iostream>
#include <memory>
#include <numbers>

#include "commands.hpp"
#include "progress.hpp"
#include "vibrissa/io/trial_io.hpp"
#include "vibrissa/trial/synth.hpp"

namespace vibrissa::cli {

void register_synth(CLI::App& app) {
  auto* cmd = app.add_subcommand("synth", "Write a synthetic trial: whisking against a peg with friction (docs/trials.md)");
  auto out = std::make_shared<std::string>();
  auto o = std::make_shared<trial::SynthOptions>();
  auto deg = std::make_shared<std::array<double, 5>>();  // theta center, amplitude, peg azimuth, noise angle, phi center
  const double r2d = 180.0 / std::numbers::pi;
  (*deg)[0] = o->theta_center * r2d;
  (*deg)[1] = o->theta_amplitude * r2d;
  (*deg)[2] = o->peg_azimuth * r2d;
  (*deg)[3] = 0.0;
  (*deg)[4] = o->phi_center * r2d;
  auto mm = std::make_shared<std::array<double, 3>>();  // whisker length, peg distance [mm], noise [um]
  (*mm)[0] = o->whisker_length * 1e3;
  (*mm)[1] = o->peg_distance * 1e3;
  (*mm)[2] = 0.0;
  cmd->add_option("OUT", *out, "output trial file (.csv, .h5/.hdf5 or .mat)")->required();
  cmd->add_option("--duration", o->duration, "trial length [s]")->capture_default_str();
  cmd->add_option("--frame-rate", o->frame_rate, "frames per second [Hz]")->capture_default_str();
  cmd->add_option("--whisk-hz", o->whisk_frequency, "whisking frequency [Hz]")->capture_default_str();
  cmd->add_option("--mu", o->mu, "friction coefficient of the simulation")->capture_default_str();
  cmd->add_option("--theta-center-deg", (*deg)[0], "centre of the whisk [deg]")->capture_default_str();
  cmd->add_option("--theta-amplitude-deg", (*deg)[1], "half the whisk amplitude [deg]")->capture_default_str();
  cmd->add_option("--protraction-fraction", o->protraction_fraction, "fraction of a whisk spent protracting")
      ->capture_default_str();
  cmd->add_option("--phi-slope", o->phi_slope, "d phi / d theta (spec §2.2)")->capture_default_str();
  cmd->add_option("--zeta-slope", o->zeta_slope, "d zeta / d theta (spec §2.2)")->capture_default_str();
  cmd->add_option("--whisker-length-mm", (*mm)[0], "whisker arc length [mm]")->capture_default_str();
  cmd->add_option("--curvature", o->curvature, "rest shape y = a x^2, a [1/m]")->capture_default_str();
  cmd->add_option("--peg-distance-mm", (*mm)[1], "horizontal distance base to peg [mm]")->capture_default_str();
  cmd->add_option("--peg-azimuth-deg", (*deg)[2], "azimuth of the peg about +z [deg]")->capture_default_str();
  cmd->add_option("--noise-position-um", (*mm)[2], "sd of tracking noise on base and contact point [um]");
  cmd->add_option("--noise-angle-deg", (*deg)[3], "sd of tracking noise on the angles [deg]");
  cmd->add_option("--seed", o->seed, "random seed for the noise")->capture_default_str();
  cmd->add_flag("--shapes", o->shapes, "also write tracked 3D whisker shapes");
  cmd->callback([out, o, deg, mm] {
    const double d2r = std::numbers::pi / 180.0;
    o->theta_center = (*deg)[0] * d2r;
    o->theta_amplitude = (*deg)[1] * d2r;
    o->peg_azimuth = (*deg)[2] * d2r;
    o->noise_angle = (*deg)[3] * d2r;
    o->whisker_length = (*mm)[0] * 1e-3;
    o->peg_distance = (*mm)[1] * 1e-3;
    o->noise_position = (*mm)[2] * 1e-6;
    Progress progress("simulating frames", static_cast<std::size_t>(o->duration * o->frame_rate));
    trial::SynthStats st;
    RunControl control;
    std::size_t shown = 0;
    control.progress = [&](std::size_t done, std::size_t) {
      progress.advance(done - shown);
      shown = done;
    };
    const trial::Trial t = trial::synthesize_trial(*o, &st, control);
    progress.finish();
    io::write_trial(t, *out);
    std::cout << "vibrissa synth: " << st.frames << " frames, " << st.periods << " contact periods, "
              << st.contact_frames << " contact frames (" << st.slip_frames << " slipping, " << st.stick_frames
              << " sticking), " << st.slip_offs << " slip-offs, " << st.releases << " releases, " << st.failures
              << " solver failures; mu = " << o->mu << " -> " << *out << "\n";
  });
}

}  // namespace vibrissa::cli
