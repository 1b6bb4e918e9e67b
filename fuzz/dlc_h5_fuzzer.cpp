// libFuzzer harness: the DeepLabCut HDF5 track reader (docs/reconstruction.md, "Track files") on arbitrary
// bytes. Seeds: the pandas-written tables of tests/data/deeplabcut (deflated, under -max_len).
#include <cstdint>
#include <string_view>

#include "fuzz_contract.hpp"
#include "vibrissa/recon/tracks.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = vibrissa::fuzz::input_file(std::string_view(reinterpret_cast<const char*>(data), size), ".h5");
  vibrissa::fuzz::expect_no_crash([&] {
    for (const char* individual : {"", "mouse2"}) {
      const vibrissa::recon::Tracks2D t = vibrissa::recon::read_dlc_h5(path.string(), {}, individual);
      for (const auto& f : t.frames)
        if (f.points_px.size() != f.likelihood.size()) vibrissa::fuzz::finding("points and likelihoods differ");
    }
  });
  return 0;
}
