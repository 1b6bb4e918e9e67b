#include "vibrissa/trial/z_error.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace vibrissa::trial {

double cone_length(double S, double R_base, double ratio) {
  const double R_tip = R_base / ratio;
  return R_base / (R_base - R_tip) * S;  // eq. (5)
}

double tapered_beam_compliance(double s, double L, double E, double R) {
  return 4.0 * L / (3.0 * E * std::numbers::pi * std::pow(R, 4)) * s * s * s / (L - s);  // eqs. (4), (6)
}

namespace {
ZErrorFit fit_pairs(const std::vector<double>& x, const std::vector<double>& y) {
  ZErrorFit f;
  if (x.size() < 3) return f;
  try {
    f.all = fit_line(x, y);
  } catch (const std::invalid_argument&) {
    return f;
  }
  const auto ox = iqr_outliers(x), oy = iqr_outliers(y);
  std::vector<double> xi, yi;
  for (std::size_t k = 0; k < x.size(); ++k) {
    if (ox[k] || oy[k]) {
      ++f.outliers;
      continue;
    }
    xi.push_back(x[k]);
    yi.push_back(y[k]);
  }
  if (xi.size() >= 3) {
    try {
      f.without_outliers = fit_line(xi, yi);
    } catch (const std::invalid_argument&) {
    }
  }
  return f;
}
}  // namespace

ZErrorAnalysis analyse_z_error(const PipelineResult& r, double whisker_length, double mu) {
  ZErrorAnalysis a;
  const auto& mat = r.pre.trial.meta.material;
  a.mu_eq7 = mu;
  a.cone_length = cone_length(whisker_length, mat.base_radius, mat.taper_ratio);
  if (!std::isfinite(a.cone_length)) a.cone_length = std::nan("");  // no cone: taper ratio 1
  const std::size_t n = r.frames.size();
  a.measured.assign(n, std::nan(""));
  a.eq6.assign(n, std::nan(""));
  a.eq7.assign(n, std::nan(""));
  a.used.assign(n, false);
  std::vector<double> x, y6, y7, diffs;
  for (std::size_t i = 0; i < n; ++i) {
    const FrameResult& f = r.frames[i];
    const ModeFrame &cp = f.contact_point, &ed = f.edge;
    if (ed.ok() && f.period >= 0) {
      const double z_onset = r.periods[static_cast<std::size_t>(f.period)].onset_height_edge;
      const double sign = ed.height > z_onset ? 1.0 : (ed.height < z_onset ? -1.0 : 0.0);
      a.eq7[i] = sign * tapered_beam_compliance(ed.s_applied, a.cone_length, mat.youngs_modulus, mat.base_radius) *
                 mu * ed.normal_force;  // eq. (7)
    }
    if (cp.ok())
      a.eq6[i] = tapered_beam_compliance(cp.s_applied, a.cone_length, mat.youngs_modulus, mat.base_radius) *
                 (-cp.friction_force);  // eq. (6), force of the whisker on the peg
    if (cp.ok() && ed.ok()) {
      a.measured[i] = ed.height - cp.height;
      diffs.push_back(std::abs(a.measured[i]));
      // Eqs. (5)-(7) need a cone (taper ratio > 1): without one the predictions are not finite and stay
      // out of the fits, which are then absent rather than NaN.
      if (!f.period_edge && std::isfinite(a.eq6[i]) && std::isfinite(a.eq7[i])) {
        a.used[i] = true;
        x.push_back(a.measured[i]);
        y6.push_back(a.eq6[i]);
        y7.push_back(a.eq7[i]);
      }
    }
  }
  a.fit_eq6 = fit_pairs(x, y6);
  a.fit_eq7 = fit_pairs(x, y7);
  if (!x.empty()) {
    a.measured_min = *std::min_element(x.begin(), x.end());
    a.measured_max = *std::max_element(x.begin(), x.end());
    a.eq7_min = *std::min_element(y7.begin(), y7.end());
    a.eq7_max = *std::max_element(y7.begin(), y7.end());
  }
  if (!diffs.empty()) {
    a.mean_abs_height_difference = mean(diffs);
    a.max_abs_height_difference = *std::max_element(diffs.begin(), diffs.end());
  }
  return a;
}

}  // namespace vibrissa::trial
