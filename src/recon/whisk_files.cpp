// Janelia Whisker Tracker files (docs/reconstruction.md, "Track files"), implemented from the layout the
// tracker's public source writes (github.com/nclack/whisk, whisker_io_whiskbin1.c, whisker_io_whisker1.c,
// measurements_io_v3.c): native little-endian int32/float32/float64, no padding.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <map>
#include <stdexcept>

#include "text_cells.hpp"
#include "vibrissa/recon/tracks.hpp"

namespace vibrissa::recon {

namespace {

std::vector<char> read_bytes(const std::string& path) {
  std::ifstream in = open_input(path, "track file", std::ios::in | std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// Sequential reader of little-endian values; errors name the file, the record and the field.
struct ByteReader {
  const std::vector<char>& bytes;
  const std::string& path;
  std::size_t at = 0;
  std::size_t end;
  template <class T>
  T get(const std::string& record, const char* field) {
    if (at + sizeof(T) > end)
      throw std::invalid_argument(path + ": " + record + ", field '" + field + "': file ends early (truncated)");
    T v;
    std::memcpy(&v, bytes.data() + at, sizeof(T));
    at += sizeof(T);
    return v;
  }
};

constexpr char whiskbin1_magic[12] = {'b', 'w', 'h', 'i', 's', 'k', 'b', 'i', 'n', '1', 0, 0};
constexpr char measv3_magic[8] = {'m', 'e', 'a', 's', 'v', '3', 0, 0};

std::vector<WhiskerSegment> read_whiskbin1(const std::vector<char>& bytes, const std::string& path) {
  if (bytes.size() < sizeof(whiskbin1_magic) + 4) throw std::invalid_argument(path + ": whiskbin1 file is truncated");
  ByteReader r{bytes, path, bytes.size() - 4, bytes.size()};
  const std::int32_t count = r.get<std::int32_t>("footer", "segment count");
  if (count < 0) throw std::invalid_argument(path + ": footer, field 'segment count': negative");
  r.at = sizeof(whiskbin1_magic);
  r.end = bytes.size() - 4;
  std::vector<WhiskerSegment> out;
  for (std::int32_t i = 0; i < count; ++i) {
    const std::string record = "segment " + std::to_string(i + 1);
    WhiskerSegment s;
    s.id = r.get<std::int32_t>(record, "id");
    s.frame = r.get<std::int32_t>(record, "time");
    const std::int32_t len = r.get<std::int32_t>(record, "len");
    const std::string where = record + " (frame " + std::to_string(s.frame) + ")";
    if (len <= 0 || std::size_t(len) * 16 > r.end - r.at)
      throw std::invalid_argument(path + ": " + where + ", field 'len': " + std::to_string(len) +
                                  " points do not fit in the file");
    for (auto* v : {&s.x, &s.y, &s.thick, &s.score}) {
      v->resize(std::size_t(len));
      for (auto& f : *v) f = r.get<float>(where, "points");
    }
    out.push_back(std::move(s));
  }
  if (r.at != r.end)
    throw std::invalid_argument(path + ": footer, field 'segment count': " + std::to_string(count) +
                                " segments leave " + std::to_string(r.end - r.at) + " bytes unread");
  return out;
}

std::vector<WhiskerSegment> read_whisker1(const std::string& path) {
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  std::vector<WhiskerSegment> out;
  std::size_t line_no = 1;
  while (std::getline(in, line)) {
    ++line_no;
    const std::string s = trim(line);
    if (s.empty()) continue;
    const auto cells = split_cells(s);
    if (cells.size() < 4)
      throw std::invalid_argument(cell_message(path, line_no, "n", "expected frame,id,time,n then the points"));
    WhiskerSegment w;
    w.frame = std::int32_t(parse_index(cells[0], path, line_no, "frame"));
    w.id = std::int32_t(parse_index(cells[1], path, line_no, "id"));
    const std::int64_t n = parse_index(cells[3], path, line_no, "n");
    if (cells.size() != std::size_t(4 + 4 * n))
      throw std::invalid_argument(cell_message(path, line_no, "n", "frame " + std::to_string(w.frame) + ": n = " +
                                                                       std::to_string(n) + " needs " +
                                                                       std::to_string(4 + 4 * n) + " cells, got " +
                                                                       std::to_string(cells.size())));
    for (std::int64_t k = 0; k < n; ++k) {
      const std::size_t c = std::size_t(4 + 4 * k);
      static const char* fields[4] = {"x", "y", "thick", "score"};
      float v[4];
      for (int f = 0; f < 4; ++f) {
        const double d = parse_cell(cells[c + std::size_t(f)], path, line_no, fields[f]);
        if (!std::isfinite(d))
          throw std::invalid_argument(cell_message(path, line_no, fields[f], "frame " + std::to_string(w.frame) +
                                                                                 ": value is missing"));
        v[f] = float(d);
      }
      w.x.push_back(v[0]);
      w.y.push_back(v[1]);
      w.thick.push_back(v[2]);
      w.score.push_back(v[3]);
    }
    out.push_back(std::move(w));
  }
  return out;
}

}  // namespace

std::vector<WhiskerSegment> read_whiskers(const std::string& path) {
  const std::vector<char> bytes = read_bytes(path);
  if (bytes.size() >= sizeof(whiskbin1_magic) && std::memcmp(bytes.data(), whiskbin1_magic, sizeof(whiskbin1_magic)) == 0)
    return read_whiskbin1(bytes, path);
  if (bytes.size() >= 8 && std::memcmp(bytes.data(), "whisker1", 8) == 0) return read_whisker1(path);
  throw std::invalid_argument(path + ": header: not a .whiskers file (expected whiskbin1 or whisker1)");
}

std::vector<MeasurementRow> read_measurements(const std::string& path) {
  const std::vector<char> bytes = read_bytes(path);
  if (bytes.size() < sizeof(measv3_magic) || std::memcmp(bytes.data(), measv3_magic, sizeof(measv3_magic)) != 0)
    throw std::invalid_argument(path + ": header: not a measv3 .measurements file (older versions: re-save with "
                                       "the current tracker)");
  ByteReader r{bytes, path, sizeof(measv3_magic), bytes.size()};
  const std::int32_t rows = r.get<std::int32_t>("header", "n_rows");
  const std::int32_t cols = r.get<std::int32_t>("header", "n_measures");
  if (rows < 0 || cols < 0) throw std::invalid_argument(path + ": header, field 'n_rows': negative size");
  // Checked before allocating: a row is ten int32, one char, then n_measures float64 values and velocities.
  const std::size_t row_bytes = 10 * sizeof(std::int32_t) + 1 + 2 * sizeof(double) * std::size_t(cols);
  if (std::size_t(rows) > (r.end - r.at) / row_bytes)
    throw std::invalid_argument(path + ": header, field 'n_rows': " + std::to_string(rows) + " rows of " +
                                std::to_string(cols) + " measures do not fit in the file (truncated?)");
  std::vector<MeasurementRow> out;
  out.resize(std::size_t(rows));
  for (std::int32_t i = rows - 1; i >= 0; --i) {  // written last row first
    const std::string record = "row " + std::to_string(i + 1);
    MeasurementRow& m = out[std::size_t(i)];
    r.get<std::int32_t>(record, "row");
    m.frame = r.get<std::int32_t>(record, "fid");
    m.segment = r.get<std::int32_t>(record, "wid");
    m.identity = r.get<std::int32_t>(record, "state");
    r.get<std::int32_t>(record, "face_x");
    r.get<std::int32_t>(record, "face_y");
    m.follicle_x_column = r.get<std::int32_t>(record, "col_follicle_x");
    m.follicle_y_column = r.get<std::int32_t>(record, "col_follicle_y");
    r.get<std::int32_t>(record, "valid_velocity");
    const std::int32_t n = r.get<std::int32_t>(record, "n");
    r.get<char>(record, "face_axis");
    if (n != cols)
      throw std::invalid_argument(path + ": " + record + " (frame " + std::to_string(m.frame) + "), field 'n': " +
                                  std::to_string(n) + " measures, the header says " + std::to_string(cols));
    m.values.resize(std::size_t(cols));
    for (auto& v : m.values) v = r.get<double>(record, "data");
    for (std::int32_t k = 0; k < cols; ++k) r.get<double>(record, "velocity");
  }
  if (r.at != r.end) throw std::invalid_argument(path + ": trailing bytes after " + std::to_string(rows) + " rows");
  return out;
}

Tracks2D janelia_tracks(const std::string& whiskers_path, const std::string& measurements_path, int identity) {
  const auto segments = read_whiskers(whiskers_path);
  const auto rows = read_measurements(measurements_path);
  std::map<std::pair<std::int32_t, std::int32_t>, const WhiskerSegment*> by_key;
  for (const auto& s : segments) by_key[{s.frame, s.id}] = &s;
  std::map<std::int32_t, const MeasurementRow*> chosen;
  for (const auto& m : rows) {
    if (m.identity != identity) continue;
    const std::string where = measurements_path + ": frame " + std::to_string(m.frame);
    if (chosen.count(m.frame))
      throw std::invalid_argument(where + ", field 'state': two segments carry whisker identity " +
                                  std::to_string(identity));
    chosen[m.frame] = &m;
  }
  Tracks2D t;
  t.source = whiskers_path;
  for (const auto& [frame, m] : chosen) {
    const std::string where = measurements_path + ": frame " + std::to_string(frame);
    auto it = by_key.find({frame, m->segment});
    if (it == by_key.end())
      throw std::invalid_argument(where + ", field 'wid': segment " + std::to_string(m->segment) + " is not in " +
                                  whiskers_path);
    const WhiskerSegment& s = *it->second;
    TrackFrame f;
    f.frame = frame;
    for (std::size_t k = 0; k < s.x.size(); ++k) f.points_px.emplace_back(s.x[k], s.y[k]);
    const auto cx = std::size_t(m->follicle_x_column), cy = std::size_t(m->follicle_y_column);
    if (m->follicle_x_column >= 0 && m->follicle_y_column >= 0 && cx < m->values.size() && cy < m->values.size()) {
      const Eigen::Vector2d follicle(m->values[cx], m->values[cy]);
      if ((f.points_px.back() - follicle).norm() < (f.points_px.front() - follicle).norm())
        std::reverse(f.points_px.begin(), f.points_px.end());
    }
    f.likelihood.assign(f.points_px.size(), 1.0);
    t.frames.push_back(std::move(f));
  }
  return t;
}

}  // namespace vibrissa::recon
