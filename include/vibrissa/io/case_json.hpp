#pragma once
// The `vibrissa solve` JSON contract (docs/formats.md): a case (whisker + load) in, a result out, SI units.
// Readers reject unknown fields and name the offending field and value in std::invalid_argument.
#include <memory>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "vibrissa/core/whisker.hpp"
#include "vibrissa/io/json_file.hpp"
#include "vibrissa/objects/shape.hpp"
#include "vibrissa/solve/base_wrench.hpp"
#include "vibrissa/solve/options.hpp"
#include "vibrissa/solve/solution.hpp"

namespace vibrissa {

struct ForceLoad {
  double force = 0.0, arc_length = 0.0, angle = 0.0;
};
struct DeadLoad {
  Eigen::Vector3d force = Eigen::Vector3d::Zero();
  double arc_length = 0.0;
};
struct PointLoad {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  std::optional<double> arc_length_hint;
  std::optional<Eigen::Vector3d> edge_direction;
};
struct EdgeLoad {
  Edge edge;
  std::optional<double> arc_length_hint;
  std::optional<Eigen::Vector3d> approach;
};
struct FrictionalEdgeLoad {
  Edge edge;
  double friction_coefficient = 0.0;
  Eigen::Vector3d previous_contact = Eigen::Vector3d::Zero();
  std::optional<Eigen::Vector3d> approach;
};
/// The inverse (docs/inverse.md): base force and moment (world, about the base) -> contact.
struct BaseWrenchLoad {
  Eigen::Vector3d force = Eigen::Vector3d::Zero();
  Eigen::Vector3d moment = Eigen::Vector3d::Zero();
  SignalSet signals = SignalSet::all();
  Eigen::MatrixXd noise_covariance;  ///< empty: the default relative noise
};
/// An object (docs/objects.md): frictionless, or with friction_coefficient and previous_contact.
struct ObjectLoad {
  std::shared_ptr<const Shape> shape;
  bool thickness = true;
  std::optional<double> friction_coefficient;
  std::optional<Eigen::Vector3d> previous_contact;
  std::optional<double> arc_length_hint;
  std::optional<Eigen::Vector3d> approach;
};
using Load = std::variant<ForceLoad, DeadLoad, PointLoad, EdgeLoad, FrictionalEdgeLoad, BaseWrenchLoad, ObjectLoad>;

struct Case {
  Whisker whisker;
  Load load;
  SolveOptions options;
  /// Plausibility warnings only the reader can see (pose angles before they are wrapped into R_WB);
  /// case_warnings adds those of the whisker and the load.
  std::vector<std::string> input_warnings;
};

/// Whisker from the "whisker" object of a case. `input_warnings`, if given, receives the plausibility
/// warnings of its "pose" (angles beyond +-pi: degrees given as radians), which the Whisker cannot show.
Whisker whisker_from_json(const nlohmann::json& j, std::vector<std::string>* input_warnings = nullptr);
Load load_from_json(const nlohmann::json& j);
/// Whole case; options default to find_other_roots = true.
Case case_from_json(const nlohmann::json& j);

Solution solve_case(const Case& c);

/// Every plausibility warning of a case (core/plausibility.hpp): the whisker's, the pose's, and the load's
/// (a force above 0.1 N, a point or edge out of the whisker's reach).
std::vector<std::string> case_warnings(const Case& c);

nlohmann::json solution_to_json(const Solution& s);
/// The result file of `vibrissa solve`: solution_to_json, a "base_wrench" object for that mode, and
/// "warnings" (the inverse's base_wrench_warnings first, then case_warnings; empty when none).
nlohmann::json solve_case_to_json(const Case& c);
/// solution_to_json plus the case's "warnings".
nlohmann::json case_result_to_json(const Case& c, const Solution& s);
/// The inverse's result: solution_to_json of the returned fit plus "base_wrench" (roots, identifiability).
nlohmann::json base_wrench_to_json(const BaseWrenchResult& r);
BaseWrenchOptions base_wrench_options(const BaseWrenchLoad& load, const SolveOptions& options);
nlohmann::json to_json(const Eigen::Vector3d& v);

/// Reads and parses a JSON file; errors name the file.
nlohmann::json read_json_file(const std::string& path);
/// Results are written with io::write_json_file (atomic: temporary file + rename).
using io::write_json_file;

}  // namespace vibrissa
