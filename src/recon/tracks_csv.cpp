// Plain CSV tracks and the format dispatch (docs/reconstruction.md, "Track files").
#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <stdexcept>

#include "../io/guarded_read.hpp"
#include "text_cells.hpp"
#include "vibrissa/recon/tracks.hpp"

namespace vibrissa::recon {

const TrackFrame* Tracks2D::find(std::int64_t frame) const {
  auto it = std::lower_bound(frames.begin(), frames.end(), frame,
                             [](const TrackFrame& f, std::int64_t v) { return f.frame < v; });
  return it != frames.end() && it->frame == frame ? &*it : nullptr;
}

Tracks2D read_points_csv(const std::string& path) {
  std::ifstream in = open_input(path, "track file");
  std::string line;
  std::size_t line_no = 0;
  std::vector<std::string> header;
  while (header.empty() && std::getline(in, line)) {
    ++line_no;
    const std::string s = trim(line);
    if (!s.empty() && s[0] != '#') header = split_cells(s);
  }
  std::map<std::string, std::size_t> col;
  for (std::size_t c = 0; c < header.size(); ++c) {
    if (header[c] != "frame" && header[c] != "point" && header[c] != "x_px" && header[c] != "y_px" &&
        header[c] != "likelihood")
      throw std::invalid_argument(cell_message(path, line_no, header[c], "unknown column (expected frame, point, "
                                                                          "x_px, y_px and optionally likelihood)"));
    col[header[c]] = c;
  }
  for (const char* name : {"frame", "point", "x_px", "y_px"})
    if (!col.count(name)) throw std::invalid_argument(cell_message(path, line_no, name, "required column is missing"));
  struct Row {
    std::int64_t frame, point;
    Eigen::Vector2d p;
    double likelihood;
    std::size_t line;
  };
  std::vector<Row> rows;
  while (std::getline(in, line)) {
    ++line_no;
    const std::string s = trim(line);
    if (s.empty() || s[0] == '#') continue;
    const auto cells = split_cells(s);
    if (cells.size() != header.size())
      throw std::invalid_argument(cell_message(path, line_no, "", "has " + std::to_string(cells.size()) +
                                                                      " cells, the header has " +
                                                                      std::to_string(header.size())));
    auto get = [&](const char* name) { return parse_cell(cells[col[name]], path, line_no, name); };
    const std::int64_t frame = parse_index(cells[col["frame"]], path, line_no, "frame");
    const std::int64_t point = parse_index(cells[col["point"]], path, line_no, "point");
    const Eigen::Vector2d p(get("x_px"), get("y_px"));
    const double l = col.count("likelihood") ? get("likelihood") : 1.0;
    if (std::isfinite(l) && (l < 0.0 || l > 1.0))
      throw std::invalid_argument(cell_message(path, line_no, "likelihood", "must lie in [0, 1]"));
    if (!p.allFinite() || !std::isfinite(l)) continue;  // not tracked
    rows.push_back({frame, point, p, l, line_no});
  }
  std::stable_sort(rows.begin(), rows.end(),
                   [](const Row& a, const Row& b) { return a.frame != b.frame ? a.frame < b.frame : a.point < b.point; });
  Tracks2D t;
  t.source = path;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const Row& r = rows[i];
    if (i > 0 && rows[i - 1].frame == r.frame && rows[i - 1].point == r.point)
      throw std::invalid_argument(cell_message(path, r.line, "point", "frame " + std::to_string(r.frame) + ", point " +
                                                                          std::to_string(r.point) + " appears twice"));
    if (t.frames.empty() || t.frames.back().frame != r.frame) t.frames.push_back({r.frame, {}, {}});
    t.frames.back().points_px.push_back(r.p);
    t.frames.back().likelihood.push_back(r.likelihood);
  }
  return t;
}

Tracks2D read_tracks(const std::string& path, const TrackSelection& sel) {
  auto ends_with = [&](const std::string& ext) {
    if (path.size() < ext.size()) return false;
    std::string tail = path.substr(path.size() - ext.size());
    std::transform(tail.begin(), tail.end(), tail.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return tail == ext;
  };
  if (ends_with(".whiskers")) {
    if (sel.measurements.empty())
      throw std::invalid_argument(path + ": a .whiskers file needs its .measurements file for whisker identities");
    return janelia_tracks(path, sel.measurements, sel.identity);
  }
  if (ends_with(".h5") || ends_with(".hdf5"))  // libhdf5 meets the file in a child process first
    return io::guarded_read(path, "libhdf5", [&] { return read_dlc_h5(path, sel.bodyparts, sel.individual); });
  if (ends_with(".csv")) {
    std::ifstream in = open_input(path, "track file");
    std::string first;
    std::getline(in, first);
    const auto cells = split_cells(trim(first));
    if (!cells.empty() && cells[0] == "scorer") return read_dlc_csv(path, sel.bodyparts, sel.individual);
    return read_points_csv(path);
  }
  throw std::invalid_argument(path + ": unknown track file type (expected .csv, .h5/.hdf5 or .whiskers)");
}

}  // namespace vibrissa::recon
