#include "vibrissa/io/temporary_files.hpp"

#include <signal.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <string>

namespace vibrissa::io {
namespace {

// A slot is free, being filled (invisible to the handler) or live (its path may be unlinked at any time).
enum SlotState : int { kFree = 0, kFilling = 1, kLive = 2 };

struct Slot {
  std::atomic<int> state{kFree};
  bool folder = false;  // written before the slot turns live
  char path[kMaxTemporaryPath] = {};
};
static_assert(std::atomic<int>::is_always_lock_free, "the signal handler needs lock-free atomics");

// Static storage: nothing is allocated while registering or in the handler.
std::array<Slot, kMaxLiveTemporaries> g_slots;

extern "C" void cleanup_and_reraise(int sig) {
  const int saved_errno = errno;
  unlink_live_temporaries();
  errno = saved_errno;
  // SA_RESETHAND restored the default action; the signal is blocked until the handler returns, then the
  // default action ends the process with this signal's status.
  raise(sig);
}

std::size_t register_slot(const std::filesystem::path& path, bool folder) {
  const std::string& text = path.native();
  if (text.size() >= kMaxTemporaryPath)
    throw std::runtime_error("temporary file path is " + std::to_string(text.size()) + " bytes, longer than " +
                             std::to_string(kMaxTemporaryPath - 1) + ": " + text);
  for (std::size_t i = 0; i < g_slots.size(); ++i) {
    int expected = kFree;
    if (!g_slots[i].state.compare_exchange_strong(expected, kFilling)) continue;
    std::memcpy(g_slots[i].path, text.c_str(), text.size() + 1);
    g_slots[i].folder = folder;
    g_slots[i].state.store(kLive);
    return i;
  }
  throw std::runtime_error("more than " + std::to_string(kMaxLiveTemporaries) +
                           " temporary files open at once; cannot track " + text);
}

}  // namespace

std::size_t register_temporary(const std::filesystem::path& path) { return register_slot(path, false); }
std::size_t register_temporary_folder(const std::filesystem::path& path) { return register_slot(path, true); }

void unregister_temporary(std::size_t slot) noexcept {
  if (slot < g_slots.size()) g_slots[slot].state.store(kFree);
}

std::size_t live_temporaries() noexcept {
  std::size_t n = 0;
  for (const Slot& s : g_slots) n += s.state.load() == kLive ? 1 : 0;
  return n;
}

void unlink_live_temporaries() noexcept {
  for (Slot& s : g_slots)
    if (s.state.load() == kLive && !s.folder) ::unlink(s.path);
  for (Slot& s : g_slots)
    if (s.state.load() == kLive && s.folder) ::rmdir(s.path);
}

void install_cleanup_signal_handlers() {
  struct sigaction action {};
  action.sa_handler = cleanup_and_reraise;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESETHAND;
  for (const int sig : {SIGINT, SIGTERM, SIGHUP}) {
    struct sigaction current {};
    // A signal ignored on entry stays ignored (nohup, background jobs of non-interactive shells).
    if (sigaction(sig, nullptr, &current) == 0 && current.sa_handler == SIG_IGN) continue;
    if (sigaction(sig, &action, nullptr) != 0)
      throw std::runtime_error("cannot install the handler for signal " + std::to_string(sig) + ": " +
                               std::strerror(errno));
  }
}

}  // namespace vibrissa::io
