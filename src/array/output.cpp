#include "vibrissa/array/output.hpp"

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <stdexcept>

#include "array_util.hpp"
#include "h5_writer.hpp"
#include "vibrissa/array/sweep.hpp"

namespace vibrissa::array {

void write_array_h5(const ArrayResult& r, const SimulationConfig& c, const std::filesystem::path& path) {
  h5::Writer out(path.string());
  const hid_t root = out.root();
  const hsize_t P = r.n_pitches, W = r.n_whiskers, F = r.n_frames;
  const std::vector<hsize_t> pwf{P, W, F}, pwf3{P, W, F, 3}, wf{W, F};
  out.attribute(root, "layout", "[pitch][whisker][frame]");
  out.attribute(root, "morphology", c.morphology.source);
  out.attribute(root, "mode", std::string(to_string(c.mode)));
  out.attribute(root, "mu", c.mu);
  out.attribute(root, "slopes", std::string(to_string(c.whisking.slopes)));
  out.attribute(root, "state_codes", "0 free, 1 contact, 2 pushed_past");
  out.attribute(root, "solver_status_codes", "-1 no solve, 0 converged, 1 no_contact, 2 slipped_off, 3 not_converged");
  out.write(root, "time", r.times, {F}, "s");
  out.write(root, "pitch", r.pitches, {P}, "rad");
  out.write_strings(root, "whisker", r.labels);
  std::vector<std::int8_t> side, row, column;
  for (const WhiskerSpec& s : c.morphology.whiskers) {
    side.push_back(s.side == Side::right ? 1 : -1);
    row.push_back(static_cast<std::int8_t>(s.row));
    column.push_back(static_cast<std::int8_t>(s.column));
  }
  out.write(root, "side", side, {W}, "+1 right, -1 left");
  out.write(root, "row", row, {W}, "1..5 = A..E");
  out.write(root, "column", column, {W});
  out.write(root, "state", r.state, pwf);
  out.write(root, "solver_status", r.solver_status, pwf);
  out.write(root, "edge_index", r.edge, pwf);
  out.write(root, "s_applied", r.s_applied, pwf, "m");
  out.write(root, "contact_point_W", r.contact_W, pwf3, "m");
  out.write(root, "force_W", r.force_W, pwf3, "N");
  out.write(root, "moment_W", r.moment_W, pwf3, "N m");
  out.write(root, "force_B", r.force_B, pwf3, "N");
  out.write(root, "moment_B", r.moment_B, pwf3, "N m");
  out.write(root, "FT", r.FT, pwf, "N");
  out.write(root, "MB", r.MB, pwf, "N m");
  out.write(root, "FD", r.FD, pwf, "rad");
  out.write(root, "MD", r.MD, pwf, "rad");
  out.write(root, "normal_force", r.normal_force, pwf, "N");
  out.write(root, "edge_force", r.edge_force, pwf, "N");
  out.write(root, "z_edge", r.z_edge, pwf, "m");
  out.write(root, "z_error", r.z_error, pwf, "m");
  out.write(root, "base_W", r.base_W, pwf3, "m");
  out.write(root, "theta", r.theta, wf, "rad");
  out.write(root, "phi", r.phi, wf, "rad");
  out.write(root, "zeta", r.zeta, wf, "rad");
  const h5::Id render = out.group("render");
  const hsize_t R = r.render_frames.size(), N = r.n_nodes;
  out.attribute(render.get(), "pitch_index", static_cast<double>(c.render_pitch));
  out.write(render.get(), "frame", r.render_frames, {R});
  out.write(render.get(), "rest", r.rest_shapes, {R, W, N, 3}, "m");
  out.write(render.get(), "deflected", r.deflected_shapes, {R, W, N, 3}, "m");
  out.write(render.get(), "edges", r.render_edges, {R, r.n_edges, 2, 3}, "m");
}

void write_array_csv(const ArrayResult& r, const std::filesystem::path& path) {
  std::FILE* f = std::fopen(path.string().c_str(), "w");
  if (!f) throw std::runtime_error("cannot write '" + path.string() + "'");
  std::fprintf(f,
               "pitch_deg,whisker,frame,time_s,state,edge,s_applied_mm,contact_x_mm,contact_y_mm,contact_z_mm,"
               "Fx_W_mN,Fy_W_mN,Fz_W_mN,Mx_W_uNm,My_W_uNm,Mz_W_uNm,Fx_mN,Fy_mN,Fz_mN,Mx_uNm,My_uNm,Mz_uNm,"
               "FT_mN,MB_uNm,FD_deg,MD_deg,FN_mN,z_error_mm\n");
  for (std::size_t p = 0; p < r.n_pitches; ++p)
    for (std::size_t w = 0; w < r.n_whiskers; ++w)
      for (std::size_t fr = 0; fr < r.n_frames; ++fr) {
        const std::size_t k = r.index(p, w, fr);
        const auto v = [&](const std::vector<double>& a, int i) { return a[3 * k + static_cast<std::size_t>(i)]; };
        std::fprintf(f, "%.6g,%s,%zu,%.9g,%s,%d,%.9g,%.9g,%.9g,%.9g", to_deg(r.pitches[p]), r.labels[w].c_str(), fr,
                     r.times[fr], std::string(to_string(static_cast<ContactState>(r.state[k]))).c_str(), r.edge[k],
                     r.s_applied[k] * 1e3, v(r.contact_W, 0) * 1e3, v(r.contact_W, 1) * 1e3, v(r.contact_W, 2) * 1e3);
        for (const auto* a : {&r.force_W, &r.moment_W, &r.force_B, &r.moment_B}) {
          const double unit = (a == &r.force_W || a == &r.force_B) ? 1e3 : 1e6;
          for (int i = 0; i < 3; ++i) std::fprintf(f, ",%.9g", v(*a, i) * unit);
        }
        std::fprintf(f, ",%.9g,%.9g,%.9g,%.9g,%.9g,%.9g\n", r.FT[k] * 1e3, r.MB[k] * 1e6, to_deg(r.FD[k]),
                     to_deg(r.MD[k]), r.normal_force[k] * 1e3, r.z_error[k] * 1e3);
      }
  std::fclose(f);
}

void write_pitch_summary_csv(const ArrayResult& r, const std::filesystem::path& path) {
  std::ofstream out(path);
  if (!out) throw std::runtime_error("cannot write '" + path.string() + "'");
  out << "pitch_deg,whiskers_touching,whiskers_pushed_past,contact_frames,first_onset_ms,peak_MB_uNm,"
         "peak_MB_whisker,mean_peak_MB_uNm,mean_peak_FT_mN,max_abs_z_error_mm\n";
  for (const PitchSummary& s : summarize_pitches(r)) {
    out << to_deg(s.pitch) << ',' << s.whiskers_touching << ',' << s.whiskers_pushed_past << ',' << s.contact_frames
        << ',' << (s.whiskers_touching ? fmt(s.first_onset_time * 1e3) : std::string()) << ',' << s.peak_MB * 1e6
        << ',' << s.peak_MB_whisker << ',' << s.mean_peak_MB * 1e6 << ',' << s.mean_peak_FT * 1e3 << ','
        << s.max_abs_z_error * 1e3 << '\n';
  }
}

std::vector<std::size_t> h5_dataset_shape(const std::filesystem::path& path, const std::string& name) {
  H5E_auto2_t func = nullptr;
  void* data = nullptr;
  H5Eget_auto2(H5E_DEFAULT, &func, &data);
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  std::vector<std::size_t> shape;
  bool ok = false;
  const hid_t file = H5Fopen(path.string().c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  if (file >= 0) {
    const hid_t set = H5Dopen2(file, name.c_str(), H5P_DEFAULT);
    if (set >= 0) {
      const hid_t space = H5Dget_space(set);
      std::vector<hsize_t> dims(static_cast<std::size_t>(std::max(H5Sget_simple_extent_ndims(space), 0)));
      H5Sget_simple_extent_dims(space, dims.data(), nullptr);
      for (hsize_t d : dims) shape.push_back(static_cast<std::size_t>(d));
      ok = true;
      H5Sclose(space);
      H5Dclose(set);
    }
    H5Fclose(file);
  }
  H5Eset_auto2(H5E_DEFAULT, func, data);
  if (!ok) throw std::runtime_error("no dataset '" + name + "' in '" + path.string() + "'");
  return shape;
}

nlohmann::json summary_json(const ArrayResult& r, const SimulationConfig& c) {
  nlohmann::json j;
  j["morphology"] = c.morphology.source;
  j["whiskers"] = r.n_whiskers;
  j["frames"] = r.n_frames;
  j["pitches_deg"] = nlohmann::json::array();
  for (double p : r.pitches) j["pitches_deg"].push_back(to_deg(p));
  j["mode"] = std::string(to_string(c.mode));
  j["mu"] = c.mu;
  j["solves"] = r.solves;
  j["failed_solves"] = r.failed_solves;
  j["simulation_seconds"] = r.wall_seconds;
  j["per_pitch"] = nlohmann::json::array();
  for (const PitchSummary& s : summarize_pitches(r)) {
    nlohmann::json e;
    e["pitch_deg"] = to_deg(s.pitch);
    e["whiskers_touching"] = s.whiskers_touching;
    e["whiskers_pushed_past"] = s.whiskers_pushed_past;
    e["contact_frames"] = s.contact_frames;
    e["first_onset_ms"] = s.whiskers_touching ? nlohmann::json(s.first_onset_time * 1e3) : nlohmann::json();
    e["peak_MB_uNm"] = s.peak_MB * 1e6;
    e["peak_MB_whisker"] = s.peak_MB_whisker;
    e["mean_peak_MB_uNm"] = s.mean_peak_MB * 1e6;
    e["mean_peak_FT_mN"] = s.mean_peak_FT * 1e3;
    e["max_abs_z_error_mm"] = s.max_abs_z_error * 1e3;
    nlohmann::json per = nlohmann::json::object();
    for (std::size_t w = 0; w < r.n_whiskers; ++w) {
      const WhiskerRunSummary& ws = s.whiskers[w];
      if (!ws.touched && !ws.pushed_past) continue;
      per[r.labels[w]] = {{"contact_frames", ws.contact_frames},
                          {"pushed_past", ws.pushed_past},
                          {"onset_ms", ws.touched ? nlohmann::json(ws.onset_time * 1e3) : nlohmann::json()},
                          {"peak_FT_mN", ws.peak_FT * 1e3},
                          {"peak_MB_uNm", ws.peak_MB * 1e6},
                          {"MD_at_peak_deg", to_deg(ws.MD_at_peak_MB)},
                          {"peak_abs_Fx_mN", ws.peak_abs_Fx * 1e3},
                          {"max_abs_z_error_mm", ws.max_abs_z_error * 1e3}};
    }
    e["whiskers"] = per;
    j["per_pitch"].push_back(e);
  }
  return j;
}

}  // namespace vibrissa::array
