// `vibrissa modes CASE.json [-o MODES.json]`: natural frequencies, damping ratios and mode shapes of a whisker.
// `vibrissa dynamics CASE.json --out DIR`: its motion with a prescribed base (docs/dynamics.md).
#include <cstdio>
#include <iostream>
#include <stdexcept>
#include <memory>
#include <string>

#include "commands.hpp"
#include "vibrissa/io/case_json.hpp"
#include "vibrissa/io/dynamics_case.hpp"
#include "vibrissa/io/json_file.hpp"

namespace vibrissa::cli {

void register_modes(CLI::App& app) {
  auto* cmd = app.add_subcommand("modes", "Natural vibration modes of a whisker about its rest shape, or about its "
                                          "equilibrium under the case's \"load\"; see docs/dynamics.md");
  auto case_path = std::make_shared<std::string>();
  auto out_path = std::make_shared<std::string>();
  auto count = std::make_shared<int>(0);
  cmd->add_option("CASE", *case_path, "case file (JSON: whisker, dynamics, optional load and contact)")->required()->check(CLI::ExistingFile);
  cmd->add_option("-o,--output", *out_path, "write the modes here (JSON) instead of standard output")
      ->check(output_path());
  cmd->add_option("-n,--count", *count, "number of modes (default: the case's \"modes\", else 10)")
      ->check(CLI::Range(1, 100000));
  cmd->callback([case_path, out_path, count] {
    const io::DynamicsCase c = io::dynamics_case_from_json(read_json_file(*case_path));
    const int n = *count > 0 ? *count : c.mode_count;
    const io::CaseModes cm = io::case_modes(c, n);
    const dynamics::Modes& m = cm.modes;
    nlohmann::json result = io::modes_to_json(m, c.whisker, c);
    if (cm.deflected) result["equilibrium"] = io::equilibrium_to_json(cm, c.whisker);
    if (out_path->empty()) {
      if (cm.deflected) {
        const auto& e = result["equilibrium"];
        std::cout << "about the equilibrium under the load (" << e["load"].get<std::string>() << ", contact "
                  << e["contact"].get<std::string>() << ", " << cm.deflected->constraints
                  << " constraints): force_B " << e["force_B"].dump() << " N at s = " << cm.held.arc_length
                  << " m, tip_B " << e["tip_B"].dump() << " m\n";
      }
      std::cout << "mode  frequency_Hz  damped_Hz  damping_ratio  torsion_fraction\n";
      for (int i = 0; i < m.count(); ++i)
        std::printf("%4d  %12.4f  %9.4f  %13.4f  %16.3f\n", i + 1, m.frequency_hz(i), m.damped_frequency_hz(i),
                    m.damping_ratio(i), m.torsion_fraction(i));
    } else {
      io::write_json_file(*out_path, result);
    }
  });
}

void register_dynamics(CLI::App& app) {
  auto* cmd = app.add_subcommand("dynamics", "Motion of a whisker whose base whisks or holds still, in air or "
                                             "against pegs and edges (implicit integration, linear or nonlinear "
                                             "chain); see docs/dynamics.md");
  auto case_path = std::make_shared<std::string>();
  auto out_dir = std::make_shared<std::string>();
  cmd->add_option("CASE", *case_path, "case file (JSON: whisker, dynamics, whisking, initial, objects, contact, model, "
                                     "duration, output_rate)")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("--out", *out_dir, "output folder: dynamics.csv, dynamics.h5, summary.json")
      ->required()
      ->check(output_path());
  cmd->callback([case_path, out_dir] {
    const io::DynamicsCase c = io::dynamics_case_from_json(read_json_file(*case_path));
    const dynamics::LinearModel model = dynamics::linear_model(c.whisker, c.properties);
    const dynamics::Modes all = dynamics::modes(model, c.whisker);
    const dynamics::TimeSeries ts = dynamics::simulate(c.whisker, model, all, io::base_trajectory(c),
                                                       c.properties.gravity_W, c.options, io::initial_state(c, model),
                                                       io::external_load(c));
    const nlohmann::json summary = io::dynamics_summary(ts, all, c);
    io::write_dynamics_outputs(ts, summary, *out_dir);
    std::cout << summary.dump(2) << "\n";
    for (const auto& w : summary.at("warnings")) std::cerr << "vibrissa: warning: " << w.get<std::string>() << "\n";
    if (ts.status != dynamics::SimulationStatus::completed)
      throw std::runtime_error("the integration stopped early: " + std::string(dynamics::to_string(ts.status)));
  });
}

}  // namespace vibrissa::cli
