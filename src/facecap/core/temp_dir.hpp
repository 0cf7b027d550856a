#pragma once
// A fresh temporary folder, removed with its contents on destruction.
#include <filesystem>
#include <string>

namespace facecap {

class TempDir {
 public:
  explicit TempDir(const std::string& prefix = "facecap");
  ~TempDir();
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

}  // namespace facecap
