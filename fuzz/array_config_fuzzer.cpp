// libFuzzer harness: the array configuration reader (docs/array.md) on arbitrary JSON text.
#include <cstdint>
#include <filesystem>
#include <string_view>

#include "fuzz_contract.hpp"
#include "vibrissa/io/array_config.hpp"
#include "vibrissa/io/json_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  vibrissa::fuzz::expect_no_crash([&] {
    const auto j = vibrissa::io::parse_json_text(text, "fuzz", true);
    // Morphology tables named by the config are looked up in an empty directory.
    const auto config = vibrissa::io::array_config_from_json(j, std::filesystem::temp_directory_path() / "vibrissa-fuzz-none");
    vibrissa::array::validate(config);
  });
  return 0;
}
