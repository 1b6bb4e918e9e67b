// CSV trial files (docs/trials.md): '#'-prefixed "key: value" metadata lines, one header row, one row per
// frame. Lengths, angles and times in the units declared by "# units:"; empty cells and "nan" are NaN.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <limits>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>

#include "csv_cells.hpp"
#include "vibrissa/core/checks.hpp"
#include "vibrissa/io/atomic_file.hpp"
#include "vibrissa/io/trial_io.hpp"

namespace vibrissa::io {

using trial::located_message;

namespace {

constexpr double nan_v = std::numeric_limits<double>::quiet_NaN();

using csv::trim;

double parse_number(const std::string& cell, const std::string& src, std::size_t row, const std::string& col) {
  const std::optional<double> v = csv::number(cell);  // decimal only: "0x10" and trailing text are errors
  if (!v) throw std::invalid_argument(located_message(src, row, col, "cannot parse '" + quote_text(cell) + "' as a number"));
  return *v;
}

std::vector<double> parse_numbers(const std::string& text, std::size_t count, const std::string& src,
                                  std::size_t row, const std::string& key) {
  std::istringstream is(text);
  std::vector<double> v;
  std::string tok;
  while (is >> tok) v.push_back(parse_number(tok, src, row, key));
  if (v.size() != count)
    throw std::invalid_argument(located_message(src, row, key, "expected " + std::to_string(count) +
                                                                   " numbers, got '" + quote_text(text) + "'"));
  return v;
}

/// Reads one line of at most limits::max_csv_line_bytes.
bool read_line(std::istream& in, std::string& line, const std::string& src, std::size_t line_no) {
  if (!std::getline(in, line)) return false;
  if (line.size() > limits::max_csv_line_bytes)
    throw std::invalid_argument(located_message(src, line_no, "", "line of " + std::to_string(line.size()) +
                                                                       " bytes is longer than the limit of " +
                                                                       std::to_string(limits::max_csv_line_bytes)));
  return true;
}

}  // namespace

trial::Trial read_trial_csv(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::invalid_argument(path + ": cannot open the trial file");
  {
    std::error_code ec;
    const auto size = std::filesystem::file_size(path, ec);
    if (!ec) require_at_most(size, limits::max_csv_file_bytes, path + ": file size in bytes");
  }
  trial::Trial t;
  t.source = path;
  std::map<std::string, std::pair<std::string, std::size_t>> meta;  // key -> (value, line)
  std::vector<std::pair<std::string, std::size_t>> edges, rest_points;
  std::string line;
  std::size_t line_no = 0;
  std::vector<std::string> header;
  std::size_t header_line = 0;
  while (read_line(in, line, path, line_no + 1)) {
    ++line_no;
    if (line_no == 1 && line.starts_with("\xEF\xBB\xBF")) line.erase(0, 3);  // UTF-8 byte order mark
    const std::string s = trim(line);
    if (s.empty()) continue;
    if (s[0] == '#') {
      const std::string body = trim(s.substr(1));
      if (body.empty() || body[0] == '#') continue;  // "#" alone or "##": a free comment
      const auto colon = body.find(':');
      if (colon == std::string::npos)
        throw std::invalid_argument(located_message(
            path, line_no, "", "'" + quote_text(s) + "' is not a '# key: value' metadata line (free comments start with '##')"));
      const std::string key = trim(body.substr(0, colon)), value = trim(body.substr(colon + 1));
      if (key == "edge")
        edges.emplace_back(value, line_no);
      else if (key == "rest_point")
        rest_points.emplace_back(value, line_no);
      else if (!meta.emplace(key, std::make_pair(value, line_no)).second)
        throw std::invalid_argument(located_message(path, line_no, quote_text(key), "metadata key appears twice (first on line " +
                                                                        std::to_string(meta[key].second) + ")"));
      continue;
    }
    header = csv::split(s);
    header_line = line_no;
    break;
  }
  if (header.empty()) throw std::invalid_argument(path + ": no header row found");
  {  // The format version: required, so that a future format is never misread as this one.
    const auto it = meta.find("vibrissa-trial");
    if (it == meta.end())
      throw std::invalid_argument(located_message(path, 1, "vibrissa-trial",
                                                  "the version line '# vibrissa-trial: 1' is missing"));
    if (it->second.first != "1")
      throw std::invalid_argument(located_message(path, it->second.second, "vibrissa-trial",
                                                  "unknown format version '" + quote_text(it->second.first) +
                                                      "' (this reader knows version 1)"));
  }
  require_at_most(header.size(), limits::max_shape_points, path + ": number of columns");
  require_at_most(edges.size(), limits::max_edges, path + ": number of '# edge' lines");
  require_at_most(rest_points.size(), limits::max_shape_points, path + ": number of '# rest_point' lines");

  // Units first: everything else depends on them.
  trial::Units& u = t.meta.declared_units;
  std::size_t meta_units_line = 0;
  if (auto it = meta.find("units"); it != meta.end()) {
    meta_units_line = it->second.second;
    std::istringstream is(it->second.first);
    std::string kv;
    std::set<std::string> seen;
    while (is >> kv) {
      const auto eq = kv.find('=');
      const std::string k = kv.substr(0, eq), v = eq == std::string::npos ? "" : kv.substr(eq + 1);
      if (!seen.insert(k).second)
        throw std::invalid_argument(located_message(path, it->second.second, "units", "unit kind '" + quote_text(k) + "' is given twice"));
      if (k == "length") u.length = v;
      else if (k == "angle") u.angle = v;
      else if (k == "time") u.time = v;
      else throw std::invalid_argument(located_message(path, it->second.second, "units", "unknown unit kind '" + quote_text(k) + "'"));
    }
    meta.erase(it);
  }
  const std::size_t uline = meta_units_line;
  const double Ls = trial::length_scale(u.length, located_message(path, uline, "units", "length"));
  const double As = trial::angle_scale(u.angle, located_message(path, uline, "units", "angle"));
  const double Ts = trial::time_scale(u.time, located_message(path, uline, "units", "time"));

  auto& mat = t.meta.material;
  for (const auto& entry : meta) {  // no structured bindings: clang 14 cannot capture them in the lambda
    const std::string& key = entry.first;
    const std::string& value = entry.second.first;
    const std::size_t ln = entry.second.second;
    auto num = [&] { return parse_numbers(value, 1, path, ln, key)[0]; };
    if (key == "vibrissa-trial") continue;
    if (key == "frame_rate_Hz") t.meta.frame_rate = num();
    else if (key == "youngs_modulus_Pa") mat.youngs_modulus = num();
    else if (key == "poisson_ratio") mat.poisson_ratio = num();
    else if (key == "base_radius") mat.base_radius = num() * Ls;
    else if (key == "taper_ratio") mat.taper_ratio = num();
    else if (key == "links") {
      try {
        mat.links = require_integer(num(), 2, limits::max_links, "links");
      } catch (const std::invalid_argument& e) {
        throw std::invalid_argument(located_message(path, ln, key, e.what()));
      }
    }
    else throw std::invalid_argument(located_message(path, ln, quote_text(key), "unknown metadata key"));
  }
  for (const auto& [value, ln] : edges) {
    const auto v = parse_numbers(value, 6, path, ln, "edge");
    Edge e;
    e.point = Eigen::Vector3d(v[0], v[1], v[2]) * Ls;
    e.direction = Eigen::Vector3d(v[3], v[4], v[5]);
    t.meta.edges.push_back(e);
  }
  for (const auto& [value, ln] : rest_points) {
    const auto v = parse_numbers(value, 3, path, ln, "rest_point");
    t.meta.rest_shape.emplace_back(Eigen::Vector3d(v[0], v[1], v[2]) * Ls);
  }

  // Columns.
  std::map<std::string, std::size_t> col;
  for (std::size_t c = 0; c < header.size(); ++c) {
    if (col.count(header[c]))
      throw std::invalid_argument(located_message(path, header_line, quote_text(header[c]), "column appears twice"));
    col[header[c]] = c;
  }
  auto require = [&](const char* name) {
    if (!col.count(name))
      throw std::invalid_argument(located_message(path, header_line, name, "required column is missing"));
    return col[name];
  };
  const std::size_t c_time = require("time"), c_theta = require("theta"), c_phi = require("phi"),
                    c_contact = require("contact");
  const std::size_t c_base[3] = {require("base_x"), require("base_y"), require("base_z")};
  const bool has_zeta = col.count("zeta") > 0;
  const int n_contact_cols = int(col.count("contact_x") + col.count("contact_y") + col.count("contact_z"));
  if (n_contact_cols != 0 && n_contact_cols != 3)
    throw std::invalid_argument(located_message(path, header_line, "contact_x",
                                                "contact_x, contact_y and contact_z must appear together"));
  std::size_t shape_nodes = 0;
  while (col.count("shape_x_" + std::to_string(shape_nodes))) ++shape_nodes;
  for (std::size_t k = 0; k < shape_nodes; ++k)
    for (const char* a : {"shape_y_", "shape_z_"})
      if (!col.count(a + std::to_string(k)))
        throw std::invalid_argument(located_message(path, header_line, a + std::to_string(k),
                                                    "shape columns must come in x, y, z triples"));
  for (const auto& [name, c] : col) {
    (void)c;
    const bool known = name == "time" || name == "theta" || name == "phi" || name == "zeta" ||
                       name == "contact" || name.rfind("base_", 0) == 0 || name.rfind("contact_", 0) == 0 ||
                       name.rfind("shape_", 0) == 0 || name == "reconstructed" || name == "reprojection_px" ||
                       name == "likelihood";
    if (!known) throw std::invalid_argument(located_message(path, header_line, quote_text(name), "unknown column"));
  }

  std::vector<std::size_t> rows;
  while (read_line(in, line, path, line_no + 1)) {
    ++line_no;
    const std::string s = trim(line);
    if (s.empty() || s[0] == '#') continue;
    if (rows.size() == limits::max_trial_frames)
      require_at_most(rows.size() + 1, limits::max_trial_frames, path + ": number of frames");
    const auto cells = csv::split(s);
    if (cells.size() != header.size())
      throw std::invalid_argument(located_message(path, line_no, "",
                                                  "has " + std::to_string(cells.size()) + " cells, the header has " +
                                                      std::to_string(header.size())));
    auto get = [&](std::size_t c) { return parse_number(cells[c], path, line_no, header[c]); };
    rows.push_back(line_no);
    t.time.push_back(get(c_time) * Ts);
    t.base_W.emplace_back(Eigen::Vector3d(get(c_base[0]), get(c_base[1]), get(c_base[2])) * Ls);
    t.theta.push_back(get(c_theta) * As);
    t.phi.push_back(get(c_phi) * As);
    if (has_zeta) t.zeta.push_back(get(col["zeta"]) * As);
    const double flag = get(c_contact);
    if (!(flag == 0.0 || flag == 1.0))
      throw std::invalid_argument(located_message(path, line_no, "contact",
                                                  "contact flag must be 0 or 1, got '" + quote_text(cells[c_contact]) + "'"));
    t.contact.push_back(static_cast<std::uint8_t>(flag));
    if (col.count("reconstructed")) {
      const double r = get(col["reconstructed"]);
      if (!(r == 0.0 || r == 1.0))
        throw std::invalid_argument(located_message(path, line_no, "reconstructed",
                                                    "flag must be 0 or 1, got '" + cells[col["reconstructed"]] + "'"));
      t.reconstructed.push_back(static_cast<std::uint8_t>(r));
    }
    if (col.count("reprojection_px")) t.reprojection_px.push_back(get(col["reprojection_px"]));
    if (col.count("likelihood")) t.likelihood.push_back(get(col["likelihood"]));
    if (n_contact_cols == 3)
      t.contact_W.emplace_back(Eigen::Vector3d(get(col["contact_x"]), get(col["contact_y"]), get(col["contact_z"])) * Ls);
    if (shape_nodes > 0) {
      std::vector<Eigen::Vector3d> shape;
      for (std::size_t k = 0; k < shape_nodes; ++k) {
        const std::string ks = std::to_string(k);
        const Eigen::Vector3d p(get(col["shape_x_" + ks]), get(col["shape_y_" + ks]), get(col["shape_z_" + ks]));
        if (!p.allFinite()) break;  // NaN-padded: shorter shapes end at the first NaN node
        shape.emplace_back(p * Ls);
      }
      t.shape_W.push_back(std::move(shape));
    }
  }
  if (t.time.empty()) throw std::invalid_argument(located_message(path, header_line + 1, "", "no data rows"));
  trial::validate(t, &rows);
  return t;
}

void write_trial_csv(const trial::Trial& t, const std::string& path) {
  write_text_atomically(path, [&](std::ostream& out) {
    out << std::setprecision(17);
    out << "# vibrissa-trial: 1\n# units: length=m angle=rad time=s\n";
    out << "# frame_rate_Hz: " << t.meta.frame_rate << "\n";
    const auto& m = t.meta.material;
    out << "# youngs_modulus_Pa: " << m.youngs_modulus << "\n# poisson_ratio: " << m.poisson_ratio
        << "\n# base_radius: " << m.base_radius << "\n# taper_ratio: " << m.taper_ratio << "\n# links: " << m.links
        << "\n";
    for (const auto& e : t.meta.edges)
      out << "# edge: " << e.point.x() << " " << e.point.y() << " " << e.point.z() << " " << e.direction.x() << " "
          << e.direction.y() << " " << e.direction.z() << "\n";
    for (const auto& p : t.meta.rest_shape) out << "# rest_point: " << p.x() << " " << p.y() << " " << p.z() << "\n";
    std::size_t K = 0;
    for (const auto& s : t.shape_W) K = std::max(K, s.size());
    out << "time,base_x,base_y,base_z,theta,phi";
    if (t.has_zeta()) out << ",zeta";
    out << ",contact";
    if (t.has_contact_point()) out << ",contact_x,contact_y,contact_z";
    if (!t.reconstructed.empty()) out << ",reconstructed";
    if (!t.reprojection_px.empty()) out << ",reprojection_px";
    if (!t.likelihood.empty()) out << ",likelihood";
    for (std::size_t k = 0; k < K; ++k) out << ",shape_x_" << k << ",shape_y_" << k << ",shape_z_" << k;
    out << "\n";
    auto cell = [&](double v) {
      out << ',';
      if (std::isfinite(v)) out << v;
      else out << "nan";
    };
    for (std::size_t i = 0; i < t.frames(); ++i) {
      out << t.time[i];
      for (int a = 0; a < 3; ++a) cell(t.base_W[i][a]);
      cell(t.theta[i]);
      cell(t.phi[i]);
      if (t.has_zeta()) cell(t.zeta[i]);
      out << ',' << int(t.contact[i]);
      if (t.has_contact_point())
        for (int a = 0; a < 3; ++a) cell(t.contact_W[i][a]);
      if (!t.reconstructed.empty()) out << ',' << int(t.reconstructed[i]);
      if (!t.reprojection_px.empty()) cell(t.reprojection_px[i]);
      if (!t.likelihood.empty()) cell(t.likelihood[i]);
      for (std::size_t k = 0; k < K; ++k)
        for (int a = 0; a < 3; ++a) cell(t.has_shapes() && k < t.shape_W[i].size() ? t.shape_W[i][k][a] : nan_v);
      out << "\n";
    }
  });
}

}  // namespace vibrissa::io
