// Hostile inputs at every reader (docs/formats.md, "Limits"): each class of defect once found by fuzzing.
#include <gtest/gtest.h>

#include "../core/test_helpers.hpp"

#include <hdf5.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "io/h5_file.hpp"
#include "vibrissa/io/array_config.hpp"
#include "vibrissa/io/case_json.hpp"
#include "vibrissa/io/json_input.hpp"
#include "vibrissa/io/trial_io.hpp"

namespace fs = std::filesystem;
using nlohmann::json;
using vibrissa::io::parse_json_text;

namespace {

using vibrissa::test::invalid_message;

bool has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

fs::path temp_dir() {
  const fs::path d = fs::temp_directory_path() /
                     ("vibrissa_hardening_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()));
  fs::create_directories(d);
  return d;
}

std::string write_text(const std::string& name, const std::string& text) {
  const fs::path p = temp_dir() / name;
  std::ofstream(p, std::ios::binary) << text;
  return p.string();
}

std::string case_error(const std::string& text) {
  return invalid_message([&] { (void)vibrissa::case_from_json(parse_json_text(text, "case")); });
}

const char* kWhisker = R"("whisker":{"length":0.03,"curvature":5})";
const char* kLoad = R"("load":{"mode":"point","point":[0.02,0.001,0]})";

std::string with_options(const std::string& options) {
  return std::string("{") + kWhisker + "," + kLoad + R"(,"options":)" + options + "}";
}

}  // namespace

TEST(JsonInput, DeepNestingIsRejectedBeforeAnyRecursion) {
  const std::string deep = std::string(100'000, '[') + std::string(100'000, ']');
  EXPECT_EQ(invalid_message([&] { (void)parse_json_text(deep, "deep.json"); }),
            "deep.json: JSON nested deeper than 64 levels");
  EXPECT_NO_THROW((void)parse_json_text(std::string(64, '[') + std::string(64, ']'), "ok"));
}

TEST(JsonInput, DuplicateKeysNulAndTrailingBytesAreRejected) {
  EXPECT_TRUE(has(invalid_message([] { (void)parse_json_text(R"({"a":1,"b":{"c":1,"c":2}})", "x"); }),
                  "x: duplicate key \"c\""));
  EXPECT_NO_THROW((void)parse_json_text(R"({"c":1,"b":{"c":2}})", "x"));  // same key in different objects
  EXPECT_EQ(invalid_message([] { (void)parse_json_text(std::string("{}\0junk", 7), "x"); }),
            "x: not valid JSON: NUL byte at offset 2");
  EXPECT_TRUE(has(invalid_message([] { (void)parse_json_text("{} {}", "x"); }), "x: not valid JSON"));
}

TEST(JsonInput, TypeErrorsNameTheFieldNotTheLibrary) {
  const std::string e = case_error(with_options(R"({"find_other_roots":"yes"})"));
  EXPECT_EQ(e, "options.find_other_roots must be true or false, got \"yes\"");
  EXPECT_FALSE(has(e, "json.exception"));
}

TEST(JsonInput, IntegersAreIntegralAndInRange) {
  EXPECT_EQ(case_error(with_options(R"({"max_iterations":2.7})")),
            "options.max_iterations must be an integer in [1, 1000000], got 2.7");
  EXPECT_EQ(case_error(with_options(R"({"max_iterations":1e300})")),
            "options.max_iterations must be an integer in [1, 1000000], got 1e+300");
  EXPECT_EQ(case_error(std::string(R"({"whisker":{"length":0.03,"links":1000000000},)") + kLoad + "}"),
            "whisker.links must be an integer in [2, 200000], got 1e+09");
}

TEST(JsonInput, LongValuesAreCutInMessages) {
  const std::string big(10'000'000, 'y');
  const std::string e = case_error(std::string(R"({"whisker":{"length":0.03,"base":")") + big + R"("},)" + kLoad + "}");
  EXPECT_LT(e.size(), 400u);
  EXPECT_TRUE(has(e, "whisker.base must be \"elastic\" or \"rigid\", got \"yyy"));
  EXPECT_TRUE(has(e, "(10000002 bytes)"));
}

TEST(JsonInput, TinyDirectionIsAcceptedAsADirection) {
  const std::string text = std::string("{") + kWhisker +
                           R"(,"load":{"mode":"edge","point":[0.02,0.001,0],"direction":[1e-300,0,1e-300]}})";
  const auto c = vibrissa::case_from_json(parse_json_text(text, "case"));
  const auto& l = std::get<vibrissa::EdgeLoad>(c.load);
  EXPECT_NEAR(l.edge.direction.norm(), 1.0, 1e-15);
  EXPECT_NE(vibrissa::solve_case(c).status, vibrissa::Status::not_converged);
}

TEST(JsonInput, SolveResultCarriesPlausibilityWarnings) {
  const std::string text = R"({"whisker":{"length":40,"curvature":0.005},"load":{"mode":"force","force":0.001,"arc_length":20}})";
  const auto c = vibrissa::case_from_json(parse_json_text(text, "case"));
  const json r = vibrissa::case_result_to_json(c, vibrissa::solve_case(c));
  ASSERT_EQ(r.at("warnings").size(), 1u);
  EXPECT_TRUE(has(r.at("warnings")[0].get<std::string>(), "whisker length 40"));
}

TEST(ArrayConfigInput, SizesAndThreadsAreBounded) {
  auto config_error = [](const std::string& patch) {
    json j = vibrissa::io::default_array_config_json();
    j.merge_patch(json::parse(patch));
    return invalid_message([&] { (void)vibrissa::io::array_config_from_json(j, temp_dir()); });
  };
  EXPECT_EQ(config_error(R"({"threads":100000})"), "threads must be an integer in [0, 1024], got 1e+05");
  EXPECT_EQ(config_error(R"({"time":{"frames":10000000}})"),
            "time.frames must be an integer in [2, 1000000], got 1e+07");
  EXPECT_EQ(config_error(R"({"time":{"frames":2.5}})"), "time.frames must be an integer in [2, 1000000], got 2.5");
  EXPECT_TRUE(has(config_error(R"({"time":{"frames":1000000},"head":{"pitches_deg":[0,1,2,3,4,5,6,7,8,9,10]}})"),
                  "frames x whiskers x pitches"));
}

TEST(TrialCsvInput, MetadataIsStrict) {
  const std::string body =
      "# edge: 20 10 0 0 0 1\n# rest_point: 0 0 0\n# rest_point: 10 0.2 0\n# rest_point: 20 0.8 0\n"
      "time,base_x,base_y,base_z,theta,phi,contact\n0,0,0,0,10,5,0\n1,0,0,0,11,5,1\n2,0,0,0,12,5,0\n";
  const std::string head = "# vibrissa-trial: 1\n# units: length=mm angle=deg time=ms\n";
  auto error = [&](const std::string& name, const std::string& text) {
    const std::string path = write_text(name, text);
    return invalid_message([&] { (void)vibrissa::io::read_trial(path); });
  };
  EXPECT_NO_THROW((void)vibrissa::io::read_trial(write_text("ok.csv", head + body)));
  EXPECT_NO_THROW((void)vibrissa::io::read_trial(write_text("bom.csv", "\xEF\xBB\xBF" + head + body)));
  EXPECT_TRUE(has(error("noversion.csv", "# units: length=mm angle=deg time=ms\n" + body),
                  "noversion.csv: row 1, column 'vibrissa-trial': the version line '# vibrissa-trial: 1' is missing"));
  EXPECT_TRUE(has(error("v2.csv", "# vibrissa-trial: 2\n" + body), "unknown format version '2'"));
  EXPECT_TRUE(has(error("links.csv", head + "# links: 2.5\n" + body),
                  "links.csv: row 3, column 'links': links must be an integer in [2, 200000], got 2.5"));
  EXPECT_TRUE(has(error("hex.csv", head + "# links: 0x10\n" + body), "cannot parse '0x10' as a number"));
  EXPECT_TRUE(has(error("garbage.csv", head + "# garbage\n" + body),
                  "garbage.csv: row 3, '# garbage' is not a '# key: value' metadata line"));
  EXPECT_TRUE(has(error("units.csv", "# vibrissa-trial: 1\n# units: length=mm length=m\n" + body),
                  "unit kind 'length' is given twice"));
  EXPECT_TRUE(has(error("dup.csv", head + "# taper_ratio: 15\n# taper_ratio: 16\n" + body), "metadata key appears twice"));
  EXPECT_TRUE(has(error("rest.csv", head + "# rest_point: 0 0 0\n" + body),
                  "rest.csv: row 2, column 'rest_shape': point [0, 0, 0] repeats the previous point"));
}

TEST(TrialH5Input, UnknownDatasetsAndArrayAttributesAreRejected) {
  namespace h5 = vibrissa::io::h5;
  auto write = [](const std::string& name, bool extra_dataset, bool array_links) {
    const std::string path = (temp_dir() / name).string();
    h5::QuietErrors quiet;
    h5::Handle f = h5::create_file(path);
    h5::write_dataset(f.get(), "time", std::vector<double>{0.0, 0.001, 0.002}, {3}, {"s"});
    h5::write_dataset(f.get(), "base", std::vector<double>(9, 0.0), {3, 3}, {"m"});
    h5::write_dataset(f.get(), "theta", std::vector<double>{0.1, 0.11, 0.12}, {3}, {"rad"});
    h5::write_dataset(f.get(), "phi", std::vector<double>{0.0, 0.0, 0.0}, {3}, {"rad"});
    h5::write_dataset(f.get(), "contact", std::vector<double>{0.0, 1.0, 0.0}, {3}, {"1"});
    h5::write_dataset(f.get(), "rest_shape", std::vector<double>{0.0, 0.0, 0.0, 0.01, 0.0002, 0.0, 0.02, 0.0008, 0.0}, {3, 3}, {"m"});
    h5::write_dataset(f.get(), "edges", std::vector<double>{0.02, 0.01, 0.0, 0.0, 0.0, 1.0}, {1, 6}, {"m"});
    if (extra_dataset) h5::write_dataset(f.get(), "thetaa", std::vector<double>{0.0, 0.0, 0.0}, {3}, {"rad"});
    if (array_links) {
      const hsize_t two = 2;
      h5::Handle space(H5Screate_simple(1, &two, nullptr), H5Sclose);
      h5::Handle a(H5Acreate2(f.get(), "links", H5T_IEEE_F64LE, space.get(), H5P_DEFAULT, H5P_DEFAULT), H5Aclose);
      const double v[2] = {100, 5};
      H5Awrite(a.get(), H5T_NATIVE_DOUBLE, v);
    }
    h5::close_file(f, path);
    return path;
  };
  EXPECT_NO_THROW((void)vibrissa::io::read_trial(write("ok.h5", false, false)));
  EXPECT_TRUE(has(invalid_message([&] { (void)vibrissa::io::read_trial(write("extra.h5", true, false)); }),
                  "column 'thetaa': unknown dataset"));
  EXPECT_TRUE(has(invalid_message([&] { (void)vibrissa::io::read_trial(write("links.h5", false, true)); }),
                  "attribute 'links': expected a single value, got 2 values"));
}
