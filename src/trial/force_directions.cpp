#include "vibrissa/trial/force_directions.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "vibrissa/trial/statistics.hpp"

namespace vibrissa::trial {

double wrap_angle(double a) {
  a = std::remainder(a, 2.0 * std::numbers::pi);
  return a <= -std::numbers::pi ? a + 2.0 * std::numbers::pi : a;
}

namespace {

constexpr double deg = 180.0 / std::numbers::pi;

double unwrapped_range(const std::vector<double>& a) {
  double lo = a.front(), hi = a.front(), cur = a.front();
  for (std::size_t k = 1; k < a.size(); ++k) {
    cur += wrap_angle(a[k] - a[k - 1]);
    lo = std::min(lo, cur);
    hi = std::max(hi, cur);
  }
  return hi - lo;
}

DirectionRanges ranges(const PipelineResult& r, Mode mode) {
  DirectionRanges out;
  for (std::size_t p = 0; p < r.pre.periods.size(); ++p) {
    std::vector<double> fd, md;
    for (std::size_t i = r.pre.periods[p].first; i <= r.pre.periods[p].last; ++i) {
      const FrameResult& f = r.frames[i];
      const ModeFrame& m = f.mode(mode);
      if (f.period_edge || !m.ok()) continue;
      fd.push_back(m.signals_B.FD);
      md.push_back(m.signals_B.MD);
    }
    if (fd.size() < 2) continue;
    out.fd_range_deg.push_back(unwrapped_range(fd) * deg);
    out.md_range_deg.push_back(unwrapped_range(md) * deg);
  }
  out.mean_fd_range_deg = mean(out.fd_range_deg);
  out.mean_md_range_deg = mean(out.md_range_deg);
  return out;
}

}  // namespace

ForceDirectionAnalysis analyse_force_directions(const PipelineResult& r) {
  ForceDirectionAnalysis a;
  if (r.has_contact_point_mode) a.contact_point = ranges(r, Mode::contact_point);
  if (r.has_edge_mode) a.edge = ranges(r, Mode::edge);
  if (r.has_frictional_mode) a.frictional = ranges(r, Mode::frictional_edge);
  std::vector<double> dfd, dmd;
  for (const FrameResult& f : r.frames)
    if (!f.period_edge && f.contact_point.ok() && f.edge.ok()) {
      dfd.push_back(wrap_angle(f.contact_point.signals_B.FD - f.edge.signals_B.FD) * deg);
      dmd.push_back(wrap_angle(f.contact_point.signals_B.MD - f.edge.signals_B.MD) * deg);
    }
  a.mean_fd_offset_deg = mean(dfd);
  a.mean_md_offset_deg = mean(dmd);
  return a;
}

}  // namespace vibrissa::trial
