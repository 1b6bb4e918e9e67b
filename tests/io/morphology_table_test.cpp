// User whisker-array tables (CSV, JSON): units of the column names to SI, mirroring of left rows, the default
// base radius of Belli's model, and errors that name the source, line and column.
#include <gtest/gtest.h>

#include <numbers>
#include <sstream>

#include <nlohmann/json.hpp>

#include "vibrissa/io/morphology_table.hpp"

using namespace vibrissa::array;
using namespace vibrissa::io;

namespace {
constexpr double mm = 1e-3;
double rad(double d) { return d * std::numbers::pi / 180.0; }
}  // namespace

TEST(MorphologyTable, CsvRowsInTableUnitsBecomeSiSpecs) {
  std::istringstream csv(
      "name,side,S_mm,A_per_mm,theta_deg,phi_deg,zeta_deg,base_x_mm,base_y_mm,base_z_mm,base_radius_um\n"
      "C2,right,45.2,0.00885,56.9,11,21.5,6.8,-2.9,0.5,90\n"
      "C2,left,45.2,0.00885,56.9,11,21.5,6.8,-2.9,0.5,90\n");
  const Morphology m = morphology_from_csv(csv);
  ASSERT_EQ(m.whiskers.size(), 2u);
  EXPECT_NEAR(m.whiskers[0].arc_length, 45.2 * mm, 1e-15);
  EXPECT_NEAR(m.whiskers[0].curvature, 8.85, 1e-12);
  EXPECT_NEAR(m.whiskers[0].base_radius, 90e-6, 1e-18);
  EXPECT_NEAR(m.whiskers[1].p_H_base.x(), -6.8 * mm, 1e-15);
  EXPECT_EQ(m.whiskers[1].row, 3);
  EXPECT_EQ(m.whiskers[1].column, 2);

  std::istringstream bad("name,S_mm,A_per_mm,theta_deg,phi_deg,zeta_deg,base_x_mm,base_y_mm,base_z_mm\n"
                         "C2,45.2,0.00885,nan,11,21.5,6.8,-2.9,0.5\n");
  try {
    morphology_from_csv(bad, "my.csv");
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("theta_deg"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("my.csv line 2"), std::string::npos) << e.what();
  }
  std::istringstream bad_name("name,S_mm,A_per_mm,theta_deg,phi_deg,zeta_deg,base_x_mm,base_y_mm,base_z_mm\n"
                              "Q2,45.2,0.00885,50,11,21.5,6.8,-2.9,0.5\n");
  EXPECT_THROW(morphology_from_csv(bad_name), std::invalid_argument);
}

TEST(MorphologyTable, JsonRowsWithDefaultRadiusFromBelliModel) {
  const auto j = nlohmann::json::parse(R"([{"name": "B1", "S_mm": 40, "A_per_mm": 0.01, "theta_deg": 50,
     "phi_deg": 15, "zeta_deg": 0, "base_x_mm": 7, "base_y_mm": -5, "base_z_mm": 1}])");
  const Morphology m = morphology_from_json(j);
  ASSERT_EQ(m.whiskers.size(), 1u);
  EXPECT_EQ(m.whiskers[0].row, 2);
  EXPECT_NEAR(m.whiskers[0].phi_rest, rad(15), 1e-15);
  // Default radius from Belli's model: 0.041 + 0.08 + 0.022 - 0.0039 = 0.1391 mm diameter.
  EXPECT_NEAR(m.whiskers[0].base_radius, 0.5 * 0.1391 * mm, 1e-15);
  auto missing = j;
  missing[0].erase("S_mm");
  try {
    morphology_from_json(missing, "arr.json");
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("arr.json[0].S_mm"), std::string::npos) << e.what();
  }
}
