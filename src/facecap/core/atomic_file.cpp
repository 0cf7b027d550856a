#include "facecap/core/atomic_file.hpp"

#include <unistd.h>

#include <atomic>
#include <fstream>
#include <iterator>

#include "facecap/core/error.hpp"

namespace facecap {

namespace fs = std::filesystem;

void ensure_writable_dir(const fs::path& dir) {
  const fs::path d = dir.empty() ? fs::path(".") : dir;
  std::error_code ec;
  if (fs::exists(d, ec) && !fs::is_directory(d, ec)) throw Error("output folder is not a folder: " + d.string());
  if (!fs::exists(d, ec)) {
    fs::create_directories(d, ec);
    if (ec) throw Error("cannot create output folder " + d.string() + ": " + ec.message());
  }
  if (::access(d.c_str(), W_OK) != 0) throw Error("output folder is not writable: " + d.string());
}

void ensure_writable_file(const fs::path& path) {
  ensure_writable_dir(path.parent_path());
  std::error_code ec;
  if (fs::is_directory(path, ec)) throw Error("cannot write " + path.string() + ": it is a folder");
}

void ensure_not_an_input(const fs::path& output, const std::vector<std::string>& inputs) {
  for (const std::string& input : inputs) {
    std::error_code ec;
    if (fs::equivalent(output, fs::path(input), ec) && !ec)
      throw Error("output " + output.string() + " is the input " + input +
                  ": write it under another name (the input would be replaced)");
  }
}

AtomicFile::AtomicFile(fs::path final_path) : final_(std::move(final_path)) {
  ensure_writable_file(final_);
  static std::atomic<int> counter{0};
  // Keep the extension last so that tools choosing a format by name (ffmpeg, OpenCV) still do.
  const std::string tag = ".partial-" + std::to_string(::getpid()) + "-" + std::to_string(counter++);
  temp_ = final_.parent_path() / (final_.stem().string() + tag + final_.extension().string());
  registered_.emplace(temp_);
}

AtomicFile::~AtomicFile() {
  if (!committed_) {
    std::error_code ec;
    fs::remove(temp_, ec);
  }
}

void AtomicFile::commit() {
  std::error_code ec;
  if (!fs::exists(temp_, ec)) throw Error("nothing was written to " + final_.string());
  fs::rename(temp_, final_, ec);
  if (ec) throw Error("cannot write " + final_.string() + ": " + ec.message());
  committed_ = true;
  registered_.reset();
}

fs::path StagedFiles::stage(const fs::path& final_path) {
  files_.push_back(std::make_unique<AtomicFile>(final_path));
  return files_.back()->temp_path();
}

void StagedFiles::commit() {
  for (const std::unique_ptr<AtomicFile>& file : files_) {
    std::error_code ec;
    if (fs::exists(file->temp_path(), ec)) file->commit();
  }
  files_.clear();
}

void FoldersMadeHere::add(const fs::path& dir) {
  std::error_code ec;
  if (!fs::exists(dir, ec)) folders_.push_back(dir);
}

FoldersMadeHere::~FoldersMadeHere() {
  if (keep_) return;
  std::error_code ec;
  for (auto it = folders_.rbegin(); it != folders_.rend(); ++it) {
    if (with_contents_)
      fs::remove_all(*it, ec);
    else
      fs::remove(*it, ec);  // only if empty
  }
}

void write_file(const fs::path& path, const std::function<void(std::ostream& out)>& fill) {
  AtomicFile file(path);
  {
    std::ofstream out(file.temp_path(), std::ios::binary);
    if (!out) throw Error("cannot write " + path.string());
    fill(out);
    if (!out.flush()) throw Error(write_failure(path));
  }
  file.commit();
}

void write_binary_file(const fs::path& path, const void* data, size_t bytes) {
  write_file(path, [&](std::ostream& out) { out.write(static_cast<const char*>(data), std::streamsize(bytes)); });
}

std::string full_disk_note(const fs::path& path) {
  std::error_code ec;
  const fs::space_info space = fs::space(path.parent_path().empty() ? fs::path(".") : path.parent_path(), ec);
  return ec ? "" : full_disk_note(space.available);
}

std::string full_disk_note(std::uintmax_t bytes_free) {
  // Below this, what failed is taken to be the want of room: a write that
  // fails for lack of it leaves at most a few blocks.
  constexpr std::uintmax_t kFullBelow = 1 << 20;
  if (bytes_free >= kFullBelow) return "";
  return "its file system is full (" + std::to_string(bytes_free / 1024) + " KiB free)";
}

std::string write_failure(const fs::path& path) {
  const std::string full = full_disk_note(path);
  return "cannot write " + path.string() + (full.empty() ? "" : ": " + full);
}

std::optional<std::vector<unsigned char>> read_binary_file(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  return std::vector<unsigned char>((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

void write_text_file(const fs::path& path, const std::string& text) {
  write_binary_file(path, text.data(), text.size());
}

}  // namespace facecap
