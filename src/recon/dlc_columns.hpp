#pragma once
// The column selection shared by the DeepLabCut CSV and HDF5 readers (private to src/recon).
#include <array>
#include <limits>
#include <string>
#include <vector>

#include "vibrissa/recon/tracks.hpp"

namespace vibrissa::recon {

inline constexpr std::size_t npos_column = std::numeric_limits<std::size_t>::max();

struct DlcColumn {
  std::string individual, bodypart, coord;
};
struct DlcColumns {
  std::vector<std::string> bodyparts;               ///< chosen keypoints, base to tip
  std::vector<std::array<std::size_t, 3>> columns;  ///< x, y, likelihood value index (npos_column: none)
};
/// Chooses the columns of `individual` (or the only one) and `bodyparts` (or all, in file order).
DlcColumns select_dlc_columns(const std::vector<DlcColumn>& columns, const std::vector<std::string>& bodyparts,
                              const std::string& individual, const std::string& path);
/// Appends one frame of values (in column order); points with NaN or no likelihood are left out; frames
/// must increase.
void append_dlc_frame(Tracks2D& tracks, std::int64_t frame, const std::vector<double>& values,
                      const DlcColumns& selection, std::size_t line);

}  // namespace vibrissa::recon
