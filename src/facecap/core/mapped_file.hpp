#pragma once
// A file mapped read-only into memory for as long as the object lives: its
// bytes without copying them, for large caches read whole at start-up. The
// file's pages are mapped on opening (MAP_POPULATE). A file replaced by a
// rename while mapped is harmless (the mapping keeps the old one); one cut
// short in place by another process is not, which facecap's own writers never
// do (they write atomically, core/atomic_file.hpp).
#include <cstddef>
#include <filesystem>
#include <span>

namespace facecap {

class MappedFile {
 public:
  // Throws facecap::Error naming the file when it cannot be opened or mapped,
  // or is empty.
  explicit MappedFile(const std::filesystem::path& path);
  ~MappedFile();
  MappedFile(const MappedFile&) = delete;
  MappedFile& operator=(const MappedFile&) = delete;

  std::span<const std::byte> bytes() const { return {data_, size_}; }

 private:
  const std::byte* data_ = nullptr;
  size_t size_ = 0;
};

}  // namespace facecap
