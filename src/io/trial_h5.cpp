// HDF5 trial files (docs/trials.md): one dataset per array at the root, units and metadata as root attributes.
#include <stdexcept>

#include "h5_file.hpp"
#include "vibrissa/core/checks.hpp"
#include "trial_arrays.hpp"
#include "vibrissa/io/atomic_file.hpp"
#include "vibrissa/io/trial_io.hpp"

namespace vibrissa::io {

trial::Trial read_trial_h5(const std::string& path) {
  h5::QuietErrors quiet;
  h5::Handle file = h5::open_file_read(path);
  const hid_t root = file.get();
  for (const std::string& name : h5::member_names(root)) {
    bool known = false;
    for (const char* k : trial_array_names) known = known || name == k;
    if (!known) {
      std::string expected;
      for (const char* k : trial_array_names) expected += std::string(expected.empty() ? "" : ", ") + k;
      throw std::invalid_argument(
          trial::located_message(path, 0, quote_text(name), "unknown dataset (expected one of " + expected + ")"));
    }
  }
  ArrayReader r;
  r.source = path;
  r.array = [&](const std::string& name) -> std::optional<NamedArray> {
    if (!h5::has_dataset(root, name)) return std::nullopt;
    std::vector<hsize_t> dims;
    NamedArray a;
    a.data = h5::read_doubles(root, name, dims, path);
    for (hsize_t d : dims) a.dims.push_back(static_cast<std::size_t>(d));
    return a;
  };
  r.text = [&](const std::string& name) { return h5::read_string_attribute(root, name, path); };
  r.number = [&](const std::string& name) { return h5::read_double_attribute(root, name, path); };
  return assemble_trial(r);
}

void write_trial_h5(const trial::Trial& t, const std::string& path) {
  const TrialArrays arrays = disassemble_trial(t);
  write_atomically(path, [&](const std::string& tmp) {
    h5::QuietErrors quiet;
    h5::Handle file = h5::create_file(tmp);
    h5::write_string_attribute(file.get(), "format", "vibrissa-trial");
    h5::write_double_attribute(file.get(), "format_version", 1.0);
    for (const auto& [name, a] : arrays.arrays) {
      std::vector<hsize_t> dims(a.dims.begin(), a.dims.end());
      h5::write_dataset(file.get(), name, a.data, dims, {a.units});
    }
    for (const auto& [name, s] : arrays.texts) h5::write_string_attribute(file.get(), name, s);
    for (const auto& [name, v] : arrays.numbers) h5::write_double_attribute(file.get(), name, v);
    h5::close_file(file, path);
  });
}

}  // namespace vibrissa::io
