// Input checks vs invariants (core/checks.hpp), the model's geometry checks and plausibility warnings.
#include <gtest/gtest.h>

#include "test_helpers.hpp"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>

#include "vibrissa/core/checks.hpp"
#include "vibrissa/core/plausibility.hpp"
#include "vibrissa/core/whisker.hpp"

using namespace vibrissa;

namespace {
using vibrissa::test::invalid_message;
}  // namespace

TEST(Checks, FormatValueIsShortestRoundTrip) {
  EXPECT_EQ(format_value(0.03), "0.03");
  EXPECT_EQ(format_value(0.0300000001), "0.0300000001");  // never prints like the bound 0.03
  EXPECT_EQ(format_value(1e-300), "1e-300");
  EXPECT_EQ(format_value(1e300), "1e+300");
  EXPECT_EQ(format_value(std::numeric_limits<double>::quiet_NaN()), "nan");
  EXPECT_EQ(format_value(-std::numeric_limits<double>::infinity()), "-inf");
  EXPECT_EQ(format_value(Eigen::Vector3d(1, -2.5, 0)), "[1, -2.5, 0]");
}

TEST(Checks, QuoteTextCutsLongInputAndHidesControlBytes) {
  const std::string long_text(10'000'000, 'x');
  const std::string q = quote_text(long_text);
  EXPECT_EQ(q, std::string(limits::max_quoted_chars, 'x') + "... (10000000 bytes)");
  EXPECT_EQ(quote_text(std::string("a\0b\n", 4)), "a?b?");
}

TEST(Checks, IntegersMustBeIntegralAndInRange) {
  EXPECT_EQ(require_integer(7.0, 1, 10, "n"), 7);
  EXPECT_EQ(invalid_message([] { require_integer(2.7, 1, 10, "options.max_iterations"); }),
            "options.max_iterations must be an integer in [1, 10], got 2.7");
  EXPECT_EQ(invalid_message([] { require_integer(1e300, 1, 10, "n"); }), "n must be an integer in [1, 10], got 1e+300");
  EXPECT_EQ(invalid_message([] { require_integer(std::nan(""), 1, 10, "n"); }), "n must be an integer in [1, 10], got nan");
}

TEST(Checks, TinyDirectionsNormaliseWithoutUnderflow) {
  const Eigen::Vector3d d = unit_direction(Eigen::Vector3d(1e-300, 0, 0), "load.direction");
  EXPECT_EQ(d, Eigen::Vector3d(1, 0, 0));
  EXPECT_EQ(invalid_message([] { unit_direction(Eigen::Vector3d::Zero(), "load.direction"); }),
            "load.direction must be non-zero, got [0, 0, 0]");
  EXPECT_NE(invalid_message([] { require_normalizable(Eigen::Vector3d(1e-300, 0, 0), "edge.direction"); })
                .find("edge.direction must be non-zero with a length between 1e-150 and 1e150"),
            std::string::npos);
}

TEST(Checks, InvariantsAreNotInputErrors) {
  bool internal = false;
  try {
    VIBRISSA_DEMAND(1 + 1 == 3);
  } catch (const std::invalid_argument&) {
    FAIL() << "an invariant must not look like bad input";
  } catch (const InternalError& e) {
    internal = std::string(e.what()).find("1 + 1 == 3") != std::string::npos;
  }
  EXPECT_TRUE(internal);
}

TEST(Checks, HugeRestPointsAreRejectedBeforeTheModelIsBuilt) {
  // Once: a NaN arc length made locate() return link N and deflect() write past the arrays.
  const std::vector<Eigen::Vector3d> pts = {{0, 0, 0}, {1e300, 1e299, 0}, {2e300, 2e299, 0}};
  const std::string message = invalid_message([&] { (void)Whisker::from_points(pts, WhiskerProperties{}); });
  EXPECT_NE(message.find("whisker.points"), std::string::npos) << message;
}

TEST(Checks, LocateNeverIndexesPastTheLinksForNaN) {
  const Whisker w = Whisker::from_parabola(0.03, 5.0, WhiskerProperties{});
  int k = -1;
  double h = 0.0;
  w.locate(std::nan(""), k, h);
  EXPECT_EQ(k, 0);
}

