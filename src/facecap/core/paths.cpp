#include "facecap/core/paths.hpp"

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <string>

#ifndef FACECAP_SOURCE_DIR
#define FACECAP_SOURCE_DIR "."
#endif

namespace facecap {

namespace fs = std::filesystem;

namespace {

fs::path from_env_or_shared(const char* env, const char* shared_sub) {
  if (const char* v = std::getenv(env); v != nullptr && *v != '\0') return fs::path(v);
  const fs::path beside_source = fs::path(FACECAP_SOURCE_DIR) / ".." / "shared" / shared_sub;
  std::error_code ec;
  if (fs::exists(beside_source, ec)) return fs::weakly_canonical(beside_source, ec);
  return fs::path("..") / "shared" / shared_sub;
}

}  // namespace

fs::path default_model_dir() { return from_env_or_shared("FACECAP_MODEL_DIR", "models/ict-facekit"); }

fs::path default_data_dir() { return from_env_or_shared("FACECAP_DATA_DIR", "data"); }

fs::path cache_dir() {
  if (const char* v = std::getenv("FACECAP_CACHE_DIR"); v != nullptr && *v != '\0') return fs::path(v);
  if (const char* v = std::getenv("XDG_CACHE_HOME"); v != nullptr && *v != '\0') return fs::path(v) / "facecap";
  if (const char* v = std::getenv("HOME"); v != nullptr && *v != '\0') return fs::path(v) / ".cache" / "facecap";
  return fs::temp_directory_path() / "facecap-cache";
}

std::optional<fs::path> data_file(const std::string& name) {
  const fs::path p = default_data_dir() / name;
  std::error_code ec;
  if (fs::is_regular_file(p, ec)) return p;
  return std::nullopt;
}

bool running_under_ci() {
  const char* v = std::getenv("CI");
  return v != nullptr && (std::string(v) == "true" || std::string(v) == "1");
}

std::optional<std::string_view> numbered_name_digits(std::string_view name, std::string_view prefix,
                                                     std::string_view suffix) {
  if (name.size() <= prefix.size() + suffix.size() || !name.starts_with(prefix) || !name.ends_with(suffix))
    return std::nullopt;
  const std::string_view digits = name.substr(prefix.size(), name.size() - prefix.size() - suffix.size());
  if (!std::all_of(digits.begin(), digits.end(), [](unsigned char c) { return std::isdigit(c) != 0; }))
    return std::nullopt;
  return digits;
}

}  // namespace facecap
