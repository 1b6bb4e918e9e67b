#pragma once
// User whisker-array tables (docs/array.md, "Morphology"): a CSV table with the header
//   name,side,S_mm,A_per_mm,theta_deg,phi_deg,zeta_deg,base_x_mm,base_y_mm,base_z_mm
// plus optional columns base_radius_um, taper_ratio, youngs_modulus_GPa, poisson_ratio, or the same columns
// as a JSON array of objects (or {"whiskers": [...]}). Every row describes the right-side equivalent;
// side = left mirrors it. Name = row letter A-E followed by the column number. Units as the column names
// say; the Morphology returned is SI. Errors (std::invalid_argument) name the source, line/row and column.
#include <filesystem>
#include <istream>
#include <string>

#include <nlohmann/json_fwd.hpp>

#include "vibrissa/array/morphology.hpp"

namespace vibrissa::io {

array::Morphology morphology_from_csv(std::istream& in, const std::string& source = "csv");
array::Morphology morphology_from_json(const nlohmann::json& table, const std::string& source = "json");
/// By extension: .csv or .json.
array::Morphology read_morphology_table(const std::filesystem::path& path);

}  // namespace vibrissa::io
