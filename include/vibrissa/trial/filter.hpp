#pragma once
// Zero-phase low-pass Butterworth filtering of trial signals (spec §2.3: 85 Hz).
//
// Design: an analog Butterworth low-pass of order `order` (2 or 4), mapped to a digital filter by the
// bilinear transform with the cutoff prewarped (K = tan(pi fc / fs)), so that the single-pass gain at fc is
// exactly 1/sqrt(2). It is realised as a cascade of second-order sections (biquads), each the bilinear image
// of s^2 + s/Q_k + 1 with Q_k = 1 / (2 sin((2k+1) pi / (2 order))).
// filtfilt runs the cascade forward, then backward: the phase cancels (zero phase) and the magnitude is
// squared, so the cascade's gain at fc is exactly 1/2 (-6.02 dB), not -3 dB. Edges are padded by odd
// reflection (2 x[0] - x[pad..1]) and the sections start in their steady state for the first padded value,
// which removes start-up transients.
#include <vector>

namespace vibrissa::trial {

struct Biquad {
  double b0, b1, b2, a1, a2;  ///< y[n] = b0 x[n] + b1 x[n-1] + b2 x[n-2] - a1 y[n-1] - a2 y[n-2]
};

struct Butterworth {
  std::vector<Biquad> sections;
  double cutoff_hz = 0.0, sample_rate_hz = 0.0;
  int order = 0;
};

/// Throws std::invalid_argument unless order is 2 or 4 and 0 < cutoff < sample_rate / 2.
Butterworth design_butterworth_lowpass(double cutoff_hz, double sample_rate_hz, int order = 2);

/// Single-pass magnitude |H(e^{i 2 pi f / fs})| of the cascade.
double magnitude(const Butterworth& filter, double frequency_hz);

/// One causal pass (zero initial state).
std::vector<double> lfilter(const Butterworth& filter, const std::vector<double>& x);

/// Zero-phase forward-backward filtering with odd-reflection padding of
/// min(max(3 (2 sections + 1), 4 fs / fc), n - 1) samples. Signals of fewer than 2 samples are returned unchanged.
std::vector<double> filtfilt(const Butterworth& filter, const std::vector<double>& x);

}  // namespace vibrissa::trial
