#pragma once
// 2D whisker tracks of one camera view (docs/reconstruction.md, "Track files"): per video frame, the points
// of one whisker in pixels, ordered from the base (follicle) toward the tip, each with a likelihood in [0, 1]
// (1 when the tracker gives none). Readers for a plain CSV, DeepLabCut CSV/HDF5 and the Janelia Whisker
// Tracker's .whiskers (binary whiskbin1 and text whisker1) + .measurements (measv3); every error names the
// file, the frame (or line) and the field, and is a std::invalid_argument.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace vibrissa::recon {

struct TrackFrame {
  std::int64_t frame = 0;                     ///< video frame index (0-based)
  std::vector<Eigen::Vector2d> points_px;     ///< base first [px]
  std::vector<double> likelihood;             ///< one per point, in [0, 1]
};

struct Tracks2D {
  std::string source;               ///< file name, for messages
  std::vector<TrackFrame> frames;   ///< strictly increasing frame indices; untracked frames are absent
  /// The frame, or nullptr when the view has no track there.
  [[nodiscard]] const TrackFrame* find(std::int64_t frame) const;
};

/// Plain CSV, one row per point: `frame,point,x_px,y_px[,likelihood]` (header required; `point` orders the
/// points from the base; empty cells or nan mark a point as not tracked).
Tracks2D read_points_csv(const std::string& path);

/// DeepLabCut CSV (header rows scorer / [individuals /] bodyparts / coords with x, y, likelihood per
/// bodypart). `bodyparts` lists the keypoints along the whisker from base to tip (empty: every bodypart in
/// file order); `individual` picks one animal of a multi-animal file (empty: the file must have one).
Tracks2D read_dlc_csv(const std::string& path, const std::vector<std::string>& bodyparts = {},
                      const std::string& individual = {});
/// DeepLabCut HDF5 (pandas/PyTables table under key "df_with_missing"), same selection as the CSV.
Tracks2D read_dlc_h5(const std::string& path, const std::vector<std::string>& bodyparts = {},
                     const std::string& individual = {});

/// One traced segment of a .whiskers file.
struct WhiskerSegment {
  std::int32_t frame = 0, id = 0;
  std::vector<float> x, y, thick, score;
};
/// Janelia .whiskers, binary (whiskbin1) or text (whisker1), detected from the header.
std::vector<WhiskerSegment> read_whiskers(const std::string& path);

/// One row of a Janelia .measurements file (measv3).
struct MeasurementRow {
  std::int32_t frame = 0, segment = 0;  ///< fid, wid: the segment of the .whiskers file
  std::int32_t identity = -1;           ///< state: whisker label (-1: not a whisker)
  std::int32_t follicle_x_column = -1, follicle_y_column = -1;
  std::vector<double> values;           ///< the measurement columns (length, angle, ..., follicle x, y)
};
std::vector<MeasurementRow> read_measurements(const std::string& path);

/// The whisker labelled `identity` in the measurements, as tracks: the segment oriented so that its first
/// point is the end nearer the measured follicle; likelihood 1. Frames where no segment carries the label are
/// absent; a frame where several do is an error naming the frame.
Tracks2D janelia_tracks(const std::string& whiskers_path, const std::string& measurements_path, int identity);

/// Dispatch on the extension: .whiskers (with `measurements`), .csv (DeepLabCut if its first cell is
/// "scorer", else plain), .h5 (DeepLabCut).
struct TrackSelection {
  std::string measurements;               ///< Janelia .measurements beside a .whiskers file
  int identity = 0;                       ///< Janelia whisker label
  std::vector<std::string> bodyparts;     ///< DeepLabCut keypoints, base to tip
  std::string individual;                 ///< DeepLabCut multi-animal individual
};
Tracks2D read_tracks(const std::string& path, const TrackSelection& selection = {});

}  // namespace vibrissa::recon
