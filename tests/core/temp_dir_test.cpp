#include "facecap/core/temp_dir.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <optional>
#include <utility>

namespace facecap {

namespace fs = std::filesystem;

// The folder and what is in it go with the TempDir that holds it last.
TEST(TempDir, TheFolderIsRemovedOnceByWhicheverHoldsItLast) {
  fs::path folder;
  {
    std::optional<TempDir> moved;
    {
      TempDir first("facecap-test");
      folder = first.path();
      std::ofstream(folder / "file.txt") << "kept while held";
      moved.emplace(std::move(first));
      EXPECT_TRUE(first.path().empty());
    }  // the moved-from one owns nothing: the folder stays
    ASSERT_TRUE(fs::exists(folder / "file.txt"));
    EXPECT_EQ(moved->path(), folder);

    TempDir other("facecap-test");
    const fs::path other_folder = other.path();
    other = std::move(*moved);  // the folder other held goes now
    EXPECT_FALSE(fs::exists(other_folder));
    EXPECT_EQ(other.path(), folder);
    EXPECT_TRUE(fs::exists(folder));
  }
  EXPECT_FALSE(fs::exists(folder));
}

}  // namespace facecap
