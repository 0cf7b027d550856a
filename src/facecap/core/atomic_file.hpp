#pragma once
// Write-then-rename output: the content goes to a temporary name beside the
// final path and is renamed over it only by commit(), so a failed or
// interrupted run never leaves a half-written file under the final name (and
// never destroys a good file that was there). Uncommitted temporaries are
// removed by the destructor.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <iosfwd>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "facecap/core/temp_files.hpp"

namespace facecap {

class AtomicFile {
 public:
  // Checks that the destination can be written (ensure_writable_file).
  explicit AtomicFile(std::filesystem::path final_path);
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  const std::filesystem::path& temp_path() const { return temp_; }
  const std::filesystem::path& final_path() const { return final_; }
  void commit();

 private:
  std::filesystem::path final_;
  std::filesystem::path temp_;
  std::optional<RegisteredTempFile> registered_;  // until committed
  bool committed_ = false;
};

// Files that appear together when a job completes: each is written under a
// temporary name when it is ready (stage()), and all are renamed into place
// by commit(). Until then, and if the job fails, none of them shows (the
// destructor removes what was written), so a run that fails after a shot cut
// leaves no later shot's file beside an earlier run's others.
class StagedFiles {
 public:
  // Where to write `final_path`'s content now (any writer, even one that
  // itself writes atomically): renamed to final_path by commit().
  std::filesystem::path stage(const std::filesystem::path& final_path);
  // Renames every staged file that was written; one that was not is skipped.
  void commit();

 private:
  std::vector<std::unique_ptr<AtomicFile>> files_;
};

// The folders a job makes for its outputs (add() before each is made),
// removed again unless the job completes (keep()), so that one that fails or
// is interrupted leaves none of them; a folder that was there before is never
// removed. `with_contents`: removed with what they hold, for a job whose
// folders fill as it goes (track --each-image); else only while empty, for
// one whose files appear only as it completes (track --all-faces).
class FoldersMadeHere {
 public:
  explicit FoldersMadeHere(bool with_contents = false) : with_contents_(with_contents) {}
  ~FoldersMadeHere();
  FoldersMadeHere(const FoldersMadeHere&) = delete;
  FoldersMadeHere& operator=(const FoldersMadeHere&) = delete;

  void add(const std::filesystem::path& dir);
  void keep() { keep_ = true; }

 private:
  std::vector<std::filesystem::path> folders_;  // the innermost last
  bool with_contents_ = false;
  bool keep_ = false;
};

// Throws facecap::Error unless `dir` exists (or can be created) and is writable.
void ensure_writable_dir(const std::filesystem::path& dir);

// Throws facecap::Error unless `path` can be written: its folder exists (or
// can be created) and is writable, and the path is not itself a folder. For
// checking an output before the work that fills it.
void ensure_writable_file(const std::filesystem::path& path);

// Throws facecap::Error when `output` names the same file as one of `inputs`
// (by identity: another spelling or a link to it counts), as in
// `transform in.mp4 -o in.mp4`: the committed output would replace what the
// run reads. Inputs that are no file (cam:0, a missing path) never match.
void ensure_not_an_input(const std::filesystem::path& output, const std::vector<std::string>& inputs);

// Writes `path` atomically (AtomicFile), its content put on a binary stream
// by `fill`; throws facecap::Error where writing fails (write_failure).
void write_file(const std::filesystem::path& path, const std::function<void(std::ostream& out)>& fill);
// Writes text, or bytes, atomically.
void write_text_file(const std::filesystem::path& path, const std::string& text);
void write_binary_file(const std::filesystem::path& path, const void* data, size_t bytes);

// "its file system is full (12 KiB free)" where the file system that holds
// `path` has under 1 MiB free, the usual reason a write fails once its file
// is open; "" where it has room. The second form takes the bytes free as given.
std::string full_disk_note(const std::filesystem::path& path);
std::string full_disk_note(std::uintmax_t bytes_free);
// The message for a write to `path` that failed once the file was open:
// "cannot write PATH", and the note above where it has one.
std::string write_failure(const std::filesystem::path& path);
// Its reading twin: the whole of a file's bytes, or nothing where it cannot
// be opened.
std::optional<std::vector<unsigned char>> read_binary_file(const std::filesystem::path& path);

}  // namespace facecap
