#include <filesystem>
#include <stdexcept>

#include "guarded_read.hpp"
#include "vibrissa/io/trial_io.hpp"

namespace vibrissa::io {

namespace {
std::string extension_of(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}
}  // namespace

trial::Trial read_trial(const std::string& path) {
  const std::string ext = extension_of(path);
  if (ext == ".csv") return read_trial_csv(path);
  // The libraries' parsers meet the file in a child process first (guarded_read.hpp).
  if (ext == ".h5" || ext == ".hdf5") return guarded_read(path, "libhdf5", [&] { return read_trial_h5(path); });
  if (ext == ".mat") return guarded_read(path, "matio", [&] { return read_trial_mat(path); });
  throw std::invalid_argument(path + ": unknown trial format '" + ext + "' (expected .csv, .h5, .hdf5 or .mat)");
}

void write_trial(const trial::Trial& trial, const std::string& path) {
  const std::string ext = extension_of(path);
  if (ext == ".csv") return write_trial_csv(trial, path);
  if (ext == ".h5" || ext == ".hdf5") return write_trial_h5(trial, path);
  if (ext == ".mat") return write_trial_mat(trial, path);
  throw std::invalid_argument(path + ": unknown trial format '" + ext + "' (expected .csv, .h5, .hdf5 or .mat)");
}

}  // namespace vibrissa::io
