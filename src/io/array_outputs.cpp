#include "vibrissa/io/array_outputs.hpp"

#include <cerrno>
#include <cmath>
#include <cstring>
#include <cstdio>
#include <future>
#include <ostream>
#include <stdexcept>

#include "../array/array_util.hpp"  // the array layer's unit helpers
#include "code_tables.hpp"
#include "h5_file.hpp"
#include "vibrissa/array/sweep.hpp"
#include "vibrissa/io/figure_files.hpp"
#include "vibrissa/io/json_file.hpp"
#include "vibrissa/io/nan_reasons.hpp"

namespace vibrissa::io {

using namespace vibrissa::array;

namespace {

void create_array_h5(const ArrayResult& r, const SimulationConfig& c, const std::string& path) {
  h5::QuietErrors quiet;
  h5::Handle file = h5::create_file(path);
  const hid_t root = file.get();
  const hsize_t P = r.n_pitches, W = r.n_whiskers, F = r.n_frames;
  const std::vector<hsize_t> pwf{P, W, F}, pwf3{P, W, F, 3}, wf{W, F};
  // Every dataset is compressed when large (most frames hold zeros); `units` names its unit.
  const auto in = [](const char* units) { return h5::DatasetOptions(units, true); };
  h5::write_string_attribute(root, "layout", "[pitch][whisker][frame]");
  h5::write_string_attribute(root, "morphology", c.morphology.source);
  h5::write_string_attribute(root, "mode", std::string(to_string(c.mode)));
  h5::write_double_attribute(root, "mu", c.mu);
  h5::write_string_attribute(root, "slopes", std::string(to_string(c.whisking.slopes)));
  // The code tables also stay root attributes, as files before the "codes" dataset attribute had them.
  h5::write_string_attribute(root, "state_codes", contact_state_code_table());
  h5::write_string_attribute(root, "solver_status_codes", status_code_table());
  h5::write_dataset(root, "time", r.times, {F}, in("s"));
  h5::write_dataset(root, "pitch", r.pitches, {P}, in("rad"));
  h5::write_fixed_strings(root, "whisker", r.labels);
  std::vector<std::int8_t> side, row, column;
  for (const WhiskerSpec& s : c.morphology.whiskers) {
    side.push_back(s.side == Side::right ? 1 : -1);
    row.push_back(static_cast<std::int8_t>(s.row));
    column.push_back(static_cast<std::int8_t>(s.column));
  }
  const auto coded = [](std::string table) { return h5::DatasetOptions("code", true, std::move(table)); };
  h5::write_dataset(root, "side", side, {W}, coded("1 right, -1 left"));
  h5::write_dataset(root, "row", row, {W}, coded("1 A, 2 B, 3 C, 4 D, 5 E"));
  h5::write_dataset(root, "column", column, {W}, in("1"));
  h5::write_dataset(root, "state", r.state, pwf, coded(contact_state_code_table()));
  h5::write_dataset(root, "solver_status", r.solver_status, pwf, coded(status_code_table()));
  h5::write_dataset(root, "edge_index", r.edge, pwf, in("1"));
  h5::write_dataset(root, "s_applied", r.s_applied, pwf, in("m"));
  h5::write_dataset(root, "contact_point_W", r.contact_W, pwf3, in("m"));
  h5::write_dataset(root, "force_W", r.force_W, pwf3, in("N"));
  h5::write_dataset(root, "moment_W", r.moment_W, pwf3, in("N m"));
  h5::write_dataset(root, "force_B", r.force_B, pwf3, in("N"));
  h5::write_dataset(root, "moment_B", r.moment_B, pwf3, in("N m"));
  h5::write_dataset(root, "FT", r.FT, pwf, in("N"));
  h5::write_dataset(root, "MB", r.MB, pwf, in("N m"));
  h5::write_dataset(root, "FD", r.FD, pwf, in("rad"));
  h5::write_dataset(root, "MD", r.MD, pwf, in("rad"));
  h5::write_dataset(root, "normal_force", r.normal_force, pwf, in("N"));
  h5::write_dataset(root, "edge_force", r.edge_force, pwf, in("N"));
  h5::write_dataset(root, "z_edge", r.z_edge, pwf, in("m"));
  h5::write_dataset(root, "z_error", r.z_error, pwf, in("m"));
  h5::write_dataset(root, "base_W", r.base_W, pwf3, in("m"));
  h5::write_dataset(root, "theta", r.theta, wf, in("rad"));
  h5::write_dataset(root, "phi", r.phi, wf, in("rad"));
  h5::write_dataset(root, "zeta", r.zeta, wf, in("rad"));
  {
    const h5::Handle render = h5::create_group(root, "render");
    const hsize_t R = r.render_frames.size(), N = r.n_nodes;
    h5::write_double_attribute(render.get(), "pitch_index", static_cast<double>(c.render_pitch));
    h5::write_dataset(render.get(), "frame", r.render_frames, {R}, in("1"));
    h5::write_dataset(render.get(), "rest", r.rest_shapes, {R, W, N, 3}, in("m"));
    h5::write_dataset(render.get(), "deflected", r.deflected_shapes, {R, W, N, 3}, in("m"));
    h5::write_dataset(render.get(), "edges", r.render_edges, {R, r.n_edges, 2, 3}, in("m"));
  }
  h5::close_file(file, path);
}

// One row per (pitch, whisker, frame); units in the column names.
void create_array_csv(const ArrayResult& r, const std::string& path, const std::filesystem::path& target) {
  std::FILE* f = std::fopen(path.c_str(), "w");
  if (!f) throw std::runtime_error("cannot write '" + target.string() + "': " + std::strerror(errno));
  std::fprintf(f,
               "pitch_deg,whisker,frame,time_s,state,edge,s_applied_mm,contact_x_mm,contact_y_mm,contact_z_mm,"
               "Fx_W_mN,Fy_W_mN,Fz_W_mN,Mx_W_uNm,My_W_uNm,Mz_W_uNm,Fx_mN,Fy_mN,Fz_mN,Mx_uNm,My_uNm,Mz_uNm,"
               "FT_mN,MB_uNm,FD_deg,MD_deg,FN_mN,z_error_mm\n");
  for (std::size_t p = 0; p < r.n_pitches; ++p)
    for (std::size_t w = 0; w < r.n_whiskers; ++w)
      for (std::size_t fr = 0; fr < r.n_frames; ++fr) {
        const std::size_t k = r.index(p, w, fr);
        const auto v = [&](const std::vector<double>& a, int i) { return a[3 * k + static_cast<std::size_t>(i)]; };
        // ",value", or "," alone where the value does not exist (NaN).
        const auto cell = [f](double x) {
          if (std::isnan(x)) std::fputc(',', f);
          else std::fprintf(f, ",%.9g", x);
        };
        std::fprintf(f, "%.6g,%s,%zu,%.9g,%s,%d", to_deg(r.pitches[p]), r.labels[w].c_str(), fr, r.times[fr],
                     std::string(to_string(static_cast<ContactState>(r.state[k]))).c_str(), r.edge[k]);
        cell(r.s_applied[k] * 1e3);
        for (int i = 0; i < 3; ++i) cell(v(r.contact_W, i) * 1e3);
        for (const auto* a : {&r.force_W, &r.moment_W, &r.force_B, &r.moment_B}) {
          const double unit = (a == &r.force_W || a == &r.force_B) ? 1e3 : 1e6;
          for (int i = 0; i < 3; ++i) cell(v(*a, i) * unit);
        }
        for (double x : {r.FT[k] * 1e3, r.MB[k] * 1e6, to_deg(r.FD[k]), to_deg(r.MD[k]), r.normal_force[k] * 1e3,
                         r.z_error[k] * 1e3})
          cell(x);
        std::fputc('\n', f);
      }
  const bool failed = std::ferror(f) != 0;
  const int err = errno;
  if (std::fclose(f) != 0 || failed)
    throw std::runtime_error("cannot write '" + target.string() + "': " + std::strerror(failed ? err : errno));
}

// Reasons for the nulls of the summaries (io/nan_reasons.hpp), shared by summary.json and pitch_summary.csv.
constexpr const char* kNoOnsetAtPitch = "no whisker touches an object at this head pitch";
constexpr const char* kPushedPastWithoutContact =
    "the whisker was pushed past the object without a converged contact frame";

// One row per pitch (the head-pitch sweep table); the last column gives the reason for each empty cell.
void print_pitch_summary_csv(const ArrayResult& r, std::ostream& out) {
  out << "pitch_deg,whiskers_touching,whiskers_pushed_past,contact_frames,first_onset_ms,peak_MB_uNm,"
         "peak_MB_whisker,mean_peak_MB_uNm,mean_peak_FT_mN,max_abs_z_error_mm,nan_reasons\n";
  for (const PitchSummary& s : summarize_pitches(r)) {
    out << to_deg(s.pitch) << ',' << s.whiskers_touching << ',' << s.whiskers_pushed_past << ',' << s.contact_frames
        << ',' << (s.whiskers_touching ? fmt(s.first_onset_time * 1e3) : std::string()) << ',' << s.peak_MB * 1e6
        << ',' << s.peak_MB_whisker << ',' << s.mean_peak_MB * 1e6 << ',' << s.mean_peak_FT * 1e3 << ','
        << s.max_abs_z_error * 1e3 << ','
        << (s.whiskers_touching ? std::string() : std::string("\"first_onset_ms: ") + kNoOnsetAtPitch + "\"") << '\n';
  }
}

}  // namespace

void write_array_outputs(const ArrayResult& result, const SimulationConfig& config, const nlohmann::json& config_json,
                         const std::filesystem::path& dir, const ArrayOutputOptions& options) {
  // One set (output_folder.hpp); the figures of an older run are not carried over.
  OutputFolder folder(dir, kArrayFigures);
  // The serial tail after the parallel simulation, overlapped: array.h5 is written on a second thread while
  // this one writes the text outputs; all are published together once every one is written.
  std::future<void> h5 = std::async(std::launch::async, [&] {
    folder.stage("array.h5", [&](const std::string& tmp) { create_array_h5(result, config, tmp); });
  });
  try {
    if (options.csv)
      folder.stage("array.csv", [&](const std::string& tmp) { create_array_csv(result, tmp, dir / "array.csv"); });
    folder.stage_text("pitch_summary.csv", [&](std::ostream& out) { print_pitch_summary_csv(result, out); });
    stage_json_file(folder, "config.json", config_json);
    stage_json_file(folder, "summary.json", array_summary_json(result, config));
  } catch (...) {
    h5.wait();  // the folder must outlive its writer
    throw;
  }
  h5.get();  // rethrows the HDF5 writer's exception
  folder.commit();
}

std::vector<std::size_t> h5_dataset_shape(const std::filesystem::path& path, const std::string& name) {
  h5::QuietErrors quiet;
  std::optional<std::vector<hsize_t>> dims;
  if (H5Fis_hdf5(path.c_str()) > 0) dims = h5::dataset_dims(h5::open_file_read(path.string()).get(), name);
  if (!dims) throw std::runtime_error("no dataset '" + name + "' in '" + path.string() + "'");
  return {dims->begin(), dims->end()};
}

nlohmann::json array_summary_json(const ArrayResult& r, const SimulationConfig& c) {
  nlohmann::json j;
  j["morphology"] = c.morphology.source;
  if (!c.morphology.phi_method.empty()) j["phi_method"] = c.morphology.phi_method;
  j["whiskers"] = r.n_whiskers;
  j["frames"] = r.n_frames;
  j["pitches_deg"] = nlohmann::json::array();
  for (double p : r.pitches) j["pitches_deg"].push_back(to_deg(p));
  j["mode"] = std::string(to_string(c.mode));
  j["mu"] = c.mu;
  j["solves"] = r.solves;
  j["failed_solves"] = r.failed_solves;
  j["simulation_seconds"] = r.wall_seconds;
  j["warnings"] = array_warnings(r);
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
  NanReasons why;
  for (std::size_t p = 0; p < j["per_pitch"].size(); ++p) {
    const std::string at = "/per_pitch/" + std::to_string(p);
    why.explain(at + "/first_onset_ms", kNoOnsetAtPitch);
    for (const auto& whisker : j["per_pitch"][p]["whiskers"].items())
      why.explain(at + "/whiskers/" + whisker.key() + "/onset_ms", kPushedPastWithoutContact);
  }
  why.attach(j);
  return j;
}

}  // namespace vibrissa::io
