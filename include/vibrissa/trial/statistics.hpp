#pragma once
// Statistics used by the paper's analyses (spec §2.3, §3.2-§3.4): least-squares line with r^2, r^2 about
// the identity line, median, mean / sd, quartiles and the 1.5 IQR outlier rule.
#include <cstddef>
#include <vector>

namespace vibrissa::trial {

/// y ≈ slope x + intercept by least squares; r2 = 1 - SS_res / SS_tot of that fit (= squared Pearson r).
/// r2_identity = 1 - sum (y - x)^2 / sum (y - mean y)^2 (the identity line as the model; may be negative).
struct LineFit {
  double slope = 0.0, intercept = 0.0, r2 = 0.0, r2_identity = 0.0;
  std::size_t count = 0;
};
/// Throws std::invalid_argument for different sizes, fewer than 2 points or zero variance in x.
LineFit fit_line(const std::vector<double>& x, const std::vector<double>& y);

double mean(const std::vector<double>& v);            ///< NaN for an empty vector
double standard_deviation(const std::vector<double>& v);  ///< sample sd (n - 1); NaN below 2 values
double median(std::vector<double> v);                 ///< NaN for an empty vector
/// Quantile with linear interpolation between order statistics (type 7, as numpy's default).
double quantile(std::vector<double> v, double q);

/// Tukey's rule (spec §3.4): true where v < Q1 - 1.5 IQR or v > Q3 + 1.5 IQR.
std::vector<bool> iqr_outliers(const std::vector<double>& v, double k = 1.5);

}  // namespace vibrissa::trial
