#include "vibrissa/io/array_outputs.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <cstdio>
#include <future>
#include <map>
#include <ostream>
#include <stdexcept>

#include "../array/array_util.hpp"  // the array layer's unit helpers
#include "code_tables.hpp"
#include "csv_cells.hpp"
#include "h5_file.hpp"
#include "vibrissa/array/sweep.hpp"
#include "vibrissa/io/dynamics_case.hpp"
#include "vibrissa/io/figure_files.hpp"
#include "vibrissa/io/json_file.hpp"
#include "vibrissa/io/nan_reasons.hpp"
#include "vibrissa/io/object_json.hpp"
#include "vibrissa/objects/mesh.hpp"

namespace vibrissa::io {

using namespace vibrissa::array;

namespace {

void create_array_h5(const ArrayResult& r, const SimulationConfig& c, const std::string& path) {
  write_labelled_h5(array_data(r, c), path);
}

// One row per (pitch, whisker, frame): pitch, whisker, frame, time, then every [pitch][whisker][frame] variable
// of array.h5 under its name (vectors as name_x, name_y, name_z; codes by their names), in its SI units.
void create_array_csv(const ArrayResult& r, const SimulationConfig& c, const std::string& path,
                      const std::filesystem::path& target) {
  const LabelledData data = array_data(r, c);
  struct Column {
    const LabelledVariable* variable;
    std::size_t width, component;
    std::map<int, std::string> labels;  // code -> name of a code variable
  };
  std::vector<Column> columns;
  std::string header = "pitch,whisker,frame,time";
  for (const LabelledVariable& v : data.variables) {
    if (v.dims.size() < 3 || v.dims[0] != "pitch" || v.dims[1] != "whisker" || v.dims[2] != "time") continue;
    const std::size_t width = v.dims.size() == 4 ? 3 : 1;
    for (std::size_t i = 0; i < width; ++i) {
      columns.push_back({&v, width, i, code_labels(v.codes)});
      header += "," + v.name + (width == 3 ? std::string("_") + "xyz"[i] : std::string());
    }
  }
  std::FILE* f = std::fopen(path.c_str(), "w");
  if (!f) throw std::runtime_error("cannot write '" + target.string() + "': " + std::strerror(errno));
  std::fprintf(f, "%s\n", header.c_str());
  std::string row;
  for (std::size_t p = 0; p < r.n_pitches; ++p)
    for (std::size_t w = 0; w < r.n_whiskers; ++w)
      for (std::size_t fr = 0; fr < r.n_frames; ++fr) {
        const std::size_t k = r.index(p, w, fr);
        row = csv::cell(r.pitches[p]) + "," + r.labels[w] + "," + std::to_string(fr) + "," + csv::cell(r.times[fr]);
        for (const Column& column : columns) {
          row += ',';
          std::visit(
              [&](const auto& values) {
                const auto x = values[k * column.width + column.component];
                if constexpr (std::is_floating_point_v<std::decay_t<decltype(x)>>) {
                  row += csv::cell(x);  // empty where the value does not exist (NaN)
                } else if constexpr (std::is_integral_v<std::decay_t<decltype(x)>>) {
                  row += column.labels.empty() ? std::to_string(x) : column.labels.at(static_cast<int>(x));
                }
              },
              column.variable->values);
        }
        row += '\n';
        std::fputs(row.c_str(), f);
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
  out << "pitch,whiskers_touching,whiskers_pushed_past,contact_frames,first_onset,peak_MB,peak_MB_whisker,"
         "mean_peak_MB,mean_peak_FT,max_abs_z_error,nan_reasons\n";
  for (const PitchSummary& s : summarize_pitches(r)) {
    out << csv::cell(s.pitch) << ',' << s.whiskers_touching << ',' << s.whiskers_pushed_past << ','
        << s.contact_frames << ',' << (s.whiskers_touching ? csv::cell(s.first_onset_time) : std::string()) << ','
        << csv::cell(s.peak_MB) << ',' << s.peak_MB_whisker << ',' << csv::cell(s.mean_peak_MB) << ','
        << csv::cell(s.mean_peak_FT) << ',' << csv::cell(s.max_abs_z_error) << ','
        << (s.whiskers_touching ? std::string() : std::string("\"first_onset: ") + kNoOnsetAtPitch + "\"") << '\n';
  }
}

}  // namespace

LabelledData array_data(const ArrayResult& r, const SimulationConfig& c) {
  LabelledData d;
  const std::size_t P = r.n_pitches, W = r.n_whiskers, F = r.n_frames;
  const std::vector<std::string> pwf{"pitch", "whisker", "time"}, pwf3{"pitch", "whisker", "time", "component"};
  // Every [pitch][whisker][frame] variable is compressed when large (most frames hold zeros).
  const auto per_frame = [&](std::string name, const auto& values, std::string units, std::string long_name) {
    d.variables.push_back({.name = std::move(name), .dims = pwf, .shape = {P, W, F}, .values = std::span(values),
                           .units = std::move(units), .long_name = std::move(long_name), .compress = true});
  };
  const auto vector_per_frame = [&](std::string name, const std::vector<double>& values, std::string units,
                                    std::string long_name) {
    d.variables.push_back({.name = std::move(name), .dims = pwf3, .shape = {P, W, F, 3}, .values = std::span(values),
                           .units = std::move(units), .long_name = std::move(long_name), .compress = true});
  };
  d.variables.push_back({.name = "pitch", .dims = {"pitch"}, .shape = {P}, .values = std::span(r.pitches),
                         .units = "rad", .long_name = "head pitch added to the head's own pitch (the pitch sweep)"});
  d.variables.push_back({.name = "whisker", .dims = {"whisker"}, .shape = {W}, .values = std::span(r.labels),
                         .units = "text", .long_name = "whisker name: row, column, side (R right, L left)"});
  d.variables.push_back({.name = "time", .dims = {"time"}, .shape = {F}, .values = std::span(r.times), .units = "s",
                         .long_name = "time of the frame"});
  d.add_component_coordinate();
  std::vector<std::int8_t> side, row, column;
  for (const WhiskerSpec& s : c.morphology.whiskers) {
    side.push_back(s.side == Side::right ? 1 : -1);
    row.push_back(static_cast<std::int8_t>(s.row));
    column.push_back(static_cast<std::int8_t>(s.column));
  }
  d.add_owned({.name = "side", .dims = {"whisker"}, .shape = {W}, .units = "code", .long_name = "side of the face",
               .codes = "1 right, -1 left"},
              std::move(side));
  d.add_owned({.name = "row", .dims = {"whisker"}, .shape = {W}, .units = "code", .long_name = "row of the whisker",
               .codes = "1 A, 2 B, 3 C, 4 D, 5 E"},
              std::move(row));
  d.add_owned({.name = "column", .dims = {"whisker"}, .shape = {W}, .units = "1",
               .long_name = "column of the whisker (0: the straddler, Greek column)"},
              std::move(column));
  d.variables.push_back({.name = "state", .dims = pwf, .shape = {P, W, F}, .values = std::span(r.state),
                         .units = "code", .long_name = "contact state", .codes = contact_state_code_table(),
                         .compress = true});
  d.variables.push_back({.name = "solver_status", .dims = pwf, .shape = {P, W, F},
                         .values = std::span(r.solver_status), .units = "code",
                         .long_name = "status of the frame's solve (not_in_contact: no solve)",
                         .codes = status_code_table(), .compress = true});
  per_frame("edge_index", r.edge, "1", "index of the object edge in contact (-1: none)");
  per_frame("s_applied", r.s_applied, "m", "arc length of the contact point from the base");
  vector_per_frame("contact_point_W", r.contact_W, "m", "contact point, world frame");
  vector_per_frame("force_W", r.force_W, "N", "contact force on the whisker, world frame");
  vector_per_frame("moment_W", r.moment_W, "N m", "moment of the contact force about the base, world frame");
  vector_per_frame("force_B", r.force_B, "N", "force at the base, whisker frame (Fx axial, Fy, Fz)");
  vector_per_frame("moment_B", r.moment_B, "N m", "moment at the base, whisker frame (Mx twist, My, Mz)");
  per_frame("FT", r.FT, "N", "transverse force at the base, sqrt(Fy^2 + Fz^2)");
  per_frame("MB", r.MB, "N m", "bending moment at the base, sqrt(My^2 + Mz^2)");
  per_frame("FD", r.FD, "rad", "direction of the transverse force, atan2(Fz, Fy)");
  per_frame("MD", r.MD, "rad", "direction of the bending moment, atan2(Mz, My)");
  per_frame("normal_force", r.normal_force, "N", "contact force normal to the edge");
  per_frame("edge_force", r.edge_force, "N", "contact force along the edge direction");
  per_frame("z_edge", r.z_edge, "m", "contact position along the edge from its point");
  per_frame("z_error", r.z_error, "m", "eq. (7) bound on the contact height error of edge mode, for mu");
  vector_per_frame("base_W", r.base_W, "m", "whisker base point, world frame");
  if (!r.tip_displacement_B.empty())  // `vibrissa array --dynamics`: the base signals above are the dynamics'
    vector_per_frame("tip_displacement_B", r.tip_displacement_B, "m",
                     "dynamics: tip displacement from its rest position, whisker frame");
  for (const auto& [name, values, what] :
       {std::tuple{"theta", &r.theta, "protraction angle theta"}, std::tuple{"phi", &r.phi, "elevation angle phi"},
        std::tuple{"zeta", &r.zeta, "roll angle zeta"}})
    d.variables.push_back({.name = name, .dims = {"whisker", "time"}, .shape = {W, F}, .values = std::span(*values),
                           .units = "rad",
                           .long_name = std::string(what) + " of the whisker in the morphology source's convention"});
  const std::size_t R = r.render_frames.size(), N = r.n_nodes, E = r.n_edges;
  d.variables.push_back({.name = "render/frame", .dims = {"frame"}, .shape = {R}, .values = std::span(r.render_frames),
                         .units = "1", .long_name = "index of the rendered frame along time"});
  d.add_index_coordinate("render", "node", N, "node of the whisker chain (0: base)");
  d.add_index_coordinate("render", "edge", E, "object edge");
  d.add_index_coordinate("render", "end", 2, "end of the edge segment");
  d.variables.push_back({.name = "render/rest", .dims = {"frame", "whisker", "node", "component"},
                         .shape = {R, W, N, 3}, .values = std::span(r.rest_shapes), .units = "m",
                         .long_name = "rest (undeflected) whisker at the frame's pose, world frame", .compress = true});
  d.variables.push_back({.name = "render/deflected", .dims = {"frame", "whisker", "node", "component"},
                         .shape = {R, W, N, 3}, .values = std::span(r.deflected_shapes), .units = "m",
                         .long_name = "deflected whisker, world frame", .compress = true});
  d.variables.push_back({.name = "render/edges", .dims = {"frame", "edge", "end", "component"}, .shape = {R, E, 2, 3},
                         .values = std::span(r.render_edges), .units = "m",
                         .long_name = "object edges as segments (infinite edges clipped to 60 mm), world frame",
                         .compress = true});
  // The scene's surfaces (docs/objects.md), self-contained: each one's description (SI, its frame) and a mesh's
  // vertices and triangles; render/object_poses places them at each rendered frame.
  const std::size_t O = r.n_objects;
  d.add_index_coordinate("render", "object", O, "surface object (group objects)");
  d.add_index_coordinate("render", "pose", 12, "R_WO row by row, then p_WO");
  d.variables.push_back({.name = "render/object_poses", .dims = {"frame", "object", "pose"}, .shape = {R, O, 12},
                         .values = std::span(r.render_object_poses), .units = "m",
                         .long_name = "pose of each surface object: rotation R_WO (row by row, 1) and origin p_WO [m]"});
  std::vector<LabelledAttribute> object_attributes;
  std::size_t i = 0;
  for (const SceneObject& o : c.objects) {
    if (!o.shape) continue;
    const std::string group = "objects/" + std::to_string(i++);
    nlohmann::json description = shape_to_json(*o.shape);
    description["frame"] = std::string(to_string(o.frame));
    object_attributes.push_back({group, "description", description.dump()});
    if (const auto* mesh = dynamic_cast<const Mesh*>(o.shape.get())) {
      std::vector<double> v;
      std::vector<int> t;
      for (const auto& p : mesh->vertices()) v.insert(v.end(), {p.x(), p.y(), p.z()});
      for (const auto& f : mesh->triangles()) t.insert(t.end(), {f[0], f[1], f[2]});
      d.add_index_coordinate(group, "vertex", mesh->vertices().size(), "mesh vertex");
      d.add_index_coordinate(group, "corner", 3, "corner of the triangle");
      d.add_index_coordinate(group, "triangle", mesh->triangles().size(), "mesh triangle");
      d.add_owned({.name = group + "/vertices", .dims = {"vertex", "component"}, .shape = {mesh->vertices().size(), 3},
                   .units = "m", .long_name = "mesh vertices in the object's frame", .compress = true},
                  std::move(v));
      d.add_owned({.name = group + "/triangles", .dims = {"triangle", "corner"}, .shape = {mesh->triangles().size(), 3},
                   .units = "1", .long_name = "vertex indices of each triangle", .compress = true},
                  std::move(t));
    }
  }
  d.attributes = {{"", "layout", "[pitch][whisker][frame]"},
                  {"", "morphology", c.morphology.source},
                  {"", "mode", std::string(to_string(c.mode))},
                  {"", "mu", c.mu},
                  {"", "slopes", std::string(to_string(c.whisking.slopes))},
                  // The code tables also stay root attributes, as files before the "codes" dataset attribute had.
                  {"", "state_codes", contact_state_code_table()},
                  {"", "solver_status_codes", status_code_table()},
                  {"render", "pitch_index", static_cast<double>(c.render_pitch)}};
  d.attributes.insert(d.attributes.end(), object_attributes.begin(), object_attributes.end());
  return d;
}

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
      folder.stage("array.csv",
                   [&](const std::string& tmp) { create_array_csv(result, config, tmp, dir / "array.csv"); });
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
  if (c.dynamics) {
    // `vibrissa array --dynamics` (docs/array.md): the base signals are inertial (and drag) and contact; the
    // contact events of every whisker that touched.
    const dynamics::DynamicsProperties& d = *c.dynamics;
    nlohmann::json events = nlohmann::json::array();
    for (std::size_t p = 0; p < r.n_pitches; ++p)
      for (std::size_t w = 0; w < r.n_whiskers; ++w) {
        const auto& list = r.contact_events[p * r.n_whiskers + w];
        if (list.empty()) continue;
        events.push_back({{"pitch_deg", to_deg(r.pitches[p])}, {"whisker", r.labels[w]},
                          {"events", contact_events_json(list)}});
      }
    j["dynamics"] = {{"objects_touched", std::any_of(r.state.begin(), r.state.end(), [](std::int8_t v) { return v != 0; })},
                     {"events", std::move(events)},
                     {"density", d.density},
                     {"damping_ratio", d.damping_ratio},
                     {"air_drag", d.air_drag},
                     {"steps", r.dynamics_steps},
                     {"rejected_steps", r.dynamics_rejected_steps}};
  }
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
