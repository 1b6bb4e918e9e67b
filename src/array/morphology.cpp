#include "vibrissa/array/morphology.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "array_util.hpp"

namespace vibrissa::array {
namespace {

constexpr double mm = 1e-3;
constexpr char kRowLetters[] = "ABCDE";

// Towal 2011 (data sheet §1): each quantity is a·COL + b·ROW + c.
struct Linear {
  double a, b, c;
  [[nodiscard]] double operator()(int COL, int ROW) const { return a * COL + b * ROW + c; }
};
constexpr Linear kTowalThetaBp{15.2953, 0.0, -144.2220};
constexpr Linear kTowalPhiBp{0.0, 18.2237, 34.7558};
constexpr Linear kTowalS{-7.9312, 2.2224, 52.1110};
constexpr Linear kTowalTheta{10.6475, 0.0, 37.3178};
constexpr Linear kTowalPhiProjection{1.0988, -18.0334, 50.6005};
constexpr Linear kTowalPsiProjection{18.5149, 49.3499, -50.5406};
constexpr Linear kTowalZeta{18.7700, -11.3485, -4.9844};
constexpr Linear kTowalPhiEuler{0.0, -15.8761, 47.3263};

// Belli 2018 average rat (data sheet §2): S [mm], A [1/mm], theta_w, phi_w, zeta_w [deg], r_bp [mm],
// theta_bp, phi_bp [deg].
struct BelliRow {
  const char* id;
  double S, A, theta, phi, zeta, r_bp, theta_bp, phi_bp;
};
constexpr BelliRow kBelli[] = {
    {"A1", 39.9, 0.00596, 41.7, 31.9, 25.7, 7.73, -35.2, 31.4},
    {"A2", 31, 0.0118, 36.7, 42.5, 74.2, 6.73, -25, 39.5},
    {"A3", 25.1, 0.0123, 33.5, 51.9, 96.9, 6.06, -5.98, 45.8},
    {"A4", 15.4, 0.0178, 40.4, 64.7, 110, 5.95, 17.6, 50.9},
    {"A5", 10.7, 0.0222, 106, 74.3, 66.2, 5.91, 40.2, 47.1},
    {"B1", 46.8, 0.00681, 49.1, 15.6, 1.88, 7.8, -32.6, 15.9},
    {"B2", 40.8, 0.00914, 50.8, 21.9, 29.3, 6.84, -22.2, 21.9},
    {"B3", 29.3, 0.0149, 55.8, 29.9, 50.7, 6.03, -7.83, 25},
    {"B4", 20.7, 0.0166, 66.2, 31.6, 72.6, 5.46, 12.4, 26.3},
    {"B5", 11.8, 0.0244, 85.3, 36.3, 73.6, 5.45, 31.9, 23.7},
    {"C1", 52.8, 0.00694, 52.8, 1.91, -20.8, 8.46, -33.6, -0.677},
    {"C2", 45.2, 0.00885, 56.9, 11, 21.5, 7.38, -22.9, 3.95},
    {"C3", 32.6, 0.0118, 61, 9.9, 30.4, 6.42, -8.63, 5.66},
    {"C4", 22.9, 0.0136, 67.4, 9.88, 63.6, 5.76, 4.92, 5.39},
    {"C5", 13.3, 0.0233, 77.1, 10.9, 70.9, 5.56, 23.3, 1.6},
    {"C6", 7.68, 0.0185, 95.4, 9.47, 51.1, 5.82, 36.9, -1.63},
    {"D1", 52.6, 0.00809, 57, -7.28, -26.9, 8.84, -33.5, -12.6},
    {"D2", 45.9, 0.00859, 58.8, -2.39, 6.93, 7.77, -23, -9.79},
    {"D3", 35.3, 0.0104, 64.6, -1.34, 15.4, 7.04, -12.2, -11.9},
    {"D4", 25.5, 0.013, 69.8, -2.2, 32.7, 6.36, 1.63, -12},
    {"D5", 17.1, 0.0178, 78.7, -6.63, 47.7, 6.12, 13.2, -14.1},
    {"D6", 10.9, 0.0239, 88.2, -11.6, 61.4, 6.31, 28.5, -15.8},
    {"E2", 44.1, 0.0101, 56.5, -8.96, -18.3, 8.42, -28, -21.6},
    {"E3", 34.6, 0.0101, 60, -12.2, 6.34, 8.05, -16.8, -23.8},
    {"E4", 24.4, 0.0142, 65.8, -15.8, 14.2, 7.33, -4.48, -26.3},
    {"E5", 15.5, 0.0224, 74, -22.1, 31.4, 6.96, 6.91, -28},
    {"E6", 9.4, 0.0192, 88, -27.1, 42, 6.77, 20.7, -29.2},
};

const Eigen::Matrix3d kMirrorX = Eigen::Vector3d(-1.0, 1.0, 1.0).asDiagonal();

std::vector<Side> sides_of(Sides sides) {
  switch (sides) {
    case Sides::right: return {Side::right};
    case Sides::left: return {Side::left};
    case Sides::both: return {Side::right, Side::left};
  }
  return {Side::right};
}

}  // namespace

std::string_view to_string(Side side) { return side == Side::right ? "right" : "left"; }

Side side_from_string(std::string_view name, const char* field) {
  if (name == "right" || name == "R" || name == "r") return Side::right;
  if (name == "left" || name == "L" || name == "l") return Side::left;
  fail(std::string(field) + " must be 'right' or 'left', got '" + std::string(name) + "'");
}

Sides sides_from_string(std::string_view name, const char* field) {
  if (name == "right") return Sides::right;
  if (name == "left") return Sides::left;
  if (name == "both") return Sides::both;
  fail(std::string(field) + " must be 'right', 'left' or 'both', got '" + std::string(name) + "'");
}

std::string_view to_string(PhiMethod method) {
  switch (method) {
    case PhiMethod::projection: return "projection";
    case PhiMethod::projection_phi_only: return "projection_phi_only";
    case PhiMethod::euler: return "euler";
  }
  return "projection";
}

PhiMethod phi_method_from_string(std::string_view name, const char* field) {
  for (const PhiMethod m : {PhiMethod::projection, PhiMethod::projection_phi_only, PhiMethod::euler})
    if (name == to_string(m)) return m;
  fail(std::string(field) + " must be 'projection', 'projection_phi_only' or 'euler', got '" +
       quote_text(std::string(name)) + "'");
}

double towal_elevation(PhiMethod method, Side side, double thP, int COL, int ROW) {
  // RatMap Toolbox v1.1, Get_RatMap.m (LOCAL_CalculateParameters): angles in degrees, the toolbox's branches and
  // boundaries kept exactly; a case no branch covers leaves the toolbox's φ at 0, and so here.
  if (method == PhiMethod::euler) return deg(kTowalPhiEuler(COL, ROW));
  if (!(thP >= 0.0 && thP <= 180.0))
    fail("towal2011: projection theta must be in [0, 180] deg (the RatMap domain), got " + fmt(thP));
  // The toolbox's Euler θ (0..360) of this side.
  double th = 0.0;
  if (side == Side::right) th = thP >= 90.0 ? thP - 90.0 : thP + 270.0;
  else th = thP >= 90.0 ? (180.0 - thP) + 90.0 : 270.0 - thP;
  const double phP = kTowalPhiProjection(COL, ROW), psP = kTowalPsiProjection(COL, ROW);
  const auto tan_d = [](double d) { return std::tan(deg(d)); };
  const auto sin_d = [](double d) { return std::sin(deg(d)); };
  const auto cos_d = [](double d) { return std::cos(deg(d)); };
  double phi = 0.0;  // [rad]
  if (method == PhiMethod::projection_phi_only) {
    if (0.0 <= th && th < 90.0) phi = std::atan(tan_d(phP) * cos_d(th));
    else if (90.0 < th && th < 270.0) phi = std::atan(tan_d(phP) * cos_d(std::abs(180.0 - th)));
    else if (270.0 < th && th <= 360.0) phi = std::atan(tan_d(phP) * cos_d(360.0 - th));
    return phi;
  }
  const bool psi_low = 0.0 <= psP && psP <= 90.0, psi_high = 270.0 <= psP;
  if (0.0 <= th && th <= 45.0) phi = std::atan(tan_d(phP) * cos_d(th));
  else if (45.0 < th && th <= 90.0) phi = std::atan(tan_d(180.0 - psP) * sin_d(th));
  else if (90.0 < th && th <= 135.0) phi = std::atan(tan_d(180.0 - psP) * sin_d(180.0 - th));
  else if (135.0 < th && th <= 225.0) phi = std::atan(tan_d(phP) * cos_d(180.0 - th));
  else if (225.0 < th && th <= 270.0 && psi_low) phi = std::atan(tan_d(psP) * sin_d(std::abs(180.0 - th)));
  else if (225.0 < th && th <= 270.0 && psi_high) phi = std::atan(tan_d(psP - 360.0) * sin_d(std::abs(180.0 - th)));
  else if (270.0 < th && th <= 315.0 && psi_low) phi = std::atan(tan_d(psP) * sin_d(360.0 - th));
  else if (270.0 < th && th <= 315.0 && psi_high) phi = std::atan(tan_d(psP - 360.0) * sin_d(360.0 - th));
  else if (315.0 < th && th <= 360.0) phi = std::atan(tan_d(phP) * cos_d(360.0 - th));
  // The toolbox then negates this ("for correct rotation direction") and rotates by Ry(C_phi); vibrissa rotates by
  // Ry(-φ), so φ is the value before that negation.
  return phi;
}

std::string WhiskerSpec::label() const { return name + (side == Side::right ? "R" : "L"); }

void parse_whisker_name(const std::string& name, int& row, int& column, const std::string& field) {
  if (name.size() < 2) fail(field + " must be a row letter A-E and a column number, got '" + name + "'");
  const char letter = static_cast<char>(std::toupper(static_cast<unsigned char>(name[0])));
  const char* at = std::strchr(kRowLetters, letter);
  if (letter == '\0' || at == nullptr)
    fail(field + " must start with a row letter A-E, got '" + name + "'");
  row = static_cast<int>(at - kRowLetters) + 1;
  try {
    std::size_t used = 0;
    column = std::stoi(name.substr(1), &used);
    if (used != name.size() - 1 || column < 0) throw std::invalid_argument("bad");
  } catch (const std::exception&) {
    fail(field + " must end in a column number >= 0, got '" + name + "'");
  }
}

WhiskerSpec on_side(WhiskerSpec spec, Side side) {
  spec.side = side;
  if (side == Side::left) spec.p_H_base = kMirrorX * spec.p_H_base;
  return spec;
}


void validate(const WhiskerSpec& s) {
  const std::string w = "whisker " + s.name;
  if (s.row < 1 || s.row > 5) fail(w + ": row must be 1..5 (A..E), got " + std::to_string(s.row));
  if (s.column < 0) fail(w + ": column must be >= 0, got " + std::to_string(s.column));
  require_positive(s.arc_length, (w + ": S").c_str());
  require_finite(s.curvature, (w + ": A").c_str());
  require_finite(s.p_H_base, (w + ": base point").c_str());
  require_finite(s.theta_rest, (w + ": theta").c_str());
  require_finite(s.phi_rest, (w + ": phi").c_str());
  require_finite(s.zeta_rest, (w + ": zeta").c_str());
  require_positive(s.base_radius, (w + ": base_radius").c_str());
  if (!(std::isfinite(s.taper_ratio) && s.taper_ratio > 1.0))
    fail(w + ": taper_ratio must be > 1, got " + fmt(s.taper_ratio));
  require_positive(s.youngs_modulus, (w + ": youngs_modulus").c_str());
}

double belli_base_diameter_mm(double S_mm, int row, int column) {
  // Belli 2018 base-diameter model, data sheet §2.
  return 0.041 + 0.002 * S_mm + 0.011 * row - 0.0039 * column;
}

Eigen::Vector3d towal_base_point(int COL, int ROW) {
  // Towal 2011, data sheet §1. The base point is where the ray from the ellipsoid centre at spherical angles
  // (theta_bp azimuth, phi_bp measured from the ellipsoid's +z axis) meets the ellipsoid; the ellipsoid is
  // then rotated by Rz·Ry·Rx of its orientation and translated to its centre. This reading reproduces the data
  // sheet's check values (A0, E6) to 1 µm.
  const Eigen::Vector3d centre(1.9128, -7.6549, -5.4439);
  const Eigen::Vector3d radii(9.5304, 5.5393, 6.9745);
  const Eigen::Matrix3d R = rotation_z(deg(106.5100)) * rotation_y(deg(-2.5211)) * rotation_x(deg(-19.5401));
  const double th = deg(kTowalThetaBp(COL, ROW));
  const double ph = deg(kTowalPhiBp(COL, ROW));
  const Eigen::Vector3d u(std::cos(th) * std::sin(ph), std::sin(th) * std::sin(ph), std::cos(ph));
  const double t = 1.0 / u.cwiseQuotient(radii).norm();
  return (R * (t * u) + centre) * mm;
}

Morphology towal2011(Sides sides, PhiMethod phi_method) {
  Morphology m;
  m.source = "towal2011";
  m.phi_method = to_string(phi_method);
  // Per side: A0-A4, B0-B5, C0-C6, D0-D6, E1-E6 (data sheet §1); COL = column number + 1.
  const int first[5] = {0, 0, 0, 0, 1};
  const int last[5] = {4, 5, 6, 6, 6};
  for (const Side side : sides_of(sides)) {
    for (int ROW = 1; ROW <= 5; ++ROW) {
      for (int column = first[ROW - 1]; column <= last[ROW - 1]; ++column) {
        const int COL = column + 1;
        WhiskerSpec s;
        s.name = std::to_string(column);
        s.name.insert(s.name.begin(), kRowLetters[ROW - 1]);
        s.row = ROW;
        s.column = column;
        s.arc_length = kTowalS(COL, ROW) * mm;
        s.curvature = std::exp(1.0 / (-0.02052 * COL - 0.2045)) / mm;  // Towal curvature, y = a x^2 [1/mm]
        s.p_H_base = towal_base_point(COL, ROW);
        s.theta_rest = deg(kTowalTheta(COL, ROW));
        s.phi_rest = towal_elevation(phi_method, side, kTowalTheta(COL, ROW), COL, ROW);
        s.zeta_rest = deg(kTowalZeta(COL, ROW));
        // Belli's model numbers columns from 1 without the Greek column: column 0 -> col 0 (extrapolated).
        s.base_radius = 0.5 * belli_base_diameter_mm(s.arc_length / mm, ROW, column) * mm;
        m.whiskers.push_back(on_side(s, side));
      }
    }
  }
  return m;
}

Morphology belli2018(Sides sides) {
  Morphology m;
  m.source = "belli2018";
  for (const Side side : sides_of(sides)) {
    for (const BelliRow& b : kBelli) {
      WhiskerSpec s;
      s.name = b.id;
      parse_whisker_name(s.name, s.row, s.column, "belli2018");
      s.arc_length = b.S * mm;
      s.curvature = b.A / mm;
      s.theta_rest = deg(b.theta);
      s.phi_rest = deg(b.phi);
      s.zeta_rest = deg(b.zeta);
      // Data sheet §2 mapping of (r_bp, theta_bp, phi_bp) as the WHISKiT files use it. Its origin differs from
      // Towal's by about (0, 4.5, 4.3) mm; the relative layout agrees (docs/array.md).
      const double tb = deg(b.theta_bp), pb = deg(b.phi_bp);
      s.p_H_base = Eigen::Vector3d(b.r_bp * std::cos(tb), b.r_bp * std::sin(tb), b.r_bp * std::sin(pb)) * mm;
      s.base_radius = 0.5 * belli_base_diameter_mm(b.S, s.row, s.column) * mm;
      m.whiskers.push_back(on_side(s, side));
    }
  }
  return m;
}

Morphology morphology_by_name(std::string_view name, Sides sides, PhiMethod phi_method, const char* field) {
  if (name == "towal2011" || name == "towal") return towal2011(sides, phi_method);
  if (name == "belli2018" || name == "belli") return belli2018(sides);
  fail(std::string(field) + " must be 'towal2011', 'belli2018' or a .csv/.json table, got '" + std::string(name) +
       "'");
}

Morphology select_whiskers(const Morphology& m, const std::vector<std::string>& names, const char* field) {
  Morphology out;
  out.source = m.source;
  out.phi_method = m.phi_method;
  for (const std::string& n : names) {
    bool found = false;
    for (const WhiskerSpec& s : m.whiskers) {
      if (s.name == n || s.label() == n) {
        found = true;
        bool dup = false;
        for (const WhiskerSpec& o : out.whiskers) dup = dup || o.label() == s.label();
        if (!dup) out.whiskers.push_back(s);
      }
    }
    if (!found) fail(std::string(field) + ": unknown whisker '" + n + "' (not in " + m.source + ")");
  }
  return out;
}

Eigen::Matrix3d R_HB(Side side, double theta, double phi, double zeta) {
  // Source convention (data sheet §2): p_H = Rz(theta - 90°)·Ry(-phi)·Rx(zeta)·(x, 0, -A x^2). vibrissa draws
  // the same whisker as (x, A x^2, 0); Rx(-90°) takes (x, A x^2, 0) to (x, 0, -A x^2). Hence
  // R_HB = rotation_from_angles(theta - 90°, phi, zeta - 90°).
  const double quarter = 0.5 * std::numbers::pi;
  const Eigen::Matrix3d R = rotation_from_angles(theta - quarter, phi, zeta - quarter);
  if (side == Side::right) return R;
  // Left side: mirror x -> -x of the right whisker. A planar shape (z_B = 0) is unchanged by z_B -> -z_B, so
  // M R diag(1, 1, -1) is a proper rotation that draws the mirror image.
  return kMirrorX * R * Eigen::Vector3d(1.0, 1.0, -1.0).asDiagonal();
}

WhiskerProperties whisker_properties(const WhiskerSpec& spec, int links) {
  WhiskerProperties p;
  p.links = links;
  p.base_radius = spec.base_radius;
  p.taper_ratio = spec.taper_ratio;
  p.youngs_modulus = spec.youngs_modulus;
  p.poisson_ratio = spec.poisson_ratio;
  return p;
}

Whisker make_rest_whisker(const WhiskerSpec& spec, int links) {
  return Whisker::from_parabola(spec.arc_length, spec.curvature, whisker_properties(spec, links));
}

}  // namespace vibrissa::array
