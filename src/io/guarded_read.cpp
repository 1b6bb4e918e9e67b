#include "guarded_read.hpp"

#include <stdexcept>

#if defined(__linux__)
#include <dirent.h>
#include <fcntl.h>
#include <poll.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdio>
#endif

namespace vibrissa::io {

#if defined(__linux__)
namespace {

/// Reported by the child through the pipe before it leaves: the read returned, or threw.
constexpr char kReturned = 'R';
constexpr char kThrew = 'T';

/// Signals that mean the reading code crashed (the file's fault), with fixed names (strsignal may translate).
const char* crash_name(int sig) {
  switch (sig) {
    case SIGSEGV: return "segmentation fault";
    case SIGBUS: return "bus error";
    case SIGFPE: return "arithmetic exception";
    case SIGILL: return "illegal instruction";
    case SIGABRT: return "abort";
    case SIGSYS: return "bad system call";
    case SIGTRAP: return "trap";
    default: return nullptr;
  }
}

/// In the child: a signal with a handler gets the default disposition (an ignored one stays ignored), so that
/// Ctrl-C ends the child without running the parent's clean-up handlers (io/temporary_files.cpp) a second time,
/// and a crash ends it without the parent's crash reporters (a sanitizer's) printing for it.
void default_handled_signals() {
  for (const int sig : {SIGINT, SIGTERM, SIGHUP, SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT, SIGSYS, SIGTRAP}) {
    struct sigaction current {};
    if (sigaction(sig, nullptr, &current) == 0 && current.sa_handler != SIG_IGN) std::signal(sig, SIG_DFL);
  }
}

std::string corrupt(const std::string& path, std::string_view library, const std::string& how) {
  return path + ": " + std::string(library) + " " + how +
         ": it is corrupted, or not the format its extension says; nothing was read";
}

}  // namespace

bool single_threaded() {
  DIR* tasks = ::opendir("/proc/self/task");
  if (!tasks) return false;
  int n = 0;
  while (const dirent* e = ::readdir(tasks))
    if (e->d_name[0] != '.') ++n;
  ::closedir(tasks);
  return n == 1;
}

void probe_in_child(const std::string& path, std::string_view library, void (*read)(const void* context),
                    const void* context, double timeout_s) {
  if (!single_threaded()) return;
  int fds[2];
  if (::pipe2(fds, O_CLOEXEC) != 0) return;
  std::fflush(nullptr);  // nothing buffered is written twice if the library calls exit() in the child
  const pid_t pid = ::fork();
  if (pid < 0) {
    ::close(fds[0]);
    ::close(fds[1]);
    return;  // no child (process limit): read in-process, as without the guard
  }
  if (pid == 0) {
    ::close(fds[0]);
    default_handled_signals();
    // The library's own words (assimp's "ai_assert failure ...", HDF5's diagnostics) stay in the child: the
    // parent reports the outcome.
    if (const int null = ::open("/dev/null", O_WRONLY | O_CLOEXEC); null >= 0) {
      ::dup2(null, STDOUT_FILENO);
      ::dup2(null, STDERR_FILENO);
      ::close(null);
    }
    char outcome = kReturned;
    try {
      read(context);
    } catch (...) {
      outcome = kThrew;
    }
    (void)!::write(fds[1], &outcome, 1);
    ::_exit(0);  // nothing of the parent's is flushed or destroyed
  }
  ::close(fds[1]);
  // The outcome travels through the pipe, so the guard holds even where the child cannot be waited for (a
  // process that ignores SIGCHLD has its children reaped at once).
  if (timeout_s > 0.0) {  // wait for the outcome (or the child's end: EOF) at most timeout_s
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
    for (;;) {
      const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
      pollfd p{fds[0], POLLIN, 0};
      const int ready = left.count() > 0 ? ::poll(&p, 1, static_cast<int>(std::min<long long>(left.count(), 1000))) : 0;
      if (ready > 0) break;
      if (ready < 0 && errno == EINTR) continue;
      if (ready < 0 || std::chrono::steady_clock::now() >= deadline) {
        ::kill(pid, SIGKILL);
        ::close(fds[0]);
        int ignored = 0;
        while (::waitpid(pid, &ignored, 0) < 0 && errno == EINTR) {
        }
        char seconds[32];
        std::snprintf(seconds, sizeof seconds, "%.2g", timeout_s);
        throw std::invalid_argument(corrupt(path, library, std::string("did not finish reading this file within ") +
                                                               seconds + " s (a malformed file can make it loop)"));
      }
    }
  }
  char outcome = 0;
  ssize_t got;
  while ((got = ::read(fds[0], &outcome, 1)) < 0 && errno == EINTR) {
  }
  ::close(fds[0]);
  int status = 0;
  pid_t waited;
  while ((waited = ::waitpid(pid, &status, 0)) < 0 && errno == EINTR) {
  }
  if (got == 1 && (outcome == kReturned || outcome == kThrew)) return;
  if (waited == pid && WIFSIGNALED(status)) {
    const int sig = WTERMSIG(status);
    if (const char* name = crash_name(sig))
      throw std::invalid_argument(corrupt(path, library, std::string("crashed reading this file (") + name + ")"));
    throw std::runtime_error(path + ": the process reading it was killed by signal " + std::to_string(sig) +
                             " (interrupted, or out of memory); nothing was read");
  }
  if (waited == pid && WIFEXITED(status))
    throw std::invalid_argument(corrupt(path, library, "failed reading this file (its reader process exited with " +
                                                           std::to_string(WEXITSTATUS(status)) + ")"));
  throw std::invalid_argument(
      corrupt(path, library, "failed reading this file (its reader process ended without a word)"));
}
#else
bool single_threaded() { return false; }
void probe_in_child(const std::string&, std::string_view, void (*)(const void*), const void*, double) {}
#endif

}  // namespace vibrissa::io
