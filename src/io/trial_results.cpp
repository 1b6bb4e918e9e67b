#include "vibrissa/io/trial_results.hpp"

#include <cmath>
#include <map>
#include <numbers>
#include <stdexcept>

#include "code_tables.hpp"
#include "csv_cells.hpp"
#include "vibrissa/io/trial_io.hpp"
#include "vibrissa/trial/plausibility.hpp"
#include "vibrissa/trial/trial_run.hpp"
#include "vibrissa/io/output_folder.hpp"
#include "vibrissa/io/figure_files.hpp"
#include "vibrissa/io/json_file.hpp"
#include "vibrissa/io/nan_reasons.hpp"

namespace vibrissa::io {

using namespace vibrissa::trial;

namespace {

// One mode's columns; `what` describes the mode in the column descriptions.
void add_mode(ResultTable& t, const PipelineResult& r, Mode mode, const std::string& prefix) {
  const std::size_t n = r.frames.size();
  const std::string what = std::string(" (") + std::string(to_string(mode)) + " mode)";
  auto col = [&](const std::string& name, const char* units, const std::string& description, auto&& get) {
    std::vector<double> v(n);
    for (std::size_t i = 0; i < n; ++i) {
      const ModeFrame& m = r.frames[i].mode(mode);
      v[i] = m.ok() ? static_cast<double>(get(m)) : std::nan("");
    }
    t.numeric.push_back({prefix + name, std::move(v), units, description + what});
  };
  std::vector<std::string> status(n);
  for (std::size_t i = 0; i < n; ++i) {
    const ModeFrame& m = r.frames[i].mode(mode);
    status[i] = m.solved ? std::string(to_string(m.status)) : std::string("not_in_contact");
  }
  t.text.push_back({prefix + "status", std::move(status), "status of the frame's solve" + what});
  const char* xyz[3] = {"x", "y", "z"};
  for (int a = 0; a < 3; ++a)
    col(std::string("contact_") + xyz[a], "m", std::string("contact point, world ") + xyz[a],
        [a](const ModeFrame& m) { return m.contact_W[a]; });
  col("height", "m", "contact height along the edge", [](const ModeFrame& m) { return m.height; });
  col("s_applied", "m", "arc length of the contact point from the base",
      [](const ModeFrame& m) { return m.s_applied; });
  for (int a = 0; a < 3; ++a)
    col(std::string("F") + xyz[a] + "_world", "N", std::string("force at the base, world ") + xyz[a],
        [a](const ModeFrame& m) { return m.force_W[a]; });
  for (int a = 0; a < 3; ++a)
    col(std::string("M") + xyz[a] + "_world", "N m", std::string("moment at the base, world ") + xyz[a],
        [a](const ModeFrame& m) { return m.moment_W[a]; });
  for (int a = 0; a < 3; ++a)
    col(std::string("F") + xyz[a] + "_B", "N", std::string("force at the base, whisker frame ") + xyz[a],
        [a](const ModeFrame& m) { return m.signals_B.force[a]; });
  for (int a = 0; a < 3; ++a)
    col(std::string("M") + xyz[a] + "_B", "N m", std::string("moment at the base, whisker frame ") + xyz[a],
        [a](const ModeFrame& m) { return m.signals_B.moment[a]; });
  col("FT", "N", "transverse force at the base", [](const ModeFrame& m) { return m.signals_B.FT; });
  col("MB", "N m", "bending moment at the base", [](const ModeFrame& m) { return m.signals_B.MB; });
  col("FD", "rad", "direction of the transverse force", [](const ModeFrame& m) { return m.signals_B.FD; });
  col("MD", "rad", "direction of the bending moment", [](const ModeFrame& m) { return m.signals_B.MD; });
  col("normal_force", "N", "contact force normal to the edge", [](const ModeFrame& m) { return m.normal_force; });
  col("friction_force", "N", "contact force on the whisker along the edge",
      [](const ModeFrame& m) { return m.friction_force; });
  col("shape_error", "m", "mean distance of the solved shape from the tracked one",
      [](const ModeFrame& m) { return m.shape_error; });
  col("iterations", "1", "solver iterations", [](const ModeFrame& m) { return m.iterations; });
}

nlohmann::json num(double v) { return finite_or_null(v); }

nlohmann::json fit_json(const std::optional<LineFit>& f) {
  if (!f) return nullptr;
  return {{"slope", f->slope}, {"intercept", f->intercept}, {"r2", f->r2}, {"r2_identity", f->r2_identity},
          {"points", f->count}};
}

nlohmann::json friction_json(const FrictionAnalysis& a) {
  return {{"median", num(a.median)}, {"kind", a.kind.empty() ? nlohmann::json(nullptr) : nlohmann::json(a.kind)},
          {"slip_fraction", num(a.slip_fraction)}, {"frames_slipping", a.frames_slipping},
          {"median_slipping", num(a.median_slipping)}, {"warnings", a.warnings},
          {"mean", num(a.mean)}, {"sd", num(a.sd)}, {"min", num(a.min)},
          {"max", num(a.max)}, {"frames_used", a.frames_used}, {"outliers_low_normal_force", a.outliers},
          {"histogram_edges", a.histogram_edges}, {"histogram_counts", a.histogram_counts},
          {"normal_force_bins_N", a.fn_bin_center}, {"mu_mean_per_bin", [&] {
             nlohmann::json j = nlohmann::json::array();
             for (double v : a.fn_bin_mean) j.push_back(num(v));
             return j;
           }()},
          {"mu_sd_per_bin", [&] {
             nlohmann::json j = nlohmann::json::array();
             for (double v : a.fn_bin_sd) j.push_back(num(v));
             return j;
           }()},
          {"count_per_bin", a.fn_bin_count}};
}

nlohmann::json ranges_json(const DirectionRanges& d) {
  return {{"mean_FD_range_deg", num(d.mean_fd_range_deg)}, {"mean_MD_range_deg", num(d.mean_md_range_deg)},
          {"FD_range_per_whisk_deg", d.fd_range_deg}, {"MD_range_per_whisk_deg", d.md_range_deg}};
}

std::string count_text(std::size_t n, const char* what) {
  return std::to_string(n) + " " + what + (n == 1 ? "" : "s");
}

std::string joined(const std::vector<std::string>& lines) {
  std::string out;
  for (const std::string& l : lines) out += (out.empty() ? "" : "; ") + l;
  return out;
}

/// Why a mode's results are absent: it was not run (and why not), or it never converged.
std::string mode_missing(const PipelineResult& r, Mode m) {
  switch (m) {
    case Mode::contact_point:
      if (!r.has_contact_point_mode)
        return r.pre.trial.has_contact_point() ? "contact-point mode was not run"
                                               : "contact-point mode was not run: the trial has no tracked contact point";
      break;
    case Mode::edge:
      if (!r.has_edge_mode) return "edge mode was not run";
      break;
    case Mode::frictional_edge:
      if (!r.has_frictional_mode) return "frictional edge mode was not run (it needs a friction coefficient: --mu)";
      break;
  }
  return "";
}

void explain_friction(const std::string& at, const FrictionAnalysis& f, NanReasons& why) {
  // analyse_friction's own warnings say why the whole block is empty (e.g. no frame in reach of the object).
  if (f.frames_used == 0) {
    why.explain(at, joined(f.warnings));
    return;
  }
  why.explain(at + "/median_slipping", "no used frame slips along the edge (|d height / dt| above the slip speed)");
  why.explain(at + "/sd", "a standard deviation needs 2 or more used frames, got " + count_text(f.frames_used, "frame"));
  for (std::size_t b = 0; b < f.fn_bin_count.size(); ++b) {
    const std::string k = std::to_string(b);
    const std::size_t c = f.fn_bin_count[b];
    why.explain(at + "/mu_mean_per_bin/" + k, "no frame in this normal-force bin");
    why.explain(at + "/mu_sd_per_bin/" + k, c == 0 ? "no frame in this normal-force bin"
                                                  : "a standard deviation needs 2 or more frames in the bin, got 1");
  }
}

void explain_nulls(const PipelineResult& r, const TrialAnalysis& a, NanReasons& why) {
  if (a.friction) explain_friction("/friction", *a.friction, why);
  if (a.friction_frictional) explain_friction("/friction_frictional_mode", *a.friction_frictional, why);

  const std::pair<Mode, const char*> modes[] = {
      {Mode::contact_point, "contact_point"}, {Mode::edge, "edge"}, {Mode::frictional_edge, "frictional_edge"}};
  for (const auto& [m, name] : modes) {
    const std::string missing = mode_missing(r, m);
    why.explain(std::string("/force_directions/") + name,
                !missing.empty() ? missing
                                 : "no contact period has 2 or more converged frames of this mode away from its "
                                   "first and last two frames");
    why.explain(std::string("/shape_error_mean_m/") + name,
                !missing.empty()                  ? missing
                : !r.pre.trial.has_shapes()       ? "the trial has no tracked whisker shapes"
                                                  : "no converged frame of this mode has a tracked shape");
  }
  const std::string cp = mode_missing(r, Mode::contact_point), ed = mode_missing(r, Mode::edge);
  const std::string both = !cp.empty() ? cp : !ed.empty() ? ed
                                           : "no frame away from the period edges in which both contact-point and "
                                             "edge modes converged";
  why.explain("/force_directions/mean_FD_offset_cp_minus_edge_deg", both);
  why.explain("/force_directions/mean_MD_offset_cp_minus_edge_deg", both);

  if (!r.pre.trial.has_contact_point()) {
    why.explain("/kinematic_prediction/fit", "the trial has no tracked contact point to compare with");
  } else {
    std::size_t crossing = 0;
    for (std::size_t i = 0; i < a.kinematic.predicted.size(); ++i)
      crossing += std::isfinite(a.kinematic.predicted[i]) && std::isfinite(a.kinematic.measured[i]);
    why.explain("/kinematic_prediction/fit",
                crossing < 3 ? "a fit needs 3 or more contact frames in which the rest whisker crosses the edge "
                               "in the view, got " + count_text(crossing, "frame")
                             : "the measured heights do not vary, so no line can be fitted");
  }

  // r² of a fit whose predicted values do not vary is 0/0.
  for (const char* fit : {"/roll_fit", "/kinematic_prediction/fit", "/z_error/eq6/all", "/z_error/eq6/without_iqr_outliers",
                          "/z_error/eq7/all", "/z_error/eq7/without_iqr_outliers"}) {
    why.explain(std::string(fit) + "/r2", "the fitted values do not vary, so r² is 0/0");
    why.explain(std::string(fit) + "/r2_identity", "the fitted values do not vary, so r² is 0/0");
  }
  if (a.z_error) {
    const ZErrorAnalysis& z = *a.z_error;
    std::size_t pairs = 0, measured = 0;
    for (std::size_t i = 0; i < z.used.size(); ++i) {
      pairs += z.used[i];
      measured += std::isfinite(z.measured[i]);
    }
    const std::string no_cone = "the whisker is not tapered (taper ratio 1): eq. (5) has no cone length, so eqs. "
                                "(6) and (7) predict nothing";
    const std::string none_measured = "no contact frame in which both contact-point and edge modes converged";
    why.explain("/z_error/cone_length_m", no_cone);
    for (const char* eq : {"/z_error/eq6", "/z_error/eq7"}) {
      const std::string e = eq;
      if (!std::isfinite(z.cone_length)) {
        why.explain(e, no_cone);
        continue;
      }
      why.explain(e + "/all", pairs < 3 ? "a fit needs 3 or more frames with measured and predicted z error away "
                                          "from the period edges, got " + count_text(pairs, "frame")
                                        : "the measured z errors do not vary, so no line can be fitted");
      why.explain(e + "/without_iqr_outliers",
                  pairs < 3 ? "a fit needs 3 or more frames with measured and predicted z error away from the "
                              "period edges, got " + count_text(pairs, "frame")
                            : "fewer than 3 frames are left after removing the IQR outliers, or they do not vary");
    }
    why.explain("/z_error/measured_range_m", measured == 0 ? none_measured
                                                            : "no frame away from the period edges with a predicted "
                                                              "z error");
    why.explain("/z_error/eq7_range_m", !std::isfinite(z.cone_length) ? no_cone
                                        : measured == 0              ? none_measured
                                                                     : "no frame away from the period edges with a "
                                                                       "predicted z error");
    why.explain("/z_error/mean_abs_height_difference_m", none_measured);
    why.explain("/z_error/max_abs_height_difference_m", none_measured);
  }
}

}  // namespace

ResultTable result_table(const PipelineResult& r, const TrialAnalysis& a) {
  ResultTable t;
  const std::size_t n = r.frames.size();
  const Trial& tr = r.pre.trial;
  std::vector<double> time(n), contact(n), period(n), edge(n);
  for (std::size_t i = 0; i < n; ++i) {
    time[i] = r.frames[i].time;
    contact[i] = r.frames[i].contact;
    period[i] = r.frames[i].period;
    edge[i] = r.frames[i].period_edge;
  }
  t.numeric = {{"time", time, "s", "time of the frame"},
               {"contact", contact, "1", "1 in a contact frame, else 0"},
               {"period", period, "1", "contact period of the frame, from 0 (-1: none)"},
               {"period_edge", edge, "1", "1 in the first and last two frames of a contact period"},
               {"theta", tr.theta, "rad", "protraction angle used (filtered)"},
               {"phi", tr.phi, "rad", "elevation angle used (filtered)"},
               {"zeta", tr.zeta, "rad", "roll angle used (filtered; fitted during contact)"}};
  if (r.has_contact_point_mode) add_mode(t, r, Mode::contact_point, "cp_");
  if (r.has_edge_mode) add_mode(t, r, Mode::edge, "edge_");
  if (r.has_frictional_mode) add_mode(t, r, Mode::frictional_edge, "fric_");
  if (a.friction) {
    t.numeric.push_back({"mu", a.friction->mu, "1", "|friction force| / normal force (contact-point mode)"});
    std::vector<double> o(n), used(n);
    for (std::size_t i = 0; i < n; ++i) {
      o[i] = a.friction->outlier[i];
      used[i] = a.friction->used[i];
    }
    t.numeric.push_back({"mu_outlier", o, "1", "1 where the normal force is below 0.1 mN"});
    t.numeric.push_back({"mu_used", used, "1", "1 where mu enters the friction statistics"});
  }
  if (a.friction_frictional)
    t.numeric.push_back({"fric_mu", a.friction_frictional->mu, "1", "|friction force| / normal force (frictional edge mode)"});
  if (a.z_error) {
    t.numeric.push_back({"z_error", a.z_error->measured, "m", "measured z error, z_edge - z_contact_point"});
    t.numeric.push_back({"z_error_eq6", a.z_error->eq6, "m", "z error predicted by eq. (6)"});
    t.numeric.push_back({"z_error_eq7", a.z_error->eq7, "m", "z error predicted by eq. (7)"});
  }
  t.numeric.push_back({"kinematic_height", a.kinematic.predicted, "m", "contact height predicted by kinematics"});
  t.numeric.push_back({"tracked_height", a.kinematic.measured, "m", "tracked contact height"});
  return t;
}

namespace {

void print_result_table_csv(const ResultTable& t, std::ostream& out) {
  bool first = true;
  for (const auto& c : t.numeric) out << (first ? "" : ",") << c.name, first = false;
  for (const auto& c : t.text) out << "," << c.name;
  out << "\n";
  const std::size_t n = t.numeric.empty() ? 0 : t.numeric.front().values.size();
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t k = 0; k < t.numeric.size(); ++k) {
      if (k) out << ',';
      const double v = t.numeric[k].values[i];
      out << (std::isnan(v) ? std::string("nan") : csv::cell(v));
    }
    for (const auto& c : t.text) out << ',' << c.values[i];
    out << '\n';
  }
}

