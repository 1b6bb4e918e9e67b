#include "run_python.hpp"

#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
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

// The prefix of an installed full tool, <prefix>/libexec/vibrissa/vibrissa-full (apps/CMakeLists.txt); the
// build tree has the same layout under <build>.
std::filesystem::path install_prefix() {
  std::error_code ec;
  const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  return ec ? std::filesystem::path() : exe.parent_path().parent_path().parent_path();
}

std::filesystem::path figures_dir() {
  if (const char* env_dir = std::getenv("VIBRISSA_FIGURES_DIR")) return env_dir;
  // Installed: <prefix>/share/vibrissa/figures (cmake --install, the .deb).
  std::error_code ec;
  const std::filesystem::path installed = install_prefix() / VIBRISSA_FIGURES_INSTALL_DIR;
  if (std::filesystem::exists(installed / "trial_figures.py", ec)) return installed;
  return VIBRISSA_FIGURES_SOURCE_DIR;  // the build tree: the scripts in the source tree
}

// $VIBRISSA_PYTHON (the pip-installed command sets it to its own interpreter), else the one found at configure time.
std::string python_interpreter() {
  const char* env = std::getenv("VIBRISSA_PYTHON");
  return env && *env ? env : VIBRISSA_PYTHON;
}

}  // namespace

namespace {
// The shell command running figure script `script` with `args`, or "" (after a warning) if it is missing.
std::string figure_command(const std::string& script, const std::vector<std::string>& args) {
  const std::filesystem::path path = figures_dir() / script;
  if (!std::filesystem::exists(path)) {
    std::cerr << "vibrissa: warning: figure script not found: " << path << " (figures skipped)\n";
    return {};
  }
  std::ostringstream cmd;
  cmd << quote(python_interpreter()) << ' ' << quote(path.string());
  for (const auto& a : args) cmd << ' ' << quote(a);
  return cmd.str();
}

int report_figure_status(const std::string& script, int rc) {
  if (rc != 0) std::cerr << "vibrissa: warning: figure script " << script << " failed (exit " << rc << ")\n";
  return rc;
}
}  // namespace

int run_figure_script(const std::string& script, const std::vector<std::string>& args) {
  const std::string cmd = figure_command(script, args);
  if (cmd.empty()) return 2;
  return report_figure_status(script, std::system(cmd.c_str()));
}

EarlyFigureScript::EarlyFigureScript(const std::string& script, const std::vector<std::string>& args)
    : script_(script) {
  std::vector<std::string> all = args;
  all.emplace_back("--start-on-stdin");
  const std::string cmd = figure_command(script, all);
  if (cmd.empty()) return;
  std::cout.flush();  // the script shares standard output
  pipe_ = ::popen(cmd.c_str(), "w");
  if (pipe_ == nullptr) std::cerr << "vibrissa: warning: cannot start figure script " << script << ": " << std::strerror(errno) << "\n";
}

EarlyFigureScript::~EarlyFigureScript() {
  if (pipe_ != nullptr) ::pclose(pipe_);  // end of input without "go": the script exits drawing nothing
}

int EarlyFigureScript::run() {
  if (pipe_ == nullptr) return 2;
  std::cout.flush();
  // A script that already died (e.g. an import error) closed its end: a write must then fail, not raise SIGPIPE.
  void (*previous)(int) = std::signal(SIGPIPE, SIG_IGN);
  std::fputs("go\n", pipe_);
  std::fflush(pipe_);
  std::signal(SIGPIPE, previous);
  const int rc = ::pclose(pipe_);
  pipe_ = nullptr;
  return report_figure_status(script_, rc);
}

void run_figure_scripts(const std::vector<FigureScript>& scripts) {
  std::vector<std::future<int>> running;
  for (const FigureScript& f : scripts)
    running.push_back(std::async(std::launch::async, [&f] {
      return f.module ? run_python_module(f.script, f.args) : run_figure_script(f.script, f.args);
    }));
  for (auto& r : running) r.get();
}

namespace {
// PYTHONPATH for the vibrissa package: installed beside this tool (<prefix>/<python install dir>/vibrissa),
// else the build tree's. A package the interpreter finds by itself (the .deb's dist-packages) also works with
// neither (then PYTHONPATH is returned unchanged).
std::string package_python_path() {
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::path root = install_prefix() / VIBRISSA_PYTHON_PACKAGE_INSTALL_DIR;
  if (!fs::exists(root / "vibrissa" / "__init__.py", ec)) root = VIBRISSA_PYTHON_PACKAGE_BUILD_DIR;
  const char* old = std::getenv("PYTHONPATH");
  std::string path = old ? old : "";
  if (fs::exists(root / "vibrissa" / "__init__.py", ec)) path = path.empty() ? root.string() : root.string() + ":" + path;
  return path;
}
}  // namespace

int run_python_module(const std::string& module, const std::vector<std::string>& args) {
  std::ostringstream cmd;
  cmd << "PYTHONPATH=" << quote(package_python_path()) << ' ' << quote(python_interpreter()) << " -m "
      << quote(module);
  for (const auto& a : args) cmd << ' ' << quote(a);
  const int rc = std::system(cmd.str().c_str());
  if (rc != 0) std::cerr << "vibrissa: warning: python -m " << module << " failed (exit " << rc << ")\n";
  return rc;
}

int exec_python_module(const std::string& module, const std::vector<std::string>& args) {
  if (const std::string path = package_python_path(); !path.empty()) ::setenv("PYTHONPATH", path.c_str(), 1);
  const std::string python = python_interpreter();
  std::vector<std::string> words{python, "-m", module};
  words.insert(words.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (std::string& w : words) argv.push_back(w.data());
  argv.push_back(nullptr);
  std::cout.flush();
  ::execvp(python.c_str(), argv.data());  // Python takes over this process: Ctrl-C and exit status are its own
  std::cerr << "vibrissa: error: cannot run " << python << " -m " << module << ": " << std::strerror(errno) << "\n";
  return 1;
}

}  // namespace vibrissa::cli
