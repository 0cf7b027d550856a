#include "facecap/pipeline/identity_file.hpp"

#include <gtest/gtest.h>

#include <fstream>

#include "facecap/core/error.hpp"
#include "facecap/core/temp_dir.hpp"

namespace facecap {
namespace {

namespace fs = std::filesystem;

TEST(IdentityFile, ReadsTheWeightsAndNamesWhatIsWrong) {
  TempDir dir;
  const fs::path good = dir.path() / "identity.json";
  std::ofstream(good) << R"({"format": "facecap-identity", "identity_weights": [0.5, -1.25, 2]})";
  const Eigen::VectorXd w = read_identity_weights(good);
  ASSERT_EQ(w.size(), 3);
  EXPECT_EQ(w[1], -1.25);
  const std::pair<const char*, const char*> bad[] = {
      {"missing.json", nullptr},
      {"text.json", "identity"},
      {"other.json", R"({"focal_px": 1500})"},
      {"empty.json", R"({"identity_weights": []})"},
      {"strings.json", R"({"identity_weights": [1, "two"]})"},
  };
  for (const auto& [name, content] : bad) {
    if (content != nullptr) std::ofstream(dir.path() / name) << content;
    try {
      read_identity_weights(dir.path() / name);
      ADD_FAILURE() << name;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();  // names the file
    }
  }
}

}  // namespace
}  // namespace facecap
