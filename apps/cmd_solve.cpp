// `vibrissa solve CASE.json [-o RESULT.json]`: one whisker, one load (docs/formats.md).
// `vibrissa solve --jsonl FILE|-`: JSON Lines, one case per input line, one result per output line
// (docs/formats.md, "JSON Lines batch").
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <stdexcept>
#include <string>

#include "commands.hpp"
#include "vibrissa/core/checks.hpp"
#include "vibrissa/core/limits.hpp"
#include "vibrissa/io/atomic_file.hpp"
#include "vibrissa/io/case_json.hpp"
#include "vibrissa/io/json_file.hpp"
#include "vibrissa/io/json_input.hpp"

namespace vibrissa::cli {
namespace {

void print_warnings(const nlohmann::json& result, const std::string& where) {
  for (const auto& w : result.at("warnings"))
    std::cerr << "vibrissa: warning: " << where << w.get<std::string>() << "\n";
}

// Solves every non-blank line of `in` on its own (no warm start between lines, so each result equals
// `vibrissa solve` of that case). One compact JSON object per output line, flushed. A line that fails
// yields {"line": n, "error": message} and the run continues; returns the number of failed lines.
std::size_t solve_json_lines(std::istream& in, std::ostream& out) {
  std::size_t failed = 0;
  std::size_t line_number = 0;
  std::string line;
  while (std::getline(in, line)) {
    ++line_number;
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    const std::string source = "line " + std::to_string(line_number);
    nlohmann::json result;
    try {
      if (line.size() > limits::max_json_file_bytes)
        throw std::invalid_argument(source + " has " + std::to_string(line.size()) + " bytes, more than " +
                                    std::to_string(limits::max_json_file_bytes));
      result = solve_case_to_json(case_from_json(io::parse_json_text(line, source)));
      print_warnings(result, source + ": ");
    } catch (const std::exception& e) {
      ++failed;
      // A message may quote the line's bytes (invalid UTF-8 included): printable text, so that writing the
      // error line cannot fail and the batch goes on.
      const std::string message = printable_text(e.what());
      result = nlohmann::json{{"line", line_number}, {"error", message}};
      std::cerr << "vibrissa: error: " << (message.rfind(source, 0) == 0 ? "" : source + ": ") << message << "\n";
    }
    out << io::compact_json(result) << std::endl;  // flushed per line: a MATLAB or shell pipe sees each result at once
  }
  return failed;
}

}  // namespace

void register_solve(CLI::App& app) {
  auto* cmd = app.add_subcommand("solve", "Solve one case (whisker + load) given as JSON; see docs/formats.md");
  auto case_path = std::make_shared<std::string>();
  auto out_path = std::make_shared<std::string>();
  auto jsonl_path = std::make_shared<std::string>();
  auto* case_opt = cmd->add_option("CASE", *case_path, "case file (JSON)")->check(CLI::ExistingFile);
  auto* jsonl_opt = cmd->add_option("--jsonl", *jsonl_path,
                                    "JSON Lines batch: one case per line of FILE ('-': standard input), one "
                                    "result per line on standard output (or -o)");
  jsonl_opt->excludes(case_opt);
  case_opt->excludes(jsonl_opt);
  cmd->add_option("-o,--output", *out_path, "write the result here (JSON) instead of standard output");
  cmd->callback([case_path, out_path, jsonl_path, case_opt, jsonl_opt] {
    if (*jsonl_opt) {
      std::ifstream file;
      if (*jsonl_path != "-") {
        file.open(*jsonl_path);
        if (!file) throw std::invalid_argument("--jsonl: cannot open '" + *jsonl_path + "'");
      }
      std::istream& in = *jsonl_path == "-" ? std::cin : file;
      std::size_t failed = 0;
      if (out_path->empty())
        failed = solve_json_lines(in, std::cout);
      else  // atomic like every output file (docs/formats.md, "Atomic outputs"), error lines included
        io::write_text_atomically(*out_path, [&](std::ostream& out) { failed = solve_json_lines(in, out); });
      if (failed > 0) throw std::runtime_error(std::to_string(failed) + " line(s) of the JSON Lines batch failed");
      return;
    }
    if (!*case_opt) throw CLI::RequiredError("CASE or --jsonl");
    // files the case names (a mesh) are relative to the case file's folder (io::resolve_input_paths)
    const Case c = case_from_json(io::resolve_input_paths(read_json_file(*case_path),
                                                          std::filesystem::path(*case_path).parent_path()));
    const nlohmann::json result = solve_case_to_json(c);
    print_warnings(result, "");
    if (out_path->empty())
      std::cout << result.dump(2) << "\n";
    else
      write_json_file(*out_path, result);
  });
}

}  // namespace vibrissa::cli
