#pragma once
// A fresh temporary folder, removed with its contents on destruction (by
// whichever TempDir holds it then).
#include <filesystem>
#include <string>

namespace facecap {

class TempDir {
 public:
  explicit TempDir(const std::string& prefix = "facecap");
  ~TempDir();
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  // The folder goes with the move; the moved-from one owns none.
  TempDir(TempDir&& other) noexcept;
  TempDir& operator=(TempDir&& other) noexcept;
  const std::filesystem::path& path() const { return path_; }

 private:
  void remove() noexcept;
  std::filesystem::path path_;
};

}  // namespace facecap
