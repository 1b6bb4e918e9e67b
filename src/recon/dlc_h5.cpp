// DeepLabCut HDF5 tracks: see read_dlc_h5 in vibrissa/recon/tracks.hpp.
#include <stdexcept>

#include "vibrissa/recon/tracks.hpp"

namespace vibrissa::recon {

Tracks2D read_dlc_h5(const std::string& path, const std::vector<std::string>&, const std::string&) {
  // The column labels of a pandas table are stored as pickled Python objects, which the HDF5 C API cannot
  // decode; DeepLabCut writes the same data as CSV (docs/reconstruction.md, "Track files").
  throw std::invalid_argument(path + ": DeepLabCut HDF5 files are not read yet; use the CSV DeepLabCut writes "
                                     "beside it (or pandas: pd.read_hdf(path).to_csv(...))");
}

}  // namespace vibrissa::recon
