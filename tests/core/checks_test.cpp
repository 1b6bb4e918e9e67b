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
  EXPECT_NE(invalid_message([&] { (void)Whisker::from_points(pts, WhiskerProperties{}); }).find("whisker.points"),
            std::string::npos);
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
  EXPECT_NE(long_one[0].find("whisker length 39.99"), std::string::npos);
  WhiskerProperties p;
  p.base_radius = 2e-3;
  p.youngs_modulus = 3.3;
  const auto w = plausibility_warnings(Whisker::from_parabola(0.03, 5.0, p));
  ASSERT_EQ(w.size(), 2u);
  EXPECT_NE(w[0].find("base radius 0.002 m"), std::string::npos);
  EXPECT_NE(w[1].find("Young's modulus 3.3 Pa"), std::string::npos);
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
