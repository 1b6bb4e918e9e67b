// `vibrissa solve CASE.json [-o RESULT.json]`: one whisker, one load (docs/formats.md).
#include <iostream>
#include <memory>

#include "commands.hpp"
#include "vibrissa/io/case_json.hpp"

namespace vibrissa::cli {

void register_solve(CLI::App& app) {
  auto* cmd = app.add_subcommand("solve", "Solve one case (whisker + load) given as JSON; see docs/formats.md");
  auto case_path = std::make_shared<std::string>();
  auto out_path = std::make_shared<std::string>();
  cmd->add_option("CASE", *case_path, "case file (JSON)")->required()->check(CLI::ExistingFile);
  cmd->add_option("-o,--output", *out_path, "write the result here (JSON) instead of standard output");
  cmd->callback([case_path, out_path] {
    const Case c = case_from_json(read_json_file(*case_path));
    const nlohmann::json result = solve_case_to_json(c);
    for (const auto& w : result.at("warnings")) std::cerr << "vibrissa: warning: " << w.get<std::string>() << "\n";
    if (out_path->empty())
      std::cout << result.dump(2) << "\n";
    else
      write_json_file(*out_path, result);
  });
}

}  // namespace vibrissa::cli
