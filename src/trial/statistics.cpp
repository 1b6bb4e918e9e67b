#include "vibrissa/trial/statistics.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace vibrissa::trial {

LineFit fit_line(const std::vector<double>& x, const std::vector<double>& y) {
  if (x.size() != y.size()) throw std::invalid_argument("fit_line: x and y differ in length");
  const std::size_t n = x.size();
  if (n < 2) throw std::invalid_argument("fit_line: needs at least 2 points, got " + std::to_string(n));
  const double mx = mean(x), my = mean(y);
  double sxx = 0.0, sxy = 0.0, syy = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    sxx += (x[i] - mx) * (x[i] - mx);
    sxy += (x[i] - mx) * (y[i] - my);
    syy += (y[i] - my) * (y[i] - my);
  }
  if (!(sxx > 0.0)) throw std::invalid_argument("fit_line: x has no variance");
  LineFit f;
  f.count = n;
  f.slope = sxy / sxx;
  f.intercept = my - f.slope * mx;
  double ss_res = 0.0, ss_id = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const double r = y[i] - (f.slope * x[i] + f.intercept);
    ss_res += r * r;
    ss_id += (y[i] - x[i]) * (y[i] - x[i]);
  }
  f.r2 = syy > 0.0 ? 1.0 - ss_res / syy : 1.0;
  f.r2_identity = syy > 0.0 ? 1.0 - ss_id / syy : (ss_id == 0.0 ? 1.0 : -std::numeric_limits<double>::infinity());
  return f;
}

double mean(const std::vector<double>& v) {
  if (v.empty()) return std::numeric_limits<double>::quiet_NaN();
  double s = 0.0;
  for (double x : v) s += x;
  return s / static_cast<double>(v.size());
}

double standard_deviation(const std::vector<double>& v) {
  if (v.size() < 2) return std::numeric_limits<double>::quiet_NaN();
  const double m = mean(v);
  double s = 0.0;
  for (double x : v) s += (x - m) * (x - m);
  return std::sqrt(s / static_cast<double>(v.size() - 1));
}

double quantile(std::vector<double> v, double q) {
  if (v.empty()) return std::numeric_limits<double>::quiet_NaN();
  std::sort(v.begin(), v.end());
  const double pos = q * static_cast<double>(v.size() - 1);
  const auto lo = static_cast<std::size_t>(std::floor(pos));
  const std::size_t hi = std::min(lo + 1, v.size() - 1);
  const double w = pos - static_cast<double>(lo);
  return v[lo] + w * (v[hi] - v[lo]);
}

double median(std::vector<double> v) { return quantile(std::move(v), 0.5); }

std::vector<bool> iqr_outliers(const std::vector<double>& v, double k) {
  const double q1 = quantile(v, 0.25), q3 = quantile(v, 0.75), iqr = q3 - q1;
  std::vector<bool> out(v.size());
  for (std::size_t i = 0; i < v.size(); ++i) out[i] = v[i] < q1 - k * iqr || v[i] > q3 + k * iqr;
  return out;
}

}  // namespace vibrissa::trial
