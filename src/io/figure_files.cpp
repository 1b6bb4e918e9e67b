#include "vibrissa/io/figure_files.hpp"

#include <stdexcept>
#include <system_error>

namespace vibrissa::io {

void remove_figures(const std::filesystem::path& dir, std::span<const std::string_view> names) {
  for (const std::string_view name : names) {
    const std::filesystem::path path = dir / name;
    std::error_code ec;
    std::filesystem::remove_all(path, ec);
    if (ec) throw std::runtime_error("cannot remove the older figure '" + path.string() + "': " + ec.message());
  }
}

}  // namespace vibrissa::io
