#pragma once
// Progress and cooperative cancellation for long calls (trial pipeline, synthetic trials, array simulations,
// batches). A caller fills a RunControl; the long call wraps it in a ProgressCounter, which counts finished work
// items from any thread, forwards the count to the callback (serialised: never two calls at once), and
// throws Cancelled at the next work item once the cancel flag reads true.
#include <atomic>
#include <cstddef>
#include <functional>
#include <mutex>
#include <stdexcept>

namespace vibrissa {

/// Thrown by a long call whose RunControl::cancel flag was set; nothing it would have returned is valid.
class Cancelled : public std::runtime_error {
 public:
  Cancelled() : std::runtime_error("cancelled") {}
};

struct RunControl {
  /// Called with (items done, items in total); serialised, from whichever thread finished the item.
  std::function<void(std::size_t done, std::size_t total)> progress;
  /// Polled between work items (frames, contact periods, whiskers); the call throws Cancelled once true.
  const std::atomic<bool>* cancel = nullptr;
  [[nodiscard]] bool cancelled() const { return cancel != nullptr && cancel->load(std::memory_order_relaxed); }
};

/// The counting side of a RunControl inside one long call. Thread-safe.
class ProgressCounter {
 public:
  ProgressCounter(const RunControl& control, std::size_t total) : control_(control), total_(total) {}
  /// Throws Cancelled if the caller asked to stop.
  void check() const {
    if (control_.cancelled()) throw Cancelled();
  }
  /// Records `items` more finished items, reports, then checks for cancellation.
  void advance(std::size_t items = 1) {
    const std::size_t now = done_.fetch_add(items, std::memory_order_relaxed) + items;
    if (control_.progress) {
      const std::lock_guard<std::mutex> lock(mutex_);
      control_.progress(now < total_ ? now : total_, total_);
    }
    check();
  }
  [[nodiscard]] std::size_t total() const { return total_; }

 private:
  const RunControl& control_;
  std::size_t total_;
  std::atomic<std::size_t> done_{0};
  std::mutex mutex_;
};

}  // namespace vibrissa
