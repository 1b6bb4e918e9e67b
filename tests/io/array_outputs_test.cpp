// Array outputs: every file in one call, HDF5 laid out [pitch][whisker][frame], the configuration as run,
// and the figures of an older run removed so that a directory never mixes runs.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "fresh_dir.hpp"
#include "vibrissa/io/array_config.hpp"
#include "vibrissa/io/array_outputs.hpp"
#include "vibrissa/io/figure_files.hpp"

namespace fs = std::filesystem;
using vibrissa::test::fresh_dir;
using namespace vibrissa;
using nlohmann::json;

namespace {

json small_config() {
  json j = io::default_array_config_json();
  j["morphology"]["whiskers"] = {"C1", "C2", "D1"};
  j["head"]["pitches_deg"] = {0, 10};
  j["time"]["frames"] = 40;
  j["output"]["render_count"] = 5;
  return j;
}

}  // namespace

TEST(ArrayOutputs, EveryFileInOneCallWithTheHdf5LaidOutPitchWhiskerFrame) {
  const fs::path d = fresh_dir("layout");
  const json j = small_config();
  const array::SimulationConfig c = io::array_config_from_json(j);
  const array::ArrayResult r = array::simulate_array(c);
  io::write_array_outputs(r, c, j, d, {.csv = true});
  using Dims = std::vector<std::size_t>;
  EXPECT_EQ(io::h5_dataset_shape(d / "array.h5", "MB"), (Dims{2, 3, 40}));
  EXPECT_EQ(io::h5_dataset_shape(d / "array.h5", "force_B"), (Dims{2, 3, 40, 3}));
  EXPECT_EQ(io::h5_dataset_shape(d / "array.h5", "render/deflected"), (Dims{5, 3, 101, 3}));
  EXPECT_THROW(io::h5_dataset_shape(d / "array.h5", "nope"), std::runtime_error);
  EXPECT_THROW(io::h5_dataset_shape(d / "missing.h5", "MB"), std::runtime_error);

  std::ifstream used(d / "config.json");
  EXPECT_EQ(json::parse(used), j) << "config.json holds the configuration as run";
  std::ifstream csv(d / "array.csv");
  std::size_t lines = 0;
  for (std::string line; std::getline(csv, line);) ++lines;
  EXPECT_EQ(lines, 1u + 2u * 3u * 40u) << "header + one row per pitch, whisker and frame";
  std::ifstream pitches(d / "pitch_summary.csv");
  lines = 0;
  for (std::string line; std::getline(pitches, line);) ++lines;
  EXPECT_EQ(lines, 1u + 2u);
  std::ifstream summary(d / "summary.json");
  const json written = json::parse(summary);
  EXPECT_EQ(written.at("frames"), 40);
  EXPECT_EQ(written.at("phi_method"), "projection") << "the RatMap Toolbox's default, recorded with the run";

  std::size_t files = 0;
  for (const auto& e : fs::directory_iterator(d)) {
    EXPECT_NE(e.path().filename().string().rfind(".tmp-", 0), 0u) << e.path();
    ++files;
  }
  EXPECT_EQ(files, 5u);
}

TEST(ArrayOutputs, FiguresOfAnOlderRunAreRemovedAndOtherFilesKept) {
  const fs::path d = fresh_dir("stale");
  for (const std::string_view name : io::kArrayFigures) std::ofstream(d / name) << "old figure";
  std::ofstream(d / "notes.txt") << "mine";
  std::ofstream(d / "array.csv") << "old csv";
  json j = small_config();
  j["head"]["pitches_deg"] = {0};
  j["time"]["frames"] = 5;
  const array::SimulationConfig c = io::array_config_from_json(j);
  io::write_array_outputs(array::simulate_array(c), c, j, d);
  for (const std::string_view name : io::kArrayFigures) EXPECT_FALSE(fs::exists(d / name)) << name;
  EXPECT_TRUE(fs::exists(d / "notes.txt"));
  EXPECT_TRUE(fs::exists(d / "array.h5"));
  // Without the csv option array.csv is not written; an older one is left alone (it is not a figure).
  EXPECT_TRUE(fs::exists(d / "array.csv"));
}
