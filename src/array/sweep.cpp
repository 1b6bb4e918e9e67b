#include "vibrissa/array/sweep.hpp"

#include <algorithm>
#include <cmath>

namespace vibrissa::array {

WhiskerRunSummary summarize_run(const ArrayResult& r, std::size_t p, std::size_t w) {
  WhiskerRunSummary s;
  for (std::size_t f = 0; f < r.n_frames; ++f) {
    const std::size_t k = r.index(p, w, f);
    const auto state = static_cast<ContactState>(r.state[k]);
    if (state == ContactState::pushed_past) s.pushed_past = true;
    if (state != ContactState::contact) continue;
    if (!s.touched) s.onset_time = r.times[f];
    s.touched = true;
    ++s.contact_frames;
    s.peak_FT = std::max(s.peak_FT, r.FT[k]);
    if (r.MB[k] > s.peak_MB) {
      s.peak_MB = r.MB[k];
      s.MD_at_peak_MB = r.MD[k];
    }
    s.peak_abs_Fx = std::max(s.peak_abs_Fx, std::abs(r.force_B[3 * k]));
    s.max_abs_z_error = std::max(s.max_abs_z_error, std::abs(r.z_error[k]));
  }
  return s;
}

std::vector<PitchSummary> summarize_pitches(const ArrayResult& r) {
  std::vector<PitchSummary> out;
  for (std::size_t p = 0; p < r.n_pitches; ++p) {
    PitchSummary ps;
    ps.pitch = r.pitches[p];
    double sum_mb = 0.0, sum_ft = 0.0;
    bool any = false;
    for (std::size_t w = 0; w < r.n_whiskers; ++w) {
      const WhiskerRunSummary s = summarize_run(r, p, w);
      ps.whiskers.push_back(s);
      if (s.pushed_past) ++ps.whiskers_pushed_past;
      if (!s.touched) continue;
      ++ps.whiskers_touching;
      ps.contact_frames += s.contact_frames;
      sum_mb += s.peak_MB;
      sum_ft += s.peak_FT;
      if (s.peak_MB > ps.peak_MB) {
        ps.peak_MB = s.peak_MB;
        ps.peak_MB_whisker = r.labels[w];
      }
      ps.max_abs_z_error = std::max(ps.max_abs_z_error, s.max_abs_z_error);
      ps.first_onset_time = any ? std::min(ps.first_onset_time, s.onset_time) : s.onset_time;
      any = true;
    }
    if (ps.whiskers_touching > 0) {
      ps.mean_peak_MB = sum_mb / double(ps.whiskers_touching);
      ps.mean_peak_FT = sum_ft / double(ps.whiskers_touching);
    }
    out.push_back(std::move(ps));
  }
  return out;
}

std::vector<std::string> array_warnings(const ArrayResult& r) {
  std::vector<std::string> out;
  const bool touched = std::any_of(r.state.begin(), r.state.end(), [](std::int8_t s) { return s != 0; });
  if (!touched && !r.state.empty())
    out.push_back("no whisker touches any object in any frame: is the scene out of reach (object positions are in mm)?");
  return out;
}

}  // namespace vibrissa::array
