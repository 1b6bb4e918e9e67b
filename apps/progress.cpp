#include "progress.hpp"

#include <unistd.h>

#include <cstdio>

namespace vibrissa::cli {

Progress::Progress(std::string label, std::size_t total)
    : label_(std::move(label)), total_(total), enabled_(isatty(fileno(stderr)) != 0),
      start_(std::chrono::steady_clock::now()), last_draw_(start_) {
  draw(true);
}
Progress::~Progress() { finish(); }

void Progress::advance(std::size_t count) {
  done_ += count;
  draw(false);
}

void Progress::finish() {
  if (finished_) return;
  finished_ = true;
  done_ = total_;
  draw(true);
  if (enabled_) std::fputc('\n', stderr);
}

void Progress::draw(bool force) {
  if (!enabled_) return;
  const auto now = std::chrono::steady_clock::now();
  if (!force && now - last_draw_ < std::chrono::milliseconds(100)) return;
  last_draw_ = now;
  const int width = 30;
  const double frac = total_ ? double(done_) / double(total_) : 1.0;
  const int filled = static_cast<int>(frac * width);
  const double secs = std::chrono::duration<double>(now - start_).count();
  std::fprintf(stderr, "\r%s [%.*s%*s] %3.0f%% %.1fs", label_.c_str(), filled, "##############################",
               width - filled, "", 100.0 * frac, secs);
  std::fflush(stderr);
}

}  // namespace vibrissa::cli
