#include "test_support.hpp"

#include <fstream>
#include <memory>
#include <mutex>
#include <sstream>

#include "facecap/model/model_cache.hpp"

namespace facecap::test {

const FaceModel* shared_model() {
  static std::once_flag once;
  static std::unique_ptr<FaceModel> model;
  std::call_once(once, [] {
    std::error_code ec;
    if (!std::filesystem::exists(default_model_dir() / "vertex_indices.json", ec)) return;
    model = std::make_unique<FaceModel>(load_face_model(default_model_dir()));
  });
  return model.get();
}

std::optional<std::filesystem::path> data_path(const std::string& name) { return data_file(name); }

std::string read_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::vector<std::string> read_lines(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

}  // namespace facecap::test
