#include "facecap/core/fingerprint.hpp"

namespace facecap {

uint64_t fnv1a(std::string_view text, uint64_t h) {
  for (const unsigned char c : text) {
    h ^= c;
    h *= 1099511628211ull;
  }
  return h;
}

std::string file_stamp(const std::filesystem::path& file, const std::string& name) {
  std::error_code ec;
  const auto size = std::filesystem::file_size(file, ec);
  const auto mtime = std::filesystem::last_write_time(file, ec).time_since_epoch().count();
  return name + ":" + std::to_string(ec ? 0 : size) + ":" + std::to_string(mtime);
}

}  // namespace facecap
