#pragma once
// Shared test helpers: locating the face model and the footage in
// ../shared (skipped with a message where absent, a failure under CI=true),
// temporary folders, and a process-wide model instance.
#include <gtest/gtest.h>

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "facecap/core/paths.hpp"
#include "facecap/model/face_model.hpp"

namespace facecap::test {

// The face model, loaded once per test program (through the cache), or
// nullptr when the model folder is absent.
const FaceModel* shared_model();

// Path of a file in the data folder, or nullopt when absent.
std::optional<std::filesystem::path> data_path(const std::string& name);

// A file's whole content ("" when it cannot be read).
std::string read_file(const std::filesystem::path& path);
// Its lines, without their line breaks (none when it cannot be read).
std::vector<std::string> read_lines(const std::filesystem::path& path);

}  // namespace facecap::test

// Skips the test (or fails it under CI=true) when the model is absent.
#define FACECAP_REQUIRE_MODEL(var)                                                                                  \
  const ::facecap::FaceModel* var = ::facecap::test::shared_model();                                                \
  if (var == nullptr) {                                                                                             \
    if (::facecap::running_under_ci()) FAIL() << "face model missing under CI: " << ::facecap::default_model_dir(); \
    GTEST_SKIP() << "face model not found at " << ::facecap::default_model_dir() << " (set FACECAP_MODEL_DIR)";     \
  }

// Skips the test (or fails it under CI=true) when a data file is absent.
#define FACECAP_REQUIRE_DATA(var, name)                                                        \
  const auto var##_opt = ::facecap::test::data_path(name);                                     \
  if (!var##_opt) {                                                                            \
    if (::facecap::running_under_ci()) FAIL() << "test data missing under CI: " << name;       \
    GTEST_SKIP() << "test data " << name << " not found in " << ::facecap::default_data_dir(); \
  }                                                                                            \
  const std::filesystem::path var = *var##_opt;