TEST(Checks, ModelRangesNameTheField) {
  WhiskerProperties p;
  p.links = limits::max_links + 1;
  EXPECT_EQ(invalid_message([&] { validate(p); }), "whisker.links must be an integer in [2, 200000], got 200001");
  p = {};
  p.youngs_modulus = 1e300;
  EXPECT_EQ(invalid_message([&] { validate(p); }), "whisker.youngs_modulus must lie in [1, 1e+15], got 1e+300");
  EXPECT_EQ(invalid_message([] { (void)Whisker::from_parabola(1e6, 0.0, WhiskerProperties{}); }),
            "whisker.length must lie in [1e-06, 1000], got 1e+06");
}

TEST(Plausibility, WarnsAboutLikelyUnitSlips) {
  EXPECT_TRUE(plausibility_warnings(Whisker::from_parabola(0.03, 5.0, WhiskerProperties{})).empty());
  const auto long_one = plausibility_warnings(Whisker::from_parabola(40.0, 0.005, WhiskerProperties{}));
  ASSERT_EQ(long_one.size(), 1u);
  EXPECT_NE(long_one[0].find("whisker length 40.0000000000000"), std::string::npos);
  WhiskerProperties p;
  p.base_radius = 2e-3;
  p.youngs_modulus = 3.3;
  const auto w = plausibility_warnings(Whisker::from_parabola(0.03, 5.0, p));
  ASSERT_EQ(w.size(), 2u);
  EXPECT_NE(w[0].find("base radius 0.002 m"), std::string::npos);
  EXPECT_NE(w[1].find("Young's modulus 3.3 Pa"), std::string::npos);
}

namespace {
bool has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }
}  // namespace

TEST(Plausibility, LengthWarningsSuggestTheUnitThatFits) {
  EXPECT_FALSE(length_warning("whisker length", 0.035));
  // Whisker.from_parabola(40, 12): mm given as metres.
  const auto metres = length_warning("whisker length", 40.0);
  ASSERT_TRUE(metres);
  EXPECT_TRUE(has(*metres, "whisker length 40 m")) << *metres;
  EXPECT_TRUE(has(*metres, "did you mean 40 mm (a length in mm given as metres)?")) << *metres;
  // A trial in metres declared length=mm: a 35 um whisker.
  const auto micro = length_warning("whisker length", 35e-6);
  ASSERT_TRUE(micro);
  EXPECT_TRUE(has(*micro, "(35 um)")) << *micro;
  EXPECT_TRUE(has(*micro, "did you mean 35 mm (metres given or declared as mm)?")) << *micro;
  EXPECT_TRUE(has(*length_warning("whisker length", 30000.0), "did you mean 30 mm (a length in um given as metres)"));
}

TEST(Plausibility, PoseForceAngleSeriesAndReach) {
  // "theta": 10 in a pose: degrees given as radians.
  const auto pose = pose_warnings(Pose{{0, 0, 0}, 10.0, 0.2, -4.0}, "whisker.pose");
  ASSERT_EQ(pose.size(), 2U);
  EXPECT_TRUE(has(pose[0], "whisker.pose.theta 10 rad (573 deg) is beyond +-pi: did you mean 10 deg")) << pose[0];
  EXPECT_TRUE(has(pose[1], "whisker.pose.zeta -4 rad")) << pose[1];
  EXPECT_TRUE(pose_warnings(Pose{{0, 0, 0}, 3.0, -1.5, 3.1}, "pose").empty());

  EXPECT_FALSE(force_warning("load.force", 2e-3));
  EXPECT_TRUE(has(*force_warning("load.force", 5.0), "load.force 5 N is above the plausible 0.1 N"));

  // Radians declared as degrees: whisking over 0.2..1.9 rad read as 0.2..1.9 deg.
  std::vector<double> theta;
  for (int i = 0; i <= 50; ++i) theta.push_back((0.2 + 1.7 * i / 50.0) * 3.141592653589793 / 180.0);
  const auto rad_as_deg = angle_series_warning("theta", theta, true);
  ASSERT_TRUE(rad_as_deg);
  EXPECT_TRUE(has(*rad_as_deg, "theta stays within +-1.9 deg although the file declares angle=deg")) << *rad_as_deg;
  EXPECT_FALSE(angle_series_warning("theta", theta, false));  // small angles declared in radians are possible
  for (double& v : theta) v *= 180.0 / 3.141592653589793 * 57.29577951308232;  // degrees declared as radians
  EXPECT_TRUE(has(*angle_series_warning("theta", theta, false), "degrees declared as radians (angle=rad)?"));
  EXPECT_FALSE(angle_series_warning("theta", {0.1, std::nan(""), 1.2}, true));  // 69 deg: a real series

  // Python's peg=[16.6, 11.2, 0] (mm given as metres) next to a 30 mm whisker based near the origin.
  const Eigen::Vector3d base(0.001, 0.002, 0.0), up = Eigen::Vector3d::UnitZ();
  const auto far = reach_warning("edge 1 (peg)", {16.6, 11.2, 0.0}, up, base, 0.03);
  ASSERT_TRUE(far);
  EXPECT_TRUE(has(*far, "edge 1 (peg) passes 20.02 m from the whisker base, beyond the reach of a 30 mm whisker"))
      << *far;
  EXPECT_TRUE(has(*far, "positions in mm given as metres?")) << *far;
  EXPECT_FALSE(reach_warning("edge 1 (peg)", {0.0166, 0.0112, 5.0}, up, base, 0.03));  // the line, not the point
  EXPECT_TRUE(reach_warning("load.point", {0.0166, 0.0112, 5.0}, Eigen::Vector3d::Zero(), base, 0.03));
}

