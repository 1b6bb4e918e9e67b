// Trial files: round trips through CSV, HDF5 and MAT, unit conversion, and clear errors for bad files.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <numbers>
#include <sstream>
#include <string>

#include "vibrissa/io/trial_io.hpp"

namespace fs = std::filesystem;
using vibrissa::trial::Trial;

namespace {

fs::path temp_dir() {
  fs::path d = fs::temp_directory_path() / ("vibrissa_io_test_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()));
  fs::create_directories(d);
  return d;
}

Trial small_trial() {
  Trial t;
  t.source = "memory";
  for (int i = 0; i < 6; ++i) {
    t.time.push_back(0.001 * i);
    t.base_W.emplace_back(1e-4 * i, -2e-4, 3e-4);
    t.theta.push_back(0.1 * i);
    t.phi.push_back(0.05 - 0.01 * i);
    t.zeta.push_back(-0.02 * i);
    const bool c = i >= 2 && i <= 4;
    t.contact.push_back(c ? 1 : 0);
    t.contact_W.emplace_back(c ? Eigen::Vector3d(0.02, 0.01, 0.001 * i)
                               : Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN()));
    std::vector<Eigen::Vector3d> shape;
    for (int k = 0; k < (c ? 4 : 3); ++k) shape.emplace_back(0.005 * k, 0.0001 * i, 0.0);
    t.shape_W.push_back(shape);
  }
  for (int k = 0; k < 5; ++k) t.meta.rest_shape.emplace_back(0.01 * k, 0.002 * k * k, 0.0);
  vibrissa::Edge e;
  e.point = Eigen::Vector3d(0.02, 0.01, 0.0);
  t.meta.edges.push_back(e);
  t.meta.material.links = 40;
  t.meta.frame_rate = 1000.0;
  return t;
}

void expect_same(const Trial& a, const Trial& b) {
  ASSERT_EQ(a.frames(), b.frames());
  for (std::size_t i = 0; i < a.frames(); ++i) {
    EXPECT_NEAR(a.time[i], b.time[i], 1e-15);
    EXPECT_TRUE(a.base_W[i].isApprox(b.base_W[i], 1e-14)) << i;
    EXPECT_DOUBLE_EQ(a.theta[i], b.theta[i]);
    EXPECT_DOUBLE_EQ(a.phi[i], b.phi[i]);
    EXPECT_DOUBLE_EQ(a.zeta[i], b.zeta[i]);
    EXPECT_EQ(a.contact[i], b.contact[i]);
    if (a.contact[i]) {
      EXPECT_TRUE(a.contact_W[i].isApprox(b.contact_W[i], 1e-14)) << i;
    }
    ASSERT_EQ(a.shape_W[i].size(), b.shape_W[i].size()) << i;
  }
  ASSERT_EQ(a.meta.rest_shape.size(), b.meta.rest_shape.size());
  EXPECT_TRUE(a.meta.rest_shape[3].isApprox(b.meta.rest_shape[3]));
  ASSERT_EQ(a.meta.edges.size(), b.meta.edges.size());
  EXPECT_TRUE(a.meta.edges[0].point.isApprox(b.meta.edges[0].point));
  EXPECT_EQ(a.meta.material.links, b.meta.material.links);
  EXPECT_DOUBLE_EQ(a.meta.material.youngs_modulus, b.meta.material.youngs_modulus);
}

std::string error_of(const std::string& path) {
  try {
    (void)vibrissa::io::read_trial(path);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "<no error>";
}

const char* good_csv =
    "# vibrissa-trial: 1\n# units: length=mm angle=deg time=ms\n"
    "# edge: 20 10 0 0 0 1\n"
    "# rest_point: 0 0 0\n# rest_point: 10 0.2 0\n# rest_point: 20 0.8 0\n"
    "time,base_x,base_y,base_z,theta,phi,zeta,contact,contact_x,contact_y,contact_z\n"
    "0,0,0,0,10,5,1,0,,,\n"
    "1,0,0,0,11,5,1,1,20,10,1\n"
    "2,0,0,0,12,5,1,1,20,10,2\n"
    "3,0,0,0,13,5,1,0,nan,nan,nan\n";

std::string write_text(const fs::path& dir, const std::string& name, const std::string& text) {
  const fs::path p = dir / name;
  std::ofstream(p) << text;
  return p.string();
}

}  // namespace

TEST(TrialIo, RoundTripsThroughEveryFormat) {
  const Trial t = small_trial();
  for (const char* ext : {".csv", ".h5", ".mat"}) {
    const std::string path = (temp_dir() / (std::string("round") + ext)).string();
    vibrissa::io::write_trial(t, path);
    const Trial back = vibrissa::io::read_trial(path);
    SCOPED_TRACE(ext);
    expect_same(t, back);
  }
}

TEST(TrialIo, CsvConvertsDeclaredUnitsToSi) {
  const Trial t = vibrissa::io::read_trial(write_text(temp_dir(), "units.csv", good_csv));
  EXPECT_DOUBLE_EQ(t.time[2], 0.002);
  EXPECT_NEAR(t.theta[1], 11.0 * std::numbers::pi / 180.0, 1e-15);
  EXPECT_NEAR(t.contact_W[2].z(), 0.002, 1e-15);
  EXPECT_NEAR(t.meta.rest_shape[2].x(), 0.020, 1e-15);
  EXPECT_NEAR(t.meta.edges[0].point.y(), 0.010, 1e-15);
  EXPECT_EQ(t.contact[0], 0);
  EXPECT_EQ(t.contact[1], 1);
}

TEST(TrialIo, BadCsvFilesNameFileRowAndColumn) {
  const fs::path d = temp_dir();
  std::string text = good_csv;
  {  // Missing column.
    std::string m = text;
    const auto hdr = m.find("time,");
    const auto end = m.find('\n', hdr);
    m.replace(hdr, end - hdr, "time,base_x,base_y,base_z,theta,zeta,contact,contact_x,contact_y,contact_z");
    // drop the phi cell (5th) of every data row
    std::string out, line;
    std::istringstream is(m);
    while (std::getline(is, line)) {
      if (!line.empty() && std::isdigit(static_cast<unsigned char>(line[0]))) {
        std::size_t p = 0;
        for (int k = 0; k < 5; ++k) p = line.find(',', p) + 1;
        line.erase(p, line.find(',', p) - p + 1);
      }
      out += line + "\n";
    }
    const std::string msg = error_of(write_text(d, "missing.csv", out));
    EXPECT_NE(msg.find("missing.csv"), std::string::npos) << msg;
    EXPECT_NE(msg.find("row 7"), std::string::npos) << msg;
    EXPECT_NE(msg.find("'phi'"), std::string::npos) << msg;
  }
  {  // NaN in a required column: row 8 is the second data row.
    std::string m = text;
    m.replace(m.find("1,0,0,0,11"), 10, "1,0,nan,0,11");
    const std::string msg = error_of(write_text(d, "nan.csv", m));
    EXPECT_NE(msg.find("nan.csv: row 9, column 'base_y'"), std::string::npos) << msg;
  }
  {  // Non-increasing time at the third data row.
    std::string m = text;
    m.replace(m.find("\n2,0,0,0,12"), 11, "\n1,0,0,0,12");
    const std::string msg = error_of(write_text(d, "time.csv", m));
    EXPECT_NE(msg.find("time.csv: row 10, column 'time'"), std::string::npos) << msg;
    EXPECT_NE(msg.find("increase"), std::string::npos) << msg;
  }
  {  // Unknown units.
    std::string m = text;
    m.replace(m.find("length=mm"), 9, "length=in");
    const std::string msg = error_of(write_text(d, "units.csv", m));
    EXPECT_NE(msg.find("units.csv: row 2, column 'units'"), std::string::npos) << msg;
    EXPECT_NE(msg.find("'in'"), std::string::npos) << msg;
  }
  {  // No contact period.
    std::string m = text;
    m.replace(m.find("5,1,1,20,10,1"), 13, "5,1,0,20,10,1");
    m.replace(m.find("5,1,1,20,10,2"), 13, "5,1,0,20,10,2");
    const std::string msg = error_of(write_text(d, "empty.csv", m));
    EXPECT_NE(msg.find("empty.csv"), std::string::npos) << msg;
    EXPECT_NE(msg.find("'contact'"), std::string::npos) << msg;
    EXPECT_NE(msg.find("no frame is flagged"), std::string::npos) << msg;
  }
  {  // Contact frame without its tracked contact point.
    std::string m = text;
    m.replace(m.find("1,20,10,2"), 9, "1,20,,2");
    const std::string msg = error_of(write_text(d, "cp.csv", m));
    EXPECT_NE(msg.find("cp.csv: row 10, column 'contact_y'"), std::string::npos) << msg;
  }
  {  // Unparseable cell.
    std::string m = text;
    m.replace(m.find("3,0,0,0,13"), 10, "3,0,0,0,abc");
    const std::string msg = error_of(write_text(d, "parse.csv", m));
    EXPECT_NE(msg.find("parse.csv: row 11, column 'theta'"), std::string::npos) << msg;
  }
  EXPECT_NE(error_of((d / "trial.txt").string()).find("unknown trial format"), std::string::npos);
}

TEST(TrialIo, BadH5AndMatFilesNameFileRowAndColumn) {
  Trial t = small_trial();
  t.phi[3] = std::numeric_limits<double>::quiet_NaN();
  for (const char* ext : {".h5", ".mat"}) {
    const std::string path = (temp_dir() / (std::string("nanrow") + ext)).string();
    // The writers do not validate (they may save work in progress); the reader must catch it.
    vibrissa::io::write_trial(t, path);
    const std::string msg = error_of(path);
    EXPECT_NE(msg.find(std::string("nanrow") + ext + ": row 4, column 'phi'"), std::string::npos) << msg;
  }
}
