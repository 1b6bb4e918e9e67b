#include "vibrissa/trial/friction_analysis.hpp"

#include <algorithm>
#include <cmath>

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
  a.histogram_edges.resize(static_cast<std::size_t>(o.histogram_bins) + 1);
  for (int b = 0; b <= o.histogram_bins; ++b) a.histogram_edges[static_cast<std::size_t>(b)] = o.histogram_max * b / o.histogram_bins;
  a.histogram_counts.assign(static_cast<std::size_t>(o.histogram_bins), 0);
  if (used_mu.empty()) return a;
  a.median = median(used_mu);
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
