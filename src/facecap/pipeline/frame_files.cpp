#include "facecap/pipeline/frame_files.hpp"

#include <cstdio>

namespace facecap {

namespace fs = std::filesystem;

std::string frame_file_name(int frame, const char* extension) {
  char name[64];
  std::snprintf(name, sizeof(name), "frame_%06d.%s", frame, extension);
  return name;
}

void remove_unwritten_frame_files(const fs::path& dir, std::initializer_list<const char*> extensions,
                                  const std::unordered_set<std::string>& written) {
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(dir, ec)) {
    const std::string name = entry.path().filename().string();
    if (!name.starts_with("frame_") || written.contains(name)) continue;
    for (const char* extension : extensions)
      if (name.ends_with(std::string(".") + extension)) fs::remove(entry.path(), ec);
  }
}

}  // namespace facecap
