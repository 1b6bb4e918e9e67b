#include "vibrissa/trial/filter.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>
#include <sstream>
#include <stdexcept>

namespace vibrissa::trial {

Butterworth design_butterworth_lowpass(double cutoff_hz, double sample_rate_hz, int order) {
  if (order != 2 && order != 4) {
    std::ostringstream os;
    os << "Butterworth order must be 2 or 4, got " << order;
    throw std::invalid_argument(os.str());
  }
  if (!(std::isfinite(sample_rate_hz) && sample_rate_hz > 0.0) || !(cutoff_hz > 0.0 && cutoff_hz < 0.5 * sample_rate_hz)) {
    std::ostringstream os;
    os << "filter cutoff must lie in (0, sample_rate / 2): cutoff " << cutoff_hz << " Hz, sample rate "
       << sample_rate_hz << " Hz";
    throw std::invalid_argument(os.str());
  }
  Butterworth f;
  f.cutoff_hz = cutoff_hz;
  f.sample_rate_hz = sample_rate_hz;
  f.order = order;
  // Prewarped analog cutoff (normalised): s = (1 - z^-1) / (1 + z^-1) / K maps Omega = 1 to fc.
  const double K = std::tan(std::numbers::pi * cutoff_hz / sample_rate_hz);
  const int pairs = order / 2;
  for (int k = 0; k < pairs; ++k) {
    const double q = 1.0 / (2.0 * std::sin((2.0 * k + 1.0) * std::numbers::pi / (2.0 * order)));
    // H(s) = 1 / (s^2 + s/q + 1), s = (1 - z^-1) / (K (1 + z^-1)).
    const double K2 = K * K, norm = 1.0 + K / q + K2;
    Biquad b;
    b.b0 = K2 / norm;
    b.b1 = 2.0 * b.b0;
    b.b2 = b.b0;
    b.a1 = 2.0 * (K2 - 1.0) / norm;
    b.a2 = (1.0 - K / q + K2) / norm;
    f.sections.push_back(b);
  }
  return f;
}

double magnitude(const Butterworth& f, double frequency_hz) {
  const std::complex<double> z1 = std::polar(1.0, -2.0 * std::numbers::pi * frequency_hz / f.sample_rate_hz);
  const std::complex<double> z2 = z1 * z1;
  std::complex<double> h = 1.0;
  for (const auto& s : f.sections) h *= (s.b0 + s.b1 * z1 + s.b2 * z2) / (1.0 + s.a1 * z1 + s.a2 * z2);
  return std::abs(h);
}

namespace {

/// Runs the cascade in place (direct form II transposed). If `steady` is finite, each section starts in
/// the steady state of a constant input equal to `steady` (DC gain of each section is 1).
void run(const Butterworth& f, std::vector<double>& x, double steady) {
  for (const auto& s : f.sections) {
    double z1 = 0.0, z2 = 0.0;
    if (std::isfinite(steady)) {
      z2 = (s.b2 - s.a2) * steady;
      z1 = (s.b1 - s.a1) * steady + z2;
    }
    for (double& v : x) {
      const double in = v;
      const double out = s.b0 * in + z1;
      z1 = s.b1 * in - s.a1 * out + z2;
      z2 = s.b2 * in - s.a2 * out;
      v = out;
    }
  }
}

}  // namespace

std::vector<double> lfilter(const Butterworth& f, const std::vector<double>& x) {
  std::vector<double> y = x;
  run(f, y, std::nan(""));
  return y;
}

std::vector<double> filtfilt(const Butterworth& f, const std::vector<double>& x) {
  const std::size_t n = x.size();
  if (n < 2) return x;
  // At least 3 (2 sections + 1) samples (as common practice) and four cutoff periods, so that start-up
  // transients of the padded signal have decayed before the data begin.
  const auto periods = static_cast<std::size_t>(std::ceil(4.0 * f.sample_rate_hz / f.cutoff_hz));
  const std::size_t pad = std::min(std::max<std::size_t>(3 * (2 * f.sections.size() + 1), periods), n - 1);
  std::vector<double> ext;
  ext.reserve(n + 2 * pad);
  for (std::size_t i = pad; i >= 1; --i) ext.push_back(2.0 * x.front() - x[i]);  // odd reflection
  ext.insert(ext.end(), x.begin(), x.end());
  for (std::size_t i = 1; i <= pad; ++i) ext.push_back(2.0 * x.back() - x[n - 1 - i]);
  run(f, ext, ext.front());
  std::reverse(ext.begin(), ext.end());
  run(f, ext, ext.front());
  std::reverse(ext.begin(), ext.end());
  return std::vector<double>(ext.begin() + static_cast<std::ptrdiff_t>(pad),
                             ext.begin() + static_cast<std::ptrdiff_t>(pad + n));
}

}  // namespace vibrissa::trial
