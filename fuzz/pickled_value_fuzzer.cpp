// libFuzzer harness: the bounded pickle reader behind the DeepLabCut HDF5 reader (src/recon/pickled_value.hpp)
// on arbitrary bytes. Seeds: the column labels Python pickled with protocols 0-5 (tests/data/deeplabcut).
#include <cstdint>
#include <string_view>

#include "fuzz_contract.hpp"
#include "recon/pickled_value.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  vibrissa::fuzz::expect_no_crash([&] {
    (void)vibrissa::recon::read_pickle(std::string_view(reinterpret_cast<const char*>(data), size), "fuzz input");
  });
  return 0;
}
