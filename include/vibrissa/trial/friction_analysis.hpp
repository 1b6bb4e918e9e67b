#pragma once
// Friction coefficient from contact-point mode (spec §2.4, §3.3, Fig. 3c-e): per frame
// mu = |F_friction| / F_N with F_friction the force along the edge (F_z world for a vertical peg) and
// F_N = |F normal to the edge|. Frames with F_N < 0.1 mN are outliers; the first and last two frames of each
// contact period are left out (§2.4).
#include <string>
#include <vector>

#include "vibrissa/trial/pipeline.hpp"

namespace vibrissa::trial {

struct FrictionAnalysisOptions {
  double outlier_normal_force = 1e-4;  ///< [N] (0.1 mN, §3.3)
  double histogram_max = 3.0;          ///< Fig. 3c plots mu > 3 at 3
  int histogram_bins = 30;
  int normal_force_bins = 12;          ///< Fig. 3d: mean ± sd of mu per normal-force bin
  /// A frame slips when its contact point moves along the edge faster than this [m/s] (central difference
  /// of the contact height within its period); a sticking frame's |F_edge| / F_N is only a lower bound on mu.
  double slip_speed = 2e-3;
  /// Below this fraction of slipping frames the median is reported as a lower bound, with a warning.
  double min_slip_fraction = 0.5;
};

struct FrictionAnalysis {
  std::vector<double> mu;        ///< per frame, NaN where not computed
  std::vector<bool> outlier;     ///< per frame: F_N below the threshold
  std::vector<bool> used;        ///< per frame: enters the median (computed, not an outlier, not a period edge)
  double median = std::nan(""), mean = std::nan(""), sd = std::nan("");
  double min = std::nan(""), max = std::nan("");
  std::size_t frames_used = 0, outliers = 0;
  /// Per frame: the contact slides along the edge (|d height / dt| > slip_speed); false where not computed.
  std::vector<bool> slipping;
  std::size_t frames_slipping = 0;     ///< of the used frames
  double slip_fraction = std::nan(""); ///< frames_slipping / frames_used
  double median_slipping = std::nan("");  ///< median mu over the used frames that slip
  /// Whether `median` estimates mu (most used frames slip) or only bounds it from below (most stick: there
  /// |F_edge| / F_N <= mu). Empty when nothing was computed.
  std::string kind;
  std::vector<std::string> warnings;  ///< why a number is NaN or only a bound, in words
  std::vector<double> histogram_edges;        ///< size bins + 1
  std::vector<std::size_t> histogram_counts;  ///< of the used values (values above max in the last bin)
  std::vector<double> fn_bin_center, fn_bin_mean, fn_bin_sd;  ///< Fig. 3d, [N] and dimensionless
  std::vector<std::size_t> fn_bin_count;
};

FrictionAnalysis analyse_friction(const PipelineResult& result, Mode mode = Mode::contact_point,
                                  const FrictionAnalysisOptions& options = {});

}  // namespace vibrissa::trial