void create_result_table_h5(const ResultTable& t, const std::string& path) {
  write_labelled_h5(trial_results_data(t), path);
}

}  // namespace

LabelledData trial_results_data(const ResultTable& table) {
  LabelledData d;
  const std::size_t n = table.numeric.empty() ? 0 : table.numeric.front().values.size();
  for (const NumericColumn& c : table.numeric)
    d.variables.push_back({.name = c.name, .dims = {"time"}, .shape = {n}, .values = std::span(c.values),
                           .units = c.units, .long_name = c.long_name});
  // Status columns as int8 codes with their code table (text in frames.csv and in Python's columns).
  for (const TextColumn& c : table.text) {
    std::vector<std::int8_t> codes;
    codes.reserve(c.values.size());
    for (const auto& s : c.values) codes.push_back(status_code(s, c.name));
    d.add_owned({.name = c.name, .dims = {"time"}, .shape = {n}, .units = "code", .long_name = c.long_name,
                 .codes = status_code_table()},
                std::move(codes));
  }
  d.attributes = {{"", "format", "vibrissa-trial-results"}, {"", "format_version", 2.0}};
  return d;
}

void write_trial_outputs(const ResultTable& table, const nlohmann::json& summary, const std::filesystem::path& dir) {
  OutputFolder folder(dir, kTrialFigures);  // one set: frames.csv, frames.h5, summary.json (figures/ removed)
  folder.stage_text("frames.csv", [&](std::ostream& out) { print_result_table_csv(table, out); });
  folder.stage("frames.h5", [&](const std::string& tmp) { create_result_table_h5(table, tmp); });
  stage_json_file(folder, "summary.json", summary);
  folder.commit();
}