// Issue 23: one rule for input numbers. Subnormals (1e-310, 5e-324) are rejected like nan and inf.
TEST(Checks, InputNumbersAreFiniteAndZeroOrNormal) {
  EXPECT_TRUE(is_input_number(0.0));
  EXPECT_TRUE(is_input_number(-0.0));
  EXPECT_TRUE(is_input_number(std::numeric_limits<double>::min()));
  EXPECT_TRUE(is_input_number(-std::numeric_limits<double>::max()));
  for (double bad : {1e-310, -5e-324, std::numeric_limits<double>::denorm_min(), std::nan(""),
                     std::numeric_limits<double>::infinity()})
    EXPECT_FALSE(is_input_number(bad)) << bad;
  EXPECT_EQ(invalid_message([] { require_positive(1e-310, "whisker.base_stiffness"); }),
            "whisker.base_stiffness must be a positive finite number of at least 2.2250738585072014e-308, got 1e-310");
  EXPECT_EQ(invalid_message([] { require_finite(Eigen::Vector3d(0.02, 0.0, 1e-310), "load.point"); }),
            "load.point must be finite, and 0 or at least 2.2250738585072014e-308 in magnitude (no subnormal numbers) "
            "in every component, got [0.02, 0, 1e-310]");
  EXPECT_NE(invalid_message([] { require_in_range(5e-324, -1.0, 1.0, "x"); }).find("got 5e-324"), std::string::npos);
  EXPECT_NO_THROW(require_finite(Eigen::Vector3d(0.02, 0.0, -0.0), "load.point"));
}

// Property: every double that is_input_number refuses is refused by each require_* with the field named, and
// every accepted one in range passes (random bit patterns cover normals, subnormals, nan and inf).
TEST(Checks, RequireFunctionsAgreeWithTheInputNumberRule) {
  std::uint64_t state = 0x9e3779b97f4a7c15ULL;
  for (int k = 0; k < 20000; ++k) {
    state ^= state << 13, state ^= state >> 7, state ^= state << 17;
    std::uint64_t bits = state;
    if (k % 4 == 1) bits &= 0x800fffffffffffffULL;  // exponent 0: zero or subnormal
    if (k % 4 == 2) bits |= 0x7ff0000000000000ULL;  // exponent all ones: inf or nan
    double v = 0.0;
    std::memcpy(&v, &bits, sizeof v);
    const bool ok = is_input_number(v);
    EXPECT_EQ(ok, std::isfinite(v) && (v == 0.0 || std::fpclassify(v) == FP_NORMAL)) << v;
    const std::string m = invalid_message([&] { require_finite(v, "field"); });
    EXPECT_EQ(m == "<no std::invalid_argument>", ok) << m;
    if (!ok) {
      EXPECT_EQ(m.rfind("field must be", 0), 0u) << m;
    }
    const std::string r = invalid_message([&] { require_in_range(v, -1e300, 1e300, "field"); });
    EXPECT_EQ(r == "<no std::invalid_argument>", ok && std::abs(v) <= 1e300) << r;
  }
}
