#pragma once
// Reading and writing trials (docs/trials.md): CSV with '#' metadata lines, HDF5, and MATLAB .mat (read
// and write). Readers convert the file's declared units to SI and validate; every error names the file,
// the row and the column. Writers are atomic (io/atomic_file.hpp): an interrupted write never leaves a file
// that looks complete.
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

}  // namespace vibrissa::io
