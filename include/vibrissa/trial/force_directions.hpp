#pragma once
// Directions of the transverse force and bending moment at the base (spec §3.3, Fig. 3b): per whisk
// (contact period) the range of F_D and M_D, averaged over whisks, for each mode; and the mean offset
// contact-point mode minus edge mode. Angles are unwrapped along each period before taking ranges;
// offsets are wrapped to (-180°, 180°]. Period-edge frames (§2.4) are left out.
#include <vector>

#include "vibrissa/trial/pipeline.hpp"

namespace vibrissa::trial {

struct DirectionRanges {
  std::vector<double> fd_range_deg, md_range_deg;  ///< per whisk with >= 2 usable frames
  double mean_fd_range_deg = std::nan(""), mean_md_range_deg = std::nan("");
};

struct ForceDirectionAnalysis {
  DirectionRanges contact_point, edge, frictional;
  double mean_fd_offset_deg = std::nan("");  ///< mean of F_D(contact point) - F_D(edge)
  double mean_md_offset_deg = std::nan("");
};

ForceDirectionAnalysis analyse_force_directions(const PipelineResult& result);

/// a - b wrapped to (-pi, pi].
double wrap_angle(double radians);

}  // namespace vibrissa::trial
