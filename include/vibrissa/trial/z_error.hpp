#pragma once
// The contact-height error of frictionless edge mode (spec §3.2, §3.4; Figs. 2e, 4b).
//   measured:   z_error = z_edge - z_cp  (heights along the edge; z_cp from contact-point mode)
//   eq. (5):    L = R_base / (R_base - R_tip) S_whisker
//   eq. (6):    z_error = 4 L / (3 E pi R_base^4) · F_friction s^3 / (L - s),  F_friction and s from
//               contact-point mode; F_friction is the force the whisker exerts on the peg along the edge,
//               i.e. minus the edge component of the force on the whisker (friction holds the whisker back
//               from the frictionless point, so z_cp - z_edge has the sign of the force on the whisker).
//   eq. (7):    z_error = sgn(z_edge - z_onset) · 4 L / (3 E pi R_base^4) · mu F_N s^3 / (L - s),  F_N, s and
//               z_edge from edge mode; z_onset = edge-mode height at the first solved frame of the period.
// Fits take the measured z_error as x and the prediction as y; outliers by the 1.5 IQR rule (§3.4) on
// either the measured or the predicted value.
#include <vector>

#include "vibrissa/trial/pipeline.hpp"
#include "vibrissa/trial/statistics.hpp"

namespace vibrissa::trial {

/// Eq. (5): length of the full cone of a linearly tapered whisker [m].
double cone_length(double whisker_length, double base_radius, double taper_ratio);
/// The beam factor 4 L / (3 E pi R_base^4) · s^3 / (L - s) of eqs. (4), (6), (7) [m/N].
double tapered_beam_compliance(double s_applied, double cone_length, double youngs_modulus, double base_radius);

struct ZErrorFit {
  std::optional<LineFit> all, without_outliers;
  std::size_t outliers = 0;
};

struct ZErrorAnalysis {
  std::vector<double> measured, eq6, eq7;  ///< per frame [m], NaN where unavailable
  std::vector<bool> used;                  ///< both modes converged, not a period edge
  double mu_eq7 = std::nan("");            ///< the mu used in eq. (7)
  double cone_length = std::nan("");       ///< L of eq. (5) [m]
  ZErrorFit fit_eq6, fit_eq7;
  double measured_min = std::nan(""), measured_max = std::nan(""), eq7_min = std::nan(""), eq7_max = std::nan("");
  double mean_abs_height_difference = std::nan(""), max_abs_height_difference = std::nan("");  ///< Fig. 2c [m]
};

/// `whisker_length` is the arc length of the rest whisker [m]; `mu` the coefficient for eq. (7).
ZErrorAnalysis analyse_z_error(const PipelineResult& result, double whisker_length, double mu);

}  // namespace vibrissa::trial
