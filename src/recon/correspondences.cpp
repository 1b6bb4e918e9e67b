// Calibration correspondences (docs/reconstruction.md, "Calibration").
#include <fstream>
#include <cmath>
#include <stdexcept>

#include "text_cells.hpp"
#include "vibrissa/recon/geometry.hpp"
#include "vibrissa/trial/format.hpp"

namespace vibrissa::recon {

Correspondences read_correspondences_csv(const std::string& path, const std::string& length_unit) {
  const double Ls = trial::length_scale(length_unit, path + ": length unit");
  std::ifstream in = open_input(path, "correspondence file");
  static const std::vector<std::string> expected = {"x", "y", "z", "u_px", "v_px"};
  std::string line;
  std::size_t line_no = 0;
  bool header = false;
  Correspondences c;
  while (std::getline(in, line)) {
    ++line_no;
    const std::string s = trim(line);
    if (s.empty() || s[0] == '#') continue;
    const auto cells = split_cells(s);
    if (!header) {
      if (cells != expected) throw std::invalid_argument(cell_message(path, line_no, "header", "expected x,y,z,u_px,v_px"));
      header = true;
      continue;
    }
    if (cells.size() != expected.size())
      throw std::invalid_argument(cell_message(path, line_no, "", "expected 5 cells, got " + std::to_string(cells.size())));
    double v[5];
    for (std::size_t k = 0; k < 5; ++k) {
      v[k] = parse_cell(cells[k], path, line_no, expected[k]);
      if (!std::isfinite(v[k])) throw std::invalid_argument(cell_message(path, line_no, expected[k], "value is missing"));
    }
    c.points_W.emplace_back(Eigen::Vector3d(v[0], v[1], v[2]) * Ls);
    c.pixels.emplace_back(v[3], v[4]);
  }
  if (!header) throw std::invalid_argument(cell_message(path, 0, "header", "the file is empty"));
  return c;
}

}  // namespace vibrissa::recon
