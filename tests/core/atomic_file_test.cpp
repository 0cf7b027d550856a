#include "facecap/core/atomic_file.hpp"

#include <gtest/gtest.h>

#include <csignal>
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <optional>

#include "facecap/core/error.hpp"
#include "facecap/core/interrupt.hpp"
#include "facecap/core/temp_dir.hpp"
#include "facecap/core/temp_files.hpp"
#include "test_support.hpp"

namespace facecap {

using test::read_file;

TEST(AtomicFile, CommitReplacesTheFinalFile) {
  TempDir dir;
  const auto path = dir.path() / "out.txt";
  write_text_file(path, "old");
  write_text_file(path, "new");
  EXPECT_EQ(read_file(path), "new");
}

TEST(AtomicFile, AbandonedWriteLeavesTheOldFileAndNoTemporary) {
  TempDir dir;
  const auto path = dir.path() / "out.mp4";
  write_text_file(path, "good");
  {
    AtomicFile f(path);
    std::ofstream(f.temp_path()) << "half-written";
    EXPECT_EQ(f.temp_path().extension(), ".mp4");  // tools that pick formats by name still work
  }
  EXPECT_EQ(read_file(path), "good");
  int files = 0;
  for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir.path())) ++files;
  EXPECT_EQ(files, 1);
}

// write_file puts what its filler writes under the final name; where the
// writing fails (a stream gone bad, as a full disk leaves it) it throws and
// the file that was there stays, with no temporary beside it.
TEST(AtomicFile, AFailedWriteLeavesTheOldFileAndSaysSo) {
  TempDir dir;
  const auto path = dir.path() / "out.bin";
  write_file(path, [](std::ostream& out) { out << "good"; });
  EXPECT_EQ(read_file(path), "good");
  try {
    write_file(path, [](std::ostream& out) {
      out << "half";
      out.setstate(std::ios::badbit);
    });
    ADD_FAILURE() << "expected an error";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), write_failure(path));
  }
  EXPECT_EQ(read_file(path), "good");
  int files = 0;
  for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir.path())) ++files;
  EXPECT_EQ(files, 1);
}

// The message names a full file system, the usual reason a write fails once
// its file is open, and only where it is full.
TEST(AtomicFile, AWriteFailureSaysWhenTheFileSystemIsFull) {
  EXPECT_EQ(full_disk_note(12 * 1024), "its file system is full (12 KiB free)");
  EXPECT_EQ(full_disk_note(0), "its file system is full (0 KiB free)");
  EXPECT_EQ(full_disk_note((1 << 20) - 1), "its file system is full (1023 KiB free)");
  EXPECT_EQ(full_disk_note(1 << 20), "");
  TempDir dir;  // a folder with room
  EXPECT_EQ(full_disk_note(dir.path() / "out.csv"), "");
  EXPECT_EQ(write_failure(dir.path() / "out.csv"), "cannot write " + (dir.path() / "out.csv").string());
}

// A second Ctrl-C quits at once, skipping the destructors: its handler
// removes what is still registered, and only that.
TEST(AtomicFile, QuittingAtOnceRemovesTheTemporariesOnly) {
  TempDir dir;
  const auto committed = dir.path() / "done.txt";
  const auto loose = dir.path() / "loose.log";
  std::ofstream(loose) << "a log that was let go";
  AtomicFile open(dir.path() / "out.mp4");
  std::ofstream(open.temp_path()) << "half-written";
  std::optional<AtomicFile> done;
  done.emplace(committed);
  std::ofstream(done->temp_path()) << "complete";
  done->commit();
  std::optional<RegisteredTempFile> log;
  log.emplace(loose);
  log.reset();  // unregistered: no longer the handler's to remove
  const auto kept = dir.path() / "kept.log";
  std::ofstream(kept) << "registered";
  RegisteredTempFile registered(kept);

  remove_registered_temp_files();
  EXPECT_FALSE(std::filesystem::exists(open.temp_path()));
  EXPECT_FALSE(std::filesystem::exists(kept));
  EXPECT_EQ(read_file(committed), "complete");
  EXPECT_TRUE(std::filesystem::exists(loose));
}

// The whole path: Ctrl-C twice in a process writing a file exits at once
// (130), and the temporary is gone.
TEST(AtomicFileDeathTest, ASecondInterruptQuitsAtOnceAndLeavesNoTemporary) {
  TempDir dir;
  const auto path = dir.path() / "out.mp4";
  EXPECT_EXIT(
      {
        install_interrupt_handler();
        AtomicFile f(path);
        std::ofstream(f.temp_path()) << "half-written";
        std::raise(SIGINT);  // the job would stop cleanly at its next frame...
        std::raise(SIGINT);  // ...but the user insists
        std::_Exit(0);
      },
      testing::ExitedWithCode(130), "");
  int files = 0;
  for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir.path())) ++files;
  EXPECT_EQ(files, 0);
}

TEST(AtomicFile, UnwritableFolderIsAClearError) {
  EXPECT_THROW(AtomicFile("/proc/facecap-no-such-dir/out.txt"), Error);
  TempDir dir;
  const auto file = dir.path() / "plain";
  write_text_file(file, "x");
  try {
    AtomicFile f(file / "out.txt");
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("not a folder"), std::string::npos) << e.what();
  }
}

// An output path that names a folder fails when the output is opened, before
// the work that would fill it, and the folder is left as it was.
TEST(AtomicFile, AFolderAsTheOutputIsAClearErrorUpFront) {
  TempDir dir;
  const auto folder = dir.path() / "out.mp4";
  std::filesystem::create_directories(folder);
  write_text_file(folder / "kept.txt", "x");
  for (const auto& check : {+[](const std::filesystem::path& p) { AtomicFile f(p); },
                            +[](const std::filesystem::path& p) { ensure_writable_file(p); }}) {
    try {
      check(folder);
      ADD_FAILURE() << "expected an error";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("is a folder"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(folder.string()), std::string::npos) << e.what();
    }
  }
  EXPECT_EQ(read_file(folder / "kept.txt"), "x");
  EXPECT_NO_THROW(ensure_writable_file(dir.path() / "new" / "out.glb"));  // a missing folder is made
}

// The folders a job made go again unless it completes: empty ones only, or
// with what they hold; one that was there before stays either way.
TEST(FoldersMadeHere, AJobThatDoesNotCompleteLeavesNoFolderItMade) {
  TempDir dir;
  const std::filesystem::path before = dir.path() / "before", filled = dir.path() / "filled",
                              empty = dir.path() / "empty";
  std::filesystem::create_directories(before);
  for (const bool with_contents : {false, true}) {
    {
      FoldersMadeHere made(with_contents);
      for (const auto& d : {before, filled, empty}) {
        made.add(d);
        std::filesystem::create_directories(d);
      }
      std::ofstream(filled / "frames.csv") << "half";
    }
    EXPECT_TRUE(std::filesystem::exists(before));
    EXPECT_FALSE(std::filesystem::exists(empty)) << with_contents;
    EXPECT_EQ(std::filesystem::exists(filled), !with_contents);
    std::filesystem::remove_all(filled);
  }
  {
    FoldersMadeHere made(true);
    made.add(filled);
    std::filesystem::create_directories(filled);
    std::ofstream(filled / "frames.csv") << "whole";
    made.keep();
  }
  EXPECT_TRUE(std::filesystem::exists(filled / "frames.csv"));
}

}  // namespace facecap
