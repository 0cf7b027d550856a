#pragma once
// Stable keys for caches: 64-bit FNV-1a over text (the same on every run and
// build, which std::hash does not promise), and the stamp of a source file
// whose change makes a cache made from it stale.
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

namespace facecap {

inline constexpr uint64_t kFnv1aSeed = 14695981039346656037ull;

// FNV-1a of `text`, continuing from `h` (chain calls to hash several texts).
uint64_t fnv1a(std::string_view text, uint64_t h = kFnv1aSeed);

// "<name>:<size in bytes>:<modification time>" of `file` (0 for what cannot
// be read): two stamps differ when the file was replaced or rewritten.
std::string file_stamp(const std::filesystem::path& file, const std::string& name);

}  // namespace facecap