nlohmann::json summary_json(const PipelineResult& r, const TrialAnalysis& a) {
  using nlohmann::json;
  const Trial& t = r.pre.trial;
  json j;
  j["source"] = t.source;
  // The units the trial file declared; its data were converted to SI on reading (every output is SI).
  const Units& u = t.meta.declared_units;
  j["input_units"] = {{"length", u.length}, {"angle", u.angle}, {"time", u.time}};
  j["frames"] = t.frames();
  j["sample_rate_Hz"] = r.pre.sample_rate_hz;
  j["contact_periods"] = r.pre.periods.size();
  j["contact_frames"] = contact_frame_count(t);
  j["zeta_source"] = r.pre.zeta_source;
  if (r.pre.roll)
    j["roll_fit"] = {{"slope", r.pre.roll->slope}, {"intercept_rad", r.pre.roll->intercept}, {"r2", r.pre.roll->r2},
                     {"frames", r.pre.roll->frames}};
  j["modes"] = {{"contact_point", r.has_contact_point_mode}, {"edge", r.has_edge_mode},
                {"frictional_edge", r.has_frictional_mode}};
  if (r.mu) j["frictional_mu"] = *r.mu;
  json status = json::object();
  for (Mode m : {Mode::contact_point, Mode::edge, Mode::frictional_edge}) {
    std::map<std::string, std::size_t> counts;
    for (const auto& f : r.frames)
      if (f.mode(m).solved) ++counts[std::string(to_string(f.mode(m).status))];
    if (!counts.empty()) status[std::string(to_string(m))] = counts;
  }
  j["status_counts"] = status;
  j["whisker_length_m"] = a.whisker_length;
  if (a.friction) j["friction"] = friction_json(*a.friction);
  if (a.friction_frictional) j["friction_frictional_mode"] = friction_json(*a.friction_frictional);
  j["force_directions"] = {{"contact_point", ranges_json(a.directions.contact_point)},
                           {"edge", ranges_json(a.directions.edge)},
                           {"frictional_edge", ranges_json(a.directions.frictional)},
                           {"mean_FD_offset_cp_minus_edge_deg", num(a.directions.mean_fd_offset_deg)},
                           {"mean_MD_offset_cp_minus_edge_deg", num(a.directions.mean_md_offset_deg)}};
  if (a.z_error) {
    const auto& z = *a.z_error;
    auto fits = [](const ZErrorFit& f) {
      return json{{"all", fit_json(f.all)}, {"without_iqr_outliers", fit_json(f.without_outliers)}, {"outliers", f.outliers}};
    };
    j["z_error"] = {{"definition", "z_edge - z_contact_point (height along the edge) [m]; fits: x = measured, y = predicted"},
                    {"cone_length_m", z.cone_length},
                    {"mu_eq7", z.mu_eq7},
                    {"eq6", fits(z.fit_eq6)},
                    {"eq7", fits(z.fit_eq7)},
                    {"measured_range_m", {num(z.measured_min), num(z.measured_max)}},
                    {"eq7_range_m", {num(z.eq7_min), num(z.eq7_max)}},
                    {"mean_abs_height_difference_m", num(z.mean_abs_height_difference)},
                    {"max_abs_height_difference_m", num(z.max_abs_height_difference)}};
  }
  j["kinematic_prediction"] = {{"fit", fit_json(a.kinematic.fit)},
                               {"view_direction_W", {r.view_direction_W.x(), r.view_direction_W.y(), r.view_direction_W.z()}}};
  j["shape_error_mean_m"] = {{"contact_point", num(a.shape_error.contact_point_mean)},
                             {"edge", num(a.shape_error.edge_mean)},
                             {"frictional_edge", num(a.shape_error.frictional_mean)}};
  j["warnings"] = trial::trial_warnings(t);  // likely unit slips of the input (trial/plausibility.hpp)
  NanReasons why;
  explain_nulls(r, a, why);
  why.attach(j);
  return j;
}

}  // namespace vibrissa::io
