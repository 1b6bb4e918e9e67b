#pragma once
// Runs a long C++ call from Python so that it behaves like a Python call: other Python threads keep running,
// Ctrl-C stops it, and a `progress(done, total)` callback sees its progress.
//
//   auto result = run_interruptible([&](const RunControl& control) { return simulate_array(config, control); },
//                                   progress);
//
// The callable runs on a worker std::thread with the GIL released (it must not touch Python objects). The
// calling thread waits in slices of at most kSlice; between slices it takes the GIL, runs the pending signal
// handlers (PyErr_CheckSignals: Ctrl-C raises KeyboardInterrupt) and calls `progress` with the latest counts
// if they grew. On a Python exception (a signal, or one raised by `progress`) it sets the cancel flag,
// waits for the worker to stop at its next work item (the callable throws Cancelled) and re-raises the Python
// exception. Exceptions thrown by the callable are re-raised in the caller and translated by pybind11
// (std::invalid_argument -> ValueError with the C++ message). After a normal return `progress` is called
// once more with the final counts, if they grew since the last call: counts reach Python
// strictly increasing.
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <exception>
#include <mutex>
#include <optional>
#include <thread>
#include <type_traits>
#include <utility>

#include <pybind11/pybind11.h>

#include "vibrissa/core/run_control.hpp"

namespace vibrissa::python {

namespace py = pybind11;

/// Longest time between two checks for signals (and progress reports) on the calling thread.
inline constexpr std::chrono::milliseconds kInterruptSlice{50};

namespace detail {

/// State shared by the calling thread and the worker. Progress counts are written by the worker's
/// RunControl callback and read by the calling thread; `finished` is guarded by `mutex`.
struct WorkerState {
  std::atomic<bool> cancel{false};
  std::atomic<std::size_t> done{0}, total{0};  ///< done: the largest count reported so far
  std::mutex mutex;
  std::condition_variable cv;
  bool finished = false;
  std::exception_ptr error;
};

/// Joins the worker on every exit path (cancelling it first unless it finished), with the GIL released.
class WorkerGuard {
 public:
  WorkerGuard(std::thread& worker, WorkerState& state) : worker_(worker), state_(state) {}
  WorkerGuard(const WorkerGuard&) = delete;
  WorkerGuard& operator=(const WorkerGuard&) = delete;
  ~WorkerGuard() {
    if (!worker_.joinable()) return;
    state_.cancel.store(true);
    py::gil_scoped_release release;
    worker_.join();
  }

 private:
  std::thread& worker_;
  WorkerState& state_;
};

}  // namespace detail

/// Calls `work(control)` as described above and returns its result. Must be called with the GIL held.
/// `progress` is None or a Python callable progress(done: int, total: int).
template <class Work>
auto run_interruptible(Work&& work, const py::object& progress) {
  using Result = std::invoke_result_t<Work&, const RunControl&>;
  static_assert(!std::is_void_v<Result>, "run_interruptible: the callable must return a value");
  detail::WorkerState state;
  RunControl control;
  control.cancel = &state.cancel;
  control.progress = [&state](std::size_t done, std::size_t total) {
    // Counts from several worker threads may arrive out of order: keep the largest, so Python sees a
    // non-decreasing sequence.
    state.total.store(total);
    std::size_t seen = state.done.load();
    while (done > seen && !state.done.compare_exchange_weak(seen, done)) {
    }
  };
  std::optional<Result> result;
  std::thread worker([&] {
    try {
      result.emplace(work(control));
    } catch (...) {
      state.error = std::current_exception();
    }
    {
      const std::lock_guard<std::mutex> lock(state.mutex);
      state.finished = true;
    }
    state.cv.notify_all();
  });
  detail::WorkerGuard guard(worker, state);

  std::size_t reported = 0;  // the count passed to the last Python progress call
  auto report = [&] {
    const std::size_t done = state.done.load();
    if (progress.is_none() || done == reported) return;
    reported = done;
    progress(done, state.total.load());
  };
  for (;;) {
    bool finished = false;
    {
      py::gil_scoped_release release;
      std::unique_lock<std::mutex> lock(state.mutex);
      finished = state.cv.wait_for(lock, kInterruptSlice, [&] { return state.finished; });
    }
    if (finished) break;
    if (PyErr_CheckSignals() != 0) throw py::error_already_set();  // the guard cancels and joins
    report();  // an exception from the callback also cancels through the guard
  }
  {
    py::gil_scoped_release release;
    worker.join();
  }
  if (state.error) std::rethrow_exception(state.error);
  report();
  return std::move(*result);
}

}  // namespace vibrissa::python
