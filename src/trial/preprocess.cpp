#include "vibrissa/trial/preprocess.hpp"

#include <cmath>
#include <stdexcept>

#include "vibrissa/core/checks.hpp"
#include "vibrissa/trial/filter.hpp"
#include "vibrissa/trial/statistics.hpp"

namespace vibrissa::trial {

Preprocessed preprocess(const Trial& input, const PreprocessOptions& opt) {
  validate(input);
  Preprocessed out;
  out.trial = input;
  Trial& t = out.trial;
  const std::size_t n = t.frames();
  out.periods = contact_periods(t.contact);

  std::vector<double> dt;
  for (std::size_t i = 1; i < n; ++i) dt.push_back(t.time[i] - t.time[i - 1]);
  out.sample_rate_hz = dt.empty() ? t.meta.frame_rate : 1.0 / median(dt);

  // Roll (spec §2.3): fit on the raw non-contact frames, then filter the completed signal.
  if (t.has_zeta() && opt.roll_from_theta) {
    out.roll = fit_roll(t.theta, t.zeta, t.contact, t.source);
    t.zeta = extrapolate_roll(*out.roll, t.theta, t.zeta, t.contact);
    out.zeta_source = "tracked, contact frames from the theta fit";
  } else if (t.has_zeta()) {
    out.zeta_source = "tracked";
  } else {
    t.zeta.assign(n, 0.0);
    out.zeta_source = "not tracked: 0";
  }

  if (opt.filter && n >= 2 && !(opt.cutoff_hz > 0.0 && opt.cutoff_hz < 0.5 * out.sample_rate_hz))
    throw std::invalid_argument(located_message(
        t.source, 0, "time",
        "the median time step " + format_value(1.0 / out.sample_rate_hz) + " s gives a sample rate of " +
            format_value(out.sample_rate_hz) + " Hz; the filter cutoff " + format_value(opt.cutoff_hz) +
            " Hz must lie in (0, sample rate / 2) (check the time unit, --cutoff, or use --no-filter)"));
  if (opt.filter && n >= 2) {
    const Butterworth f = design_butterworth_lowpass(opt.cutoff_hz, out.sample_rate_hz, opt.filter_order);
    t.theta = filtfilt(f, t.theta);
    t.phi = filtfilt(f, t.phi);
    t.zeta = filtfilt(f, t.zeta);
    for (int a = 0; a < 3; ++a) {
      std::vector<double> c(n);
      for (std::size_t i = 0; i < n; ++i) c[i] = t.base_W[i][a];
      c = filtfilt(f, c);
      for (std::size_t i = 0; i < n; ++i) t.base_W[i][a] = c[i];
    }
    // The contact point exists only during contact: filter each period on its own.
    if (t.has_contact_point())
      for (const auto& p : out.periods)
        for (int a = 0; a < 3; ++a) {
          std::vector<double> c;
          for (std::size_t i = p.first; i <= p.last; ++i) c.push_back(t.contact_W[i][a]);
          c = filtfilt(f, c);
          for (std::size_t i = p.first; i <= p.last; ++i) t.contact_W[i][a] = c[i - p.first];
        }
  }

  for (const auto& p : out.periods) {
    if (!opt.rest_shape_per_contact) {
      out.rest_shapes.push_back(t.meta.rest_shape);
      continue;
    }
    // §2.3: the shape at the very end of contact, when the whisker is least deflected.
    const std::vector<Eigen::Vector3d>* shape = nullptr;
    for (std::size_t i = p.last + 1; i-- > p.first;)
      if (t.has_shapes() && t.shape_W[i].size() >= 3) {
        shape = &t.shape_W[i];
        break;
      }
    if (!shape)
      throw std::invalid_argument(located_message(t.source, p.last + 1, "shape",
                                                  "a rest shape per contact period was requested but the contact "
                                                  "period ending here has no tracked shape (>= 3 nodes)"));
    out.rest_shapes.push_back(*shape);
  }
  return out;
}

}  // namespace vibrissa::trial
