#pragma once
// All of the paper's trial analyses in one call (spec §2.3-§3.4): friction coefficient (Fig. 3c-e),
// force / moment directions (Fig. 3b, §3.3), z_error against eqs. (6) and (7) (Figs. 2e, 4b), the kinematic
// prediction of the contact height (Fig. 2f) and the shape error (Fig. 2b).
#include <optional>

#include "vibrissa/trial/force_directions.hpp"
#include "vibrissa/trial/friction_analysis.hpp"
#include "vibrissa/trial/z_error.hpp"

namespace vibrissa::trial {

struct AnalysisOptions {
  FrictionAnalysisOptions friction;
  std::optional<double> mu_eq7;  ///< mu for eq. (7); default: the median mu of contact-point mode, else the
                                 ///< pipeline's frictional mu, else 0.48 (spec §3.3)
};

struct KinematicPrediction {
  std::vector<double> measured, predicted;  ///< per frame [m] (tracked contact height; Fig. 2f projection)
  std::optional<LineFit> fit;               ///< x = measured, y = predicted
};

struct ShapeErrorSummary {
  double contact_point_mean = std::nan(""), edge_mean = std::nan(""), frictional_mean = std::nan("");  ///< [m]
};

struct TrialAnalysis {
  std::optional<FrictionAnalysis> friction;             ///< contact-point mode
  std::optional<FrictionAnalysis> friction_frictional;  ///< frictional edge mode (checks the cone)
  ForceDirectionAnalysis directions;
  std::optional<ZErrorAnalysis> z_error;
  KinematicPrediction kinematic;
  ShapeErrorSummary shape_error;
  double whisker_length = 0.0;  ///< rest arc length used for eq. (5) [m]
};

TrialAnalysis analyse_trial(const PipelineResult& result, const AnalysisOptions& options = {});

}  // namespace vibrissa::trial
