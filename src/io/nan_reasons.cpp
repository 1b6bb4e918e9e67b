#include "vibrissa/io/nan_reasons.hpp"

#include <cmath>

namespace vibrissa::io {
namespace {

void collect_nulls(const nlohmann::json& j, const std::string& at, std::vector<std::string>& out) {
  if (j.is_null() || (j.is_number_float() && !std::isfinite(j.get<double>()))) {
    out.push_back(at);
  } else if (j.is_object()) {
    for (const auto& [key, value] : j.items()) {
      std::string escaped;  // RFC 6901: '~' -> "~0", '/' -> "~1"
      for (char c : key) escaped += c == '~' ? "~0" : c == '/' ? "~1" : std::string(1, c);
      collect_nulls(value, at + "/" + escaped, out);
    }
  } else if (j.is_array()) {
    for (std::size_t i = 0; i < j.size(); ++i) collect_nulls(j[i], at + "/" + std::to_string(i), out);
  }
}

}  // namespace

nlohmann::json finite_or_null(double value) { return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(); }

std::vector<std::string> null_pointers(const nlohmann::json& j) {
  std::vector<std::string> out;
  collect_nulls(j, "", out);
  return out;
}

void NanReasons::explain(const std::string& pointer, const std::string& reason) { reasons_[pointer] = reason; }

void NanReasons::attach(nlohmann::json& summary) const {
  summary.erase("nan_reasons");
  nlohmann::json out = nlohmann::json::object();
  for (const std::string& at : null_pointers(summary)) {
    std::string reason = kUnexplained;
    for (std::string p = at;; p.erase(p.rfind('/'))) {  // the pointer itself, then its ancestors
      const auto it = reasons_.find(p);
      if (it != reasons_.end()) {
        reason = it->second;
        break;
      }
      if (p.empty() || p.rfind('/') == std::string::npos) break;
    }
    out[at] = reason;
  }
  summary["nan_reasons"] = out;
}

}  // namespace vibrissa::io
