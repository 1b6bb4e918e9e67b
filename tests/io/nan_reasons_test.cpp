// Every null of a summary comes with its reason (docs/formats.md, "Nulls and their reasons"): trial and array
// summary.json, pitch_summary.csv.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>

#include "fresh_dir.hpp"
#include "vibrissa/io/array_config.hpp"
#include "vibrissa/io/array_outputs.hpp"
#include "vibrissa/io/nan_reasons.hpp"
#include "vibrissa/io/trial_results.hpp"
#include "vibrissa/trial/synth.hpp"
#include "vibrissa/trial/trial_run.hpp"

using namespace vibrissa;
using nlohmann::json;

namespace {

/// The nulls of `summary` (without its own "nan_reasons") and the pointers it gives reasons for must be the
/// same set, and none may be the fallback.
void expect_every_null_explained(const json& summary) {
  ASSERT_TRUE(summary.contains("nan_reasons"));
  json body = summary;
  body.erase("nan_reasons");
  const std::vector<std::string> nulls = io::null_pointers(body);
  std::set<std::string> reasons;
  for (const auto& item : summary.at("nan_reasons").items()) {
    reasons.insert(item.key());
    EXPECT_NE(item.value().get<std::string>(), io::NanReasons::kUnexplained) << item.key();
    EXPECT_FALSE(item.value().get<std::string>().empty()) << item.key();
  }
  EXPECT_EQ(reasons, std::set<std::string>(nulls.begin(), nulls.end()));
}

json trial_summary(const trial::SynthOptions& so, const trial::TrialFlags& flags = {}) {
  const trial::Trial t = trial::synthesize_trial(so);
  const trial::TrialRun run = trial::run_trial(t, trial::run_options(flags));
  return io::summary_json(run.result, run.analysis);
}

}  // namespace

TEST(NanReasons, TheMostSpecificReasonWinsAndPointersAreEscaped) {
  json j = {{"a", {{"b", nullptr}, {"c", std::nan("")}, {"d", 1.0}}}, {"x/y", nullptr}, {"list", {1.0, nullptr}}};
  io::NanReasons why;
  why.explain("/a", "section");
  why.explain("/a/c", "field");
  why.explain("/a/d", "not null: dropped");
  why.explain("/x~1y", "escaped");
  why.attach(j);
  EXPECT_EQ(j["nan_reasons"],
            (json{{"/a/b", "section"}, {"/a/c", "field"}, {"/x~1y", "escaped"}, {"/list/1", io::NanReasons::kUnexplained}}));
}

TEST(NanReasons, AFarPegGivesTheReasonForTheNaNMedian) {
  trial::SynthOptions so;
  so.duration = 0.5;
  so.peg_distance = 0.0345;  // the 35 mm whisker barely reaches it: no usable contact frame
  const json s = trial_summary(so);
  ASSERT_TRUE(s.at("friction").at("median").is_null());
  const std::string why = s.at("nan_reasons").at("/friction/median");
  EXPECT_NE(why.find("no contact frame with F_N"), std::string::npos) << why;
  EXPECT_NE(why.find("in reach"), std::string::npos) << why;
  EXPECT_NE(s.at("nan_reasons").value("/kinematic_prediction/fit", "").find("a fit needs 3 or more"), std::string::npos);
  expect_every_null_explained(s);
}

TEST(NanReasons, ANormalTrialExplainsOnlyWhatItDidNotRun) {
  trial::SynthOptions so;
  so.duration = 0.5;
  const json s = trial_summary(so);
  EXPECT_TRUE(s.at("friction").at("median").is_number());
  EXPECT_FALSE(s.at("nan_reasons").contains("/friction/median"));
  EXPECT_EQ(s.at("nan_reasons").value("/shape_error_mean_m/edge", ""), "the trial has no tracked whisker shapes");
  EXPECT_NE(s.at("nan_reasons").value("/force_directions/frictional_edge/mean_FD_range_deg", "").find("--mu"),
            std::string::npos);
  expect_every_null_explained(s);
  // With --mu the frictional mode runs: its directions are no longer null.
  trial::TrialFlags flags;
  flags.mu = 0.48;
  const json m = trial_summary(so, flags);
  EXPECT_FALSE(m.at("nan_reasons").contains("/force_directions/frictional_edge/mean_FD_range_deg"));
  expect_every_null_explained(m);
}

TEST(NanReasons, AnUntaperedWhiskerExplainsTheMissingCone) {
  trial::SynthOptions so;
  so.duration = 0.3;
  trial::Trial t = trial::synthesize_trial(so);
  t.meta.material.taper_ratio = 1.0;
  const trial::TrialRun run = trial::run_trial(t, trial::run_options({}));
  const json s = io::summary_json(run.result, run.analysis);
  EXPECT_NE(s.at("nan_reasons").value("/z_error/eq6/all", "").find("not tapered"), std::string::npos);
  expect_every_null_explained(s);
}

TEST(NanReasons, ArraySummariesExplainAPitchAtWhichNothingTouches) {
  json j = io::default_array_config_json();
  j["morphology"]["whiskers"] = {"C1", "C2"};
  j["time"]["frames"] = 40;
  j["output"]["render_count"] = 0;
  j["head"]["pitches_deg"] = {0};
  const array::SimulationConfig near = io::array_config_from_json(j);
  const json normal = io::array_summary_json(array::simulate_array(near), near);
  EXPECT_EQ(normal.at("nan_reasons"), json::object());
  expect_every_null_explained(normal);

  j["objects"][0]["point_mm"] = {200, -8, -3};  // out of reach
  const array::SimulationConfig far = io::array_config_from_json(j);
  const array::ArrayResult r = array::simulate_array(far);
  const json s = io::array_summary_json(r, far);
  EXPECT_EQ(s.at("nan_reasons").at("/per_pitch/0/first_onset_ms"), "no whisker touches an object at this head pitch");
  expect_every_null_explained(s);

  const std::filesystem::path d = vibrissa::test::fresh_dir("nan_reasons");
  io::write_array_outputs(r, far, j, d, {});
  std::ifstream csv(d / "pitch_summary.csv");
  std::string header, row;
  std::getline(csv, header);
  std::getline(csv, row);
  EXPECT_TRUE(header.ends_with(",nan_reasons")) << header;
  EXPECT_TRUE(row.ends_with(",\"first_onset: no whisker touches an object at this head pitch\"")) << row;
}
