// libFuzzer harness: the Janelia Whisker Tracker readers (.whiskers binary/text, .measurements; docs/
// reconstruction.md, "Track files") on arbitrary bytes. Seeds: files the tracker wrote (tests/data/janelia).
#include <cstdint>
#include <string_view>

#include "fuzz_contract.hpp"
#include "vibrissa/recon/tracks.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  const auto whiskers = vibrissa::fuzz::input_file(bytes, ".whiskers");
  vibrissa::fuzz::expect_no_crash([&] {
    for (const auto& s : vibrissa::recon::read_whiskers(whiskers.string()))
      if (s.x.size() != s.y.size() || s.x.size() != s.thick.size() || s.x.size() != s.score.size())
        vibrissa::fuzz::finding("segment arrays of different lengths");
  });
  const auto measurements = vibrissa::fuzz::input_file(bytes, ".measurements");
  vibrissa::fuzz::expect_no_crash([&] {
    (void)vibrissa::recon::read_measurements(measurements.string());
  });
  return 0;
}
