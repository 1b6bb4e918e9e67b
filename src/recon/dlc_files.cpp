// DeepLabCut track files (docs/reconstruction.md, "Track files"): the CSV with its three or four header rows
// (scorer / [individuals /] bodyparts / coords) and the pandas HDF5 table.
#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <stdexcept>

#include "dlc_columns.hpp"
#include "text_cells.hpp"
#include "vibrissa/recon/tracks.hpp"

namespace vibrissa::recon {

DlcColumns select_dlc_columns(const std::vector<DlcColumn>& columns, const std::vector<std::string>& bodyparts,
                              const std::string& individual, const std::string& path) {
  std::vector<std::string> individuals;
  for (const auto& c : columns)
    if (std::find(individuals.begin(), individuals.end(), c.individual) == individuals.end())
      individuals.push_back(c.individual);
  std::string who = individual;
  if (who.empty()) {
    if (individuals.size() > 1)
      throw std::invalid_argument(cell_message(path, 0, "individuals", "the file has " +
                                                                           std::to_string(individuals.size()) +
                                                                           " individuals: choose one"));
    who = individuals.empty() ? std::string() : individuals.front();
  } else if (std::find(individuals.begin(), individuals.end(), who) == individuals.end()) {
    throw std::invalid_argument(cell_message(path, 0, "individuals", "no individual '" + who + "' in the file"));
  }
  std::vector<std::string> order = bodyparts;
  if (order.empty())
    for (const auto& c : columns)
      if (c.individual == who && std::find(order.begin(), order.end(), c.bodypart) == order.end())
        order.push_back(c.bodypart);
  DlcColumns out;
  for (const auto& bp : order) {
    std::array<std::size_t, 3> idx{npos_column, npos_column, npos_column};
    for (std::size_t k = 0; k < columns.size(); ++k) {
      const auto& c = columns[k];
      if (c.individual != who || c.bodypart != bp) continue;
      const int slot = c.coord == "x" ? 0 : c.coord == "y" ? 1 : c.coord == "likelihood" ? 2 : -1;
      if (slot < 0) throw std::invalid_argument(cell_message(path, 0, "coords", "unknown coordinate '" + c.coord + "'"));
      idx[std::size_t(slot)] = k;
    }
    if (idx[0] == npos_column || idx[1] == npos_column)
      throw std::invalid_argument(cell_message(path, 0, "bodyparts", "no x and y columns for bodypart '" + bp + "'"));
    out.bodyparts.push_back(bp);
    out.columns.push_back(idx);
  }
  if (out.columns.empty()) throw std::invalid_argument(cell_message(path, 0, "bodyparts", "no bodypart selected"));
  return out;
}

void append_dlc_frame(Tracks2D& t, std::int64_t frame, const std::vector<double>& values, const DlcColumns& sel,
                      std::size_t line) {
  TrackFrame f;
  f.frame = frame;
  for (std::size_t b = 0; b < sel.columns.size(); ++b) {
    const auto& idx = sel.columns[b];
    const Eigen::Vector2d p(values[idx[0]], values[idx[1]]);
    const double l = idx[2] == npos_column ? 1.0 : values[idx[2]];
    if (std::isfinite(l) && (l < 0.0 || l > 1.0))
      throw std::invalid_argument(cell_message(t.source, line, sel.bodyparts[b] + ".likelihood",
                                               "frame " + std::to_string(frame) + ": must lie in [0, 1]"));
    if (!p.allFinite() || !std::isfinite(l)) continue;
    f.points_px.push_back(p);
    f.likelihood.push_back(l);
  }
  if (!t.frames.empty() && t.frames.back().frame >= frame)
    throw std::invalid_argument(cell_message(t.source, line, "index", "frame " + std::to_string(frame) +
                                                                          " does not follow frame " +
                                                                          std::to_string(t.frames.back().frame)));
  if (!f.points_px.empty()) t.frames.push_back(std::move(f));
}

Tracks2D read_dlc_csv(const std::string& path, const std::vector<std::string>& bodyparts,
                      const std::string& individual) {
  std::ifstream in = open_input(path, "track file");
  std::map<std::string, std::vector<std::string>> header;
  std::string line;
  std::size_t line_no = 0;
  std::size_t width = 0;
  while (!header.count("coords") && std::getline(in, line)) {
    ++line_no;
    auto cells = split_cells(trim(line));
    const std::string key = cells.empty() ? std::string() : cells[0];
    if (key != "scorer" && key != "individuals" && key != "bodyparts" && key != "coords")
      throw std::invalid_argument(cell_message(path, line_no, key, "expected the DeepLabCut header rows scorer, "
                                                                   "[individuals,] bodyparts, coords"));
    if (width == 0) width = cells.size();
    if (cells.size() != width)
      throw std::invalid_argument(cell_message(path, line_no, key, "has " + std::to_string(cells.size()) +
                                                                       " cells, the scorer row has " +
                                                                       std::to_string(width)));
    header[key] = std::move(cells);
  }
  for (const char* key : {"scorer", "bodyparts", "coords"})
    if (!header.count(key)) throw std::invalid_argument(cell_message(path, line_no, key, "header row is missing"));
  // Index columns: the leading cells whose coords entry is empty (one, or three in labelled-data files).
  std::size_t first = 1;
  while (first < width && header["coords"][first].empty()) ++first;
  std::vector<DlcColumn> columns;
  for (std::size_t c = first; c < width; ++c)
    columns.push_back({header.count("individuals") ? header["individuals"][c] : std::string(), header["bodyparts"][c],
                       header["coords"][c]});
  const DlcColumns sel = select_dlc_columns(columns, bodyparts, individual, path);
  Tracks2D t;
  t.source = path;
  std::int64_t row = -1;
  while (std::getline(in, line)) {
    ++line_no;
    const std::string s = trim(line);
    if (s.empty()) continue;
    ++row;
    const auto cells = split_cells(s);
    if (cells.size() != width)
      throw std::invalid_argument(cell_message(path, line_no, "", "has " + std::to_string(cells.size()) +
                                                                      " cells, the header has " + std::to_string(width)));
    std::int64_t frame = row;  // an integer index is the frame; an image path keeps the row order
    if (first == 1 && !cells[0].empty() && cells[0].find_first_not_of("0123456789") == std::string::npos)
      frame = parse_index(cells[0], path, line_no, "index");
    std::vector<double> values(columns.size());
    for (std::size_t c = first; c < width; ++c) {
      const std::string field = header["bodyparts"][c] + "." + header["coords"][c];
      values[c - first] = parse_cell(cells[c], path, line_no, field);
    }
    append_dlc_frame(t, frame, values, sel, line_no);
  }
  return t;
}

}  // namespace vibrissa::recon
