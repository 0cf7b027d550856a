#pragma once
// A point cache: one mesh's vertex positions at every frame, in the PC2
// format (3ds Max's Point Cache 2, read by Blender's Mesh Cache modifier,
// Maya, Houdini and Cinema 4D), streamed to disk a frame at a time. The
// mesh itself (topology, UVs) is a separate file whose vertex order the
// cache follows.
//
// Layout, little-endian: "POINTCACHE2\0", int32 version 1, int32 points,
// float32 start frame, float32 sampling (frames between samples), int32
// samples; then each sample's points as float32 x y z.
#include <cstdio>
#include <filesystem>
#include <memory>

#include "facecap/core/geometry.hpp"

namespace facecap {

class PointCacheWriter {
 public:
  // Writes to `path` as samples come (the header's sample count is filled in
  // by finish()): give it a staged name (atomic_file.hpp) where the file must
  // appear only whole. Throws facecap::Error where it cannot be written.
  PointCacheWriter(const std::filesystem::path& path, int points, float start_frame, float sampling = 1.0f);
  ~PointCacheWriter();
  PointCacheWriter(const PointCacheWriter&) = delete;
  PointCacheWriter& operator=(const PointCacheWriter&) = delete;

  // One sample: 3 x points, finite (throws facecap::Error otherwise, adding
  // nothing).
  void append(const Positions& points);
  int samples() const { return samples_; }
  // The header's count filled in and the file closed; nothing may follow.
  void finish();

 private:
  struct FileCloser {
    void operator()(std::FILE* f) const { std::fclose(f); }
  };
  std::filesystem::path path_;
  std::unique_ptr<std::FILE, FileCloser> file_;
  int points_ = 0;
  int samples_ = 0;
};

}  // namespace facecap
