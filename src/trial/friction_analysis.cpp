#include "vibrissa/trial/friction_analysis.hpp"

#include <algorithm>
#include <cmath>

#include "vibrissa/core/checks.hpp"
#include "vibrissa/trial/statistics.hpp"

namespace vibrissa::trial {

FrictionAnalysis analyse_friction(const PipelineResult& r, Mode mode, const FrictionAnalysisOptions& o) {
  FrictionAnalysis a;
  const std::size_t n = r.frames.size();
  a.mu.assign(n, std::nan(""));
  a.outlier.assign(n, false);
  a.used.assign(n, false);
  std::vector<double> used_mu, used_fn;
  for (std::size_t i = 0; i < n; ++i) {
    const FrameResult& f = r.frames[i];
    const ModeFrame& m = f.mode(mode);
    if (!m.ok() || !(m.normal_force > 0.0)) continue;
    a.mu[i] = std::abs(m.friction_force) / m.normal_force;  // §3.3
    a.outlier[i] = m.normal_force < o.outlier_normal_force;
    if (a.outlier[i]) ++a.outliers;
    if (!a.outlier[i] && !f.period_edge) {
      a.used[i] = true;
      used_mu.push_back(a.mu[i]);
      used_fn.push_back(m.normal_force);
    }
  }
  a.frames_used = used_mu.size();
  // Slip: the contact point moves along the edge (central difference of its height within the period).
  a.slipping.assign(n, false);
  std::vector<double> slipping_mu;
  for (std::size_t i = 0; i < n; ++i) {
    if (!a.used[i]) continue;
    const std::size_t lo = i > 0 && r.frames[i - 1].period == r.frames[i].period ? i - 1 : i;
    const std::size_t hi = i + 1 < n && r.frames[i + 1].period == r.frames[i].period ? i + 1 : i;
    const double h_lo = r.frames[lo].mode(mode).height, h_hi = r.frames[hi].mode(mode).height;
    const double dt = r.frames[hi].time - r.frames[lo].time;
    if (hi == lo || !(dt > 0.0) || !std::isfinite(h_lo) || !std::isfinite(h_hi)) continue;
    if (std::abs(h_hi - h_lo) / dt > o.slip_speed) {
      a.slipping[i] = true;
      slipping_mu.push_back(a.mu[i]);
    }
  }
  a.frames_slipping = slipping_mu.size();
  a.histogram_edges.resize(static_cast<std::size_t>(o.histogram_bins) + 1);
  for (int b = 0; b <= o.histogram_bins; ++b) a.histogram_edges[static_cast<std::size_t>(b)] = o.histogram_max * b / o.histogram_bins;
  a.histogram_counts.assign(static_cast<std::size_t>(o.histogram_bins), 0);
  if (used_mu.empty()) {
    a.warnings.push_back("mu: no contact frame with F_N >= " + format_value(o.outlier_normal_force * 1e3) +
                         " mN outside the first and last two frames of a contact period (is the object in reach?)");
    return a;
  }
  a.median = median(used_mu);
  a.slip_fraction = static_cast<double>(a.frames_slipping) / static_cast<double>(a.frames_used);
  a.kind = a.slip_fraction >= o.min_slip_fraction ? "estimate" : "lower_bound";
  if (!slipping_mu.empty()) a.median_slipping = median(slipping_mu);
  else a.warnings.push_back("mu: no used frame slips along the edge, so no median over slipping frames");
  if (a.kind == "lower_bound")
    a.warnings.push_back("mu: only " + std::to_string(a.frames_slipping) + " of " + std::to_string(a.frames_used) +
                         " frames slip; in sticking frames |F_edge| / F_N is below mu, so the median is a lower "
                         "bound on mu, not an estimate");
  a.mean = mean(used_mu);
  a.sd = standard_deviation(used_mu);
  a.min = *std::min_element(used_mu.begin(), used_mu.end());
  a.max = *std::max_element(used_mu.begin(), used_mu.end());
  for (double m : used_mu) {
    auto b = static_cast<int>(std::floor(m / o.histogram_max * o.histogram_bins));
    b = std::clamp(b, 0, o.histogram_bins - 1);
    ++a.histogram_counts[static_cast<std::size_t>(b)];
  }
  // Fig. 3d: mean ± sd of mu in normal-force bins over all computed frames (outliers included, so the
  // growing scatter at small F_N shows).
  std::vector<double> all_mu, all_fn;
  for (std::size_t i = 0; i < n; ++i)
    if (std::isfinite(a.mu[i]) && !r.frames[i].period_edge) {
      all_mu.push_back(a.mu[i]);
      all_fn.push_back(r.frames[i].mode(mode).normal_force);
    }
  const double fmax = *std::max_element(all_fn.begin(), all_fn.end());
  const int B = std::max(1, o.normal_force_bins);
  for (int b = 0; b < B; ++b) {
    const double lo = fmax * b / B, hi = fmax * (b + 1) / B;
    std::vector<double> in;
    for (std::size_t k = 0; k < all_mu.size(); ++k)
      if (all_fn[k] >= lo && (all_fn[k] < hi || (b == B - 1 && all_fn[k] <= hi))) in.push_back(all_mu[k]);
    a.fn_bin_center.push_back(0.5 * (lo + hi));
    a.fn_bin_mean.push_back(mean(in));
    a.fn_bin_sd.push_back(standard_deviation(in));
    a.fn_bin_count.push_back(in.size());
  }
  return a;
}

}  // namespace vibrissa::trial
