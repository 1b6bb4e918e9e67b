#pragma once
// Every null of a summary comes with its reason (docs/formats.md, "Nulls and their reasons"): a summary's
// top-level object "nan_reasons" maps the JSON Pointer (RFC 6901) of each field that is null — a NaN, or a
// value that could not be computed — to why, in words, e.g. {"/friction/median": "no contact frame ..."}.
// Empty when nothing is null. CSV summaries carry the same reasons in a last column `nan_reasons`.
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace vibrissa::io {

class NanReasons {
 public:
  /// The reason for the null at `pointer`, or for every null under it (a pointer prefix such as
  /// "/force_directions/frictional_edge"); the most specific one wins. Kept only where a null is.
  void explain(const std::string& pointer, const std::string& reason);
  /// Sets summary["nan_reasons"] to the reason of every null in `summary`. A null that nothing explains gets
  /// kUnexplained (tests assert that no summary has one).
  void attach(nlohmann::json& summary) const;

  static constexpr const char* kUnexplained = "no reason recorded (a defect in vibrissa: please report it)";

 private:
  std::map<std::string, std::string> reasons_;
};

/// `value` as JSON, or null if it is not finite (NaN or infinite).
nlohmann::json finite_or_null(double value);

/// JSON Pointers of the nulls in `j` (NaN numbers included), in document order.
std::vector<std::string> null_pointers(const nlohmann::json& j);

}  // namespace vibrissa::io
