#include "run_python.hpp"

#include <cstdlib>
#include <filesystem>
#include <future>
#include <iostream>
#include <sstream>

namespace vibrissa::cli {
namespace {
std::string quote(const std::string& s) {
  std::string out;
  out.reserve(s.size() + 8);
  out.push_back('\'');
  for (char c : s) {
    if (c == '\'') {
      out.append("'\\''");
    } else {
      out.push_back(c);
    }
  }
  out.push_back('\'');
  return out;
}

std::filesystem::path figures_dir() {
  namespace fs = std::filesystem;
  if (const char* env_dir = std::getenv("VIBRISSA_FIGURES_DIR")) return env_dir;
  // Installed: <prefix>/libexec/vibrissa/vibrissa-full (the full tool, apps/CMakeLists.txt) and
  // <prefix>/share/vibrissa/figures (cmake --install, the .deb).
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    const fs::path installed = exe.parent_path().parent_path().parent_path() / VIBRISSA_FIGURES_INSTALL_DIR;
    if (fs::exists(installed / "trial_figures.py", ec)) return installed;
  }
  return VIBRISSA_FIGURES_SOURCE_DIR;  // the build tree: the scripts in the source tree
}

}  // namespace

int run_figure_script(const std::string& script, const std::vector<std::string>& args) {
  const std::filesystem::path path = figures_dir() / script;
  if (!std::filesystem::exists(path)) {
    std::cerr << "vibrissa: warning: figure script not found: " << path << " (figures skipped)\n";
    return 2;
  }
  std::ostringstream cmd;
  cmd << quote(VIBRISSA_PYTHON) << ' ' << quote(path.string());
  for (const auto& a : args) cmd << ' ' << quote(a);
  const int rc = std::system(cmd.str().c_str());
  if (rc != 0) std::cerr << "vibrissa: warning: figure script " << script << " failed (exit " << rc << ")\n";
  return rc;
}

void run_figure_scripts(const std::vector<FigureScript>& scripts) {
  std::vector<std::future<int>> running;
  for (const FigureScript& f : scripts)
    running.push_back(std::async(std::launch::async, [&f] { return run_figure_script(f.script, f.args); }));
  for (auto& r : running) r.get();
}

}  // namespace vibrissa::cli
