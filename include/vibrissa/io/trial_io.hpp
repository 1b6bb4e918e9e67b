#pragma once
// Reading and writing trials (docs/trials.md): CSV with '#' metadata lines, HDF5, and MATLAB .mat (read
// and write). Readers convert the file's declared units to SI and validate; every error names the file,
// the row and the column. Writers write to a temporary name and rename at the end, so an interrupted
// write never leaves a file that looks complete.
#include <string>

#include "vibrissa/trial/format.hpp"

namespace vibrissa::io {

trial::Trial read_trial_csv(const std::string& path);
void write_trial_csv(const trial::Trial& trial, const std::string& path);

trial::Trial read_trial_h5(const std::string& path);
void write_trial_h5(const trial::Trial& trial, const std::string& path);

trial::Trial read_trial_mat(const std::string& path);
void write_trial_mat(const trial::Trial& trial, const std::string& path);

/// Dispatch on the extension: .csv, .h5/.hdf5, .mat. Unknown extensions throw std::invalid_argument.
trial::Trial read_trial(const std::string& path);
void write_trial(const trial::Trial& trial, const std::string& path);

/// Writes through `write(tmp_path)` to a temporary sibling of `path`, then renames it into place; removes
/// the temporary file if `write` throws.
template <class F>
void write_atomically(const std::string& path, F&& write);
std::string temporary_sibling(const std::string& path);
void commit_temporary(const std::string& tmp_path, const std::string& path);
void discard_temporary(const std::string& tmp_path) noexcept;

template <class F>
void write_atomically(const std::string& path, F&& write) {
  const std::string tmp = temporary_sibling(path);
  try {
    write(tmp);
  } catch (...) {
    discard_temporary(tmp);
    throw;
  }
  commit_temporary(tmp, path);
}

}  // namespace vibrissa::io
