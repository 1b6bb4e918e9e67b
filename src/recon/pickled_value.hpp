#pragma once
// A strictly bounded reader of the Python pickles PyTables stores as attributes of a pandas table (the column
// labels of a DeepLabCut HDF5 file; private to src/recon). Only plain data is decoded: None, bools, ints,
// str/bytes, tuples, lists, dicts, with memo put/get, protocols 0-5 (text opcodes as PyTables writes them,
// binary opcodes with PROTO/FRAME). Any other opcode (globals, object construction, reduce, persistent ids,
// floats) is rejected: nothing in the pickle is ever executed.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace vibrissa::recon {

struct PickledValue {
  enum class Kind { none, boolean, integer, string, tuple, list, dict };
  Kind kind = Kind::none;
  std::int64_t integer = 0;  ///< integer, boolean (0/1)
  std::string string;        ///< str as UTF-8, bytes as they are
  /// tuple/list elements; a dict as key, value, key, value, ...
  std::vector<std::shared_ptr<PickledValue>> items;
};

/// Values created (including copies made by memo gets) per pickle: bounds memory for any input.
inline constexpr std::size_t max_pickled_values = 1'000'000;
/// Nesting depth of containers.
inline constexpr int max_pickle_depth = 32;

/// Decodes one pickle; `what` names the source in errors (e.g. "file.h5: attribute 'non_index_axes'"),
/// which also give the byte offset of the offending opcode. Throws std::invalid_argument.
PickledValue read_pickle(std::string_view bytes, const std::string& what);

/// "list", "tuple", ... for messages.
const char* kind_name(PickledValue::Kind kind);

}  // namespace vibrissa::recon
