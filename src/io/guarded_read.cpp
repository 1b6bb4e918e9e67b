#include "guarded_read.hpp"

#include <stdexcept>

#if defined(__unix__) || defined(__APPLE__)
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstring>
#endif

namespace vibrissa::io {

#if defined(__unix__) || defined(__APPLE__)
namespace {
// Exit codes of the child: the read returned, or threw (the caller's own read will throw the same).
constexpr int kReturned = 0;
constexpr int kThrew = 86;
}  // namespace

void probe_in_child(const std::string& path, std::string_view library, void (*read)(const void* context),
                    const void* context) {
  const pid_t pid = ::fork();
  if (pid < 0) return;  // no child (process limit): read in-process, as without the guard
  if (pid == 0) {
    // The child: default dispositions, so that Ctrl-C ends it without running the parent's clean-up handlers
    // (io/temporary_files.cpp) a second time and a crash ends it without the parent's crash reporters (Python's
    // faulthandler, a sanitizer's) printing for it; _exit, so that nothing of the parent's is flushed or destroyed.
    for (const int sig : {SIGINT, SIGTERM, SIGHUP, SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT}) std::signal(sig, SIG_DFL);
    int code = kReturned;
    try {
      read(context);
    } catch (...) {
      code = kThrew;
    }
    ::_exit(code);
  }
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0)
    if (errno != EINTR) return;  // cannot tell how it ended: read in-process
  if (WIFEXITED(status) && (WEXITSTATUS(status) == kReturned || WEXITSTATUS(status) == kThrew)) return;
  const std::string what = std::string(library);
  if (WIFSIGNALED(status)) {
    const int sig = WTERMSIG(status);
    if (sig == SIGINT || sig == SIGTERM || sig == SIGHUP)
      throw std::runtime_error(path + ": reading was interrupted (signal " + std::to_string(sig) + ")");
    const char* name = strsignal(sig);
    throw std::invalid_argument(path + ": " + what + " crashed reading this file (" + (name ? name : "signal") +
                                "): it is corrupted, or not the format its extension says; nothing was read");
  }
  throw std::invalid_argument(path + ": " + what + " failed reading this file (its reader process exited with " +
                              std::to_string(WIFEXITED(status) ? WEXITSTATUS(status) : -1) +
                              "): it is corrupted, or not the format its extension says; nothing was read");
}
#else
void probe_in_child(const std::string&, std::string_view, void (*)(const void*), const void*) {}
#endif

}  // namespace vibrissa::io
