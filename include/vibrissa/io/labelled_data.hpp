#pragma once
// Labelled outputs (docs/formats.md, "Labelled HDF5 outputs"): the arrays of an output as named variables with
// named dimensions, coordinates, units and a description, as netCDF-4 and xarray see them. One table per
// output (array_data, trial_results_data, trial_file_data) feeds both its HDF5 file (write_labelled_h5:
// dimension scales, variable-length UTF-8 strings) and Python's to_xarray(), so the two cannot drift apart.
#include <cstddef>
#include <cstdint>
#include <deque>
#include <span>
#include <string>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

namespace vibrissa::io {

/// The values of one variable, row-major, borrowed from the result that owns them or from LabelledData.
using LabelledValues =
    std::variant<std::span<const double>, std::span<const float>, std::span<const int>, std::span<const std::int16_t>,
                 std::span<const std::int8_t>, std::span<const std::string>>;

struct LabelledVariable {
  std::string name{};               ///< dataset path: "FT", or "render/rest" in group render
  std::vector<std::string> dims{};  ///< dimension names, slowest first ("pitch", "whisker", "time", "component")
  std::vector<std::size_t> shape{};
  LabelledValues values{};
  std::string units{};      ///< docs/formats.md, "Units and codes"
  std::string long_name{};  ///< what the values are, in words (CF's long_name; xarray labels plots with it)
  std::string codes{};      ///< the code table of a variable of units "code"
  bool compress = false;  ///< chunk + deflate in HDF5 when large (mostly-zero arrays shrink)
};

struct LabelledAttribute {
  std::string group;  ///< "" for the root
  std::string name;
  std::variant<std::string, double> value;
};

/// Variables and attributes of one output. Every dimension has a coordinate variable: a one-dimensional
/// variable named as the dimension (time stamps, whisker names, "x"/"y"/"z", or an index). Not copyable (the
/// spans may point into its own storage); it borrows the result it was made from, which must outlive it.
struct LabelledData {
  LabelledData() = default;
  LabelledData(const LabelledData&) = delete;
  LabelledData& operator=(const LabelledData&) = delete;
  LabelledData(LabelledData&&) = default;
  LabelledData& operator=(LabelledData&&) = default;

  std::vector<LabelledVariable> variables;
  std::vector<LabelledAttribute> attributes;

  /// Adds a variable whose values this object keeps (derived arrays, coordinates); returns it.
  template <class T>
  LabelledVariable& add_owned(LabelledVariable variable, std::vector<T> values) {
    auto& store = storage<T>();
    store.push_back(std::move(values));
    variable.values = std::span<const T>(store.back());
    return variables.emplace_back(std::move(variable));
  }
  /// The coordinate variable of dimension `name`: the indices 0 .. size - 1 (units "1").
  void add_index_coordinate(const std::string& group, const std::string& name, std::size_t size,
                            std::string long_name);
  /// The coordinate "component" (or `name`) with values "x", "y", "z" (units "text").
  void add_component_coordinate(const std::string& name = "component");
  /// The variable named `name`; std::out_of_range if there is none.
  const LabelledVariable& variable(const std::string& name) const;

 private:
  template <class T>
  std::deque<std::vector<T>>& storage() {
    if constexpr (std::is_same_v<T, double>) return doubles_;
    else if constexpr (std::is_same_v<T, std::int8_t>) return int8s_;
    else if constexpr (std::is_same_v<T, int>) return ints_;
    else {
      static_assert(std::is_same_v<T, std::string>, "LabelledData keeps doubles, int8, int and strings");
      return strings_;
    }
  }
  // Deques: a new element never moves the older ones, so the spans into them stay valid.
  std::deque<std::vector<double>> doubles_;
  std::deque<std::vector<std::int8_t>> int8s_;
  std::deque<std::vector<int>> ints_;
  std::deque<std::vector<std::string>> strings_;
};

/// Writes `data` as an HDF5 file readable by xarray.open_dataset with either netCDF-4 engine: every dimension a
/// dimension scale (its coordinate variable), every string variable-length UTF-8, attributes units, long_name,
/// codes. Throws std::runtime_error if the file cannot be written; an inconsistent table (a dimension without
/// coordinate or with two lengths, values that do not fill the shape) is an internal error.
void write_labelled_h5(const LabelledData& data, const std::string& path);

}  // namespace vibrissa::io
