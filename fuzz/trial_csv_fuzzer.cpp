// libFuzzer harness: the trial CSV reader (docs/trials.md) on arbitrary bytes.
#include <cstdint>
#include <string_view>

#include "fuzz_contract.hpp"
#include "vibrissa/io/trial_io.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = vibrissa::fuzz::input_file(std::string_view(reinterpret_cast<const char*>(data), size), ".csv");
  vibrissa::fuzz::expect_no_crash([&] {
    const vibrissa::trial::Trial t = vibrissa::io::read_trial(path.string());
    vibrissa::trial::validate(t);  // a trial the reader returns is always valid
  });
  return 0;
}
