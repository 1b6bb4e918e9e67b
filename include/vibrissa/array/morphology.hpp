#pragma once
// Morphology of the rat vibrissal array: which whiskers exist, where their bases sit on the mystacial pad,
// their rest shapes and resting orientations (data sheet rat-array-data.md §1 Towal 2011, §2 Belli 2018).
//
// Head frame H (Towal 2011): x lateral toward the rat's right, y rostral, z dorsal, origin as in the source.
// Angles of a whisker are the sources' Euler angles (theta, phi, zeta) of the right-side equivalent; the
// whisker is drawn in its own frame as (x, 0, -A x^2) and placed by Rz(theta - 90°)·Ry(-phi)·Rx(zeta)
// (data sheet §2). The left side is the mirror image (x -> -x) of the right. See docs/array.md.
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "vibrissa/core/pose.hpp"
#include "vibrissa/core/whisker.hpp"

namespace vibrissa::array {

enum class Side { right, left };
std::string_view to_string(Side side);
/// "right" / "left"; throws std::invalid_argument naming `field`.
Side side_from_string(std::string_view name, const char* field = "side");

/// Which sides of the face a published array is built for.
enum class Sides { right, left, both };
Sides sides_from_string(std::string_view name, const char* field = "morphology.sides");

/// One whisker of an array, SI units. Angles are those of the right-side equivalent (see header comment).
struct WhiskerSpec {
  std::string name;                                   ///< e.g. "C2" (row letter + column number)
  Side side = Side::right;
  int row = 3;                                        ///< A..E = 1..5
  int column = 2;                                     ///< column number as named (0 = Greek/straddler)
  double arc_length = 0.0;                            ///< S [m]
  double curvature = 0.0;                             ///< A [1/m] of the rest shape y = A x^2
  Eigen::Vector3d p_H_base = Eigen::Vector3d::Zero();  ///< base point in the head frame [m] (this side)
  double theta_rest = 0.0;                            ///< source protraction angle [rad]
  double phi_rest = 0.0;                              ///< source elevation angle [rad]
  double zeta_rest = 0.0;                             ///< source roll angle [rad]
  double base_radius = 100e-6;                        ///< [m]
  double taper_ratio = 15.0;                          ///< base radius / tip radius
  double youngs_modulus = 3.3e9;                      ///< [Pa]
  double poisson_ratio = 0.38;

  /// "C2R" / "C2L": the name with the side appended.
  [[nodiscard]] std::string label() const;
};

void validate(const WhiskerSpec& spec);

struct Morphology {
  std::string source;  ///< "towal2011", "belli2018", or the file it was read from
  std::string phi_method;  ///< towal2011: the φ method used (to_string(PhiMethod)); empty for other sources
  std::vector<WhiskerSpec> whiskers;
};

/// How the Towal 2011 elevation φ of each whisker is obtained: the three `TGL_PHI` methods of the RatMap Toolbox
/// v1.1 (`Get_RatMap.m`, Towal et al. 2011). `projection` ('proj', the toolbox's default: "projection angles match
/// those shown in the publication") converts the projection angles φ_P and ψ_P, `projection_phi_only`
/// ('proj_phi_only') converts φ_P alone, `euler` uses the regression of the Euler φ directly. See docs/array.md.
enum class PhiMethod { projection, projection_phi_only, euler };
std::string_view to_string(PhiMethod method);
/// "projection" / "projection_phi_only" / "euler"; throws std::invalid_argument naming `field` and the value.
PhiMethod phi_method_from_string(std::string_view name, const char* field = "morphology.phi_method");

/// Elevation φ [rad] of a Towal 2011 whisker (vibrissa's phi_rest, > 0 points up; the toolbox's C_phi negated)
/// for a projection angle θ_P [deg] (the toolbox's domain 0..180; outside it throws) at (COL, ROW), as the
/// RatMap Toolbox v1.1 computes it, quadrant branches and all.
double towal_elevation(PhiMethod method, Side side, double theta_projection_deg, int COL, int ROW);

/// Towal et al. 2011 "RatMap" equations (data sheet §1): 31 whiskers per side, radius from Belli's model; φ by
/// `phi_method` (default as the RatMap Toolbox: projection).
Morphology towal2011(Sides sides = Sides::right, PhiMethod phi_method = PhiMethod::projection);
/// Belli et al. 2018 average-rat table (data sheet §2): 27 whiskers per side.
Morphology belli2018(Sides sides = Sides::right);
/// "towal2011" (with `phi_method`) or "belli2018"; throws std::invalid_argument naming `field` for any other name.
Morphology morphology_by_name(std::string_view name, Sides sides = Sides::right,
                              PhiMethod phi_method = PhiMethod::projection, const char* field = "morphology.source");

/// User tables (CSV/JSON) are read by io/morphology_table.hpp.

/// "C2" -> row 3 (A..E = 1..5), column 2; throws std::invalid_argument naming `field`.
void parse_whisker_name(const std::string& name, int& row, int& column, const std::string& field);
/// A right-side spec placed on `side`: the base point is mirrored (x -> -x) for the left; the angles stay
/// those of the right-side equivalent.
WhiskerSpec on_side(WhiskerSpec spec, Side side);

/// Keep only the named whiskers (name without side, e.g. "C2", or with it, "C2R"); throws
/// std::invalid_argument naming `field` and the unknown name.
Morphology select_whiskers(const Morphology& morphology, const std::vector<std::string>& names,
                           const char* field = "morphology.whiskers");

/// Belli 2018 base-diameter model [mm] (data sheet §2): 0.041 + 0.002 S + 0.011 row - 0.0039 col.
double belli_base_diameter_mm(double arc_length_mm, int row, int column);
/// Towal 2011 base point [m] in the head frame, right side (data sheet §1, ellipsoid construction).
Eigen::Vector3d towal_base_point(int COL, int ROW);

/// Orientation of the whisker frame B of vibrissa (x along emergence, concave toward +y) in the head frame,
/// for the source angles (theta, phi, zeta) [rad] of the right-side equivalent; mirrored for the left side.
Eigen::Matrix3d R_HB(Side side, double theta, double phi, double zeta);

/// Material and taper of this whisker as vibrissa WhiskerProperties with `links` links.
WhiskerProperties whisker_properties(const WhiskerSpec& spec, int links);
/// The rest whisker with its frame B at the world origin (identity pose); place it with Whisker::placed.
Whisker make_rest_whisker(const WhiskerSpec& spec, int links);

}  // namespace vibrissa::array
