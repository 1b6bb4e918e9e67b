#include "vibrissa/trial/roll_regression.hpp"

#include <stdexcept>
#include <string>

namespace vibrissa::trial {

RollFit fit_roll(const std::vector<double>& theta, const std::vector<double>& zeta,
                 const std::vector<std::uint8_t>& contact, const std::string& source) {
  std::vector<double> x, y;
  for (std::size_t i = 0; i < theta.size(); ++i)
    if (!contact[i]) {
      x.push_back(theta[i]);
      y.push_back(zeta[i]);
    }
  const std::string where = source.empty() ? std::string("trial") : source;
  if (x.size() < 2)
    throw std::invalid_argument(where + ": column 'zeta': the roll regression (spec §2.3) needs at least 2 "
                                        "non-contact frames, found " + std::to_string(x.size()));
  LineFit f;
  try {
    f = fit_line(x, y);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(where + ": column 'theta': roll regression over non-contact frames: " + e.what());
  }
  return {f.slope, f.intercept, f.r2, f.count};
}

std::vector<double> extrapolate_roll(const RollFit& fit, const std::vector<double>& theta,
                                     const std::vector<double>& zeta, const std::vector<std::uint8_t>& contact) {
  std::vector<double> out = zeta;
  for (std::size_t i = 0; i < theta.size(); ++i)
    if (contact[i]) out[i] = fit.slope * theta[i] + fit.intercept;
  return out;
}

}  // namespace vibrissa::trial
