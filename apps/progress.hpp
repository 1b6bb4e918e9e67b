#pragma once
// A progress bar on a terminal (stderr), silent when stderr is not a terminal (pipes, CI, files).
#include <chrono>
#include <cstddef>
#include <string>

namespace vibrissa::cli {

class Progress {
 public:
  Progress(std::string label, std::size_t total);
  ~Progress();
  void advance(std::size_t count = 1);  ///< thread-compatible: call from one thread
  void finish();

 private:
  void draw(bool force);
  std::string label_;
  std::size_t total_, done_ = 0;
  bool enabled_, finished_ = false;
  std::chrono::steady_clock::time_point start_, last_draw_;
};

}  // namespace vibrissa::cli
