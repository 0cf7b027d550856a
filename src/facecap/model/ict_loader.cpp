#include "facecap/model/ict_loader.hpp"

#include <fstream>
#include <mutex>
#include <nlohmann/json.hpp>

#include "facecap/core/error.hpp"
#include "facecap/core/parallel.hpp"
#include "facecap/model/obj_reader.hpp"

namespace facecap {

namespace fs = std::filesystem;

namespace {

constexpr const char* kIndexFile = "vertex_indices.json";
constexpr const char* kNeutralStem = "generic_neutral_mesh";

// Jawline candidates of FACTS.md (from the ICT-FaceKit release notes).
const std::vector<int> kJawRight{1278, 1272, 12, 1834, 243, 781, 2199, 1447};
const std::vector<int> kJawLeft{3661, 4390, 3022, 2484, 4036, 2253, 3490, 3496};
const std::vector<int> kJawRightExtended{1280, 1278, 1275, 1272, 1248, 12,  820,  1834, 1902,
                                         243,  844,  781,  1673, 2199, 801, 1447, 800};
const std::vector<int> kJawLeftExtended{3041, 3661, 3042, 4390, 3880, 3022, 3085, 2484, 4102,
                                        4036, 3061, 2253, 3466, 3490, 3493, 3496, 3498};

fs::path resolve(const fs::path& dir, const std::string& stem) {
  const fs::path plain = dir / (stem + ".obj");
  if (fs::exists(plain)) return plain;
  const fs::path gz = dir / (stem + ".obj.gz");
  if (fs::exists(gz)) return gz;
  throw Error("model file missing: " + gz.string() + " (nor " + plain.filename().string() + ")");
}

nlohmann::json read_index(const fs::path& dir) {
  const fs::path path = dir / kIndexFile;
  std::ifstream in(path);
  if (!in) throw Error("model file missing: " + path.string());
  try {
    return nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    throw Error("corrupt model file " + path.string() + ": " + e.what());
  }
}

std::vector<int> int_list(const nlohmann::json& index, const char* key, const fs::path& dir) {
  if (!index.contains(key) || !index[key].is_array()) {
    throw Error("model file " + (dir / kIndexFile).string() + " lacks the list \"" + key + "\"");
  }
  return index[key].get<std::vector<int>>();
}

std::vector<std::string> expression_list(const nlohmann::json& index, const fs::path& dir) {
  if (!index.contains("expressions") || !index["expressions"].is_array()) {
    throw Error("model file " + (dir / kIndexFile).string() + " lacks the list \"expressions\"");
  }
  return index["expressions"].get<std::vector<std::string>>();
}

void check_dir(const fs::path& dir) {
  std::error_code ec;
  if (!fs::exists(dir, ec)) {
    throw Error("face model folder not found: " + dir.string() +
                " (set FACECAP_MODEL_DIR or --model-dir; scripts/fetch-model.sh downloads it)");
  }
  if (!fs::is_directory(dir, ec)) throw Error("face model path is not a folder: " + dir.string());
}

}  // namespace

std::vector<fs::path> ict_source_files(const fs::path& dir, const IctLoadOptions& options) {
  check_dir(dir);
  const nlohmann::json index = read_index(dir);
  std::vector<fs::path> files{dir / kIndexFile, resolve(dir, kNeutralStem)};
  for (int i = 0; i < options.num_identity; ++i) {
    char stem[32];
    std::snprintf(stem, sizeof(stem), "identity%03d", i);
    files.push_back(resolve(dir, stem));
  }
  for (const std::string& name : expression_list(index, dir)) files.push_back(resolve(dir, name));
  return files;
}

FaceModel load_ict_model(const fs::path& dir, const IctLoadOptions& options) {
  check_dir(dir);
  const nlohmann::json index = read_index(dir);
  FaceModel model;
  model.expression_names = expression_list(index, dir);
  if (model.expression_names.empty())
    throw Error("model file " + (dir / kIndexFile).string() + " lists no expressions");

  const fs::path neutral_path = resolve(dir, kNeutralStem);
  ObjData neutral = read_obj(neutral_path);
  if (neutral.num_vertices() != kIctVertexCount) {
    throw Error("model file " + neutral_path.string() + " has " + std::to_string(neutral.num_vertices()) +
                " vertices, expected " + std::to_string(kIctVertexCount));
  }
  if (static_cast<int>(neutral.polygons.size()) != kIctPolygonCount) {
    throw Error("model file " + neutral_path.string() + " has " + std::to_string(neutral.polygons.size()) +
                " polygons, expected " + std::to_string(kIctPolygonCount));
  }
  const int n = neutral.num_vertices();
  model.num_vertices = n;
  model.neutral = Eigen::Map<const Eigen::VectorXf>(neutral.positions.data(), 3 * n);
  model.polygons = std::move(neutral.polygons);
  model.uvs = std::move(neutral.uvs);

  // Blendshape targets: identities then expressions, each stored as an offset from the neutral.
  std::vector<fs::path> targets;
  for (int i = 0; i < options.num_identity; ++i) {
    char stem[32];
    std::snprintf(stem, sizeof(stem), "identity%03d", i);
    targets.push_back(resolve(dir, stem));
  }
  for (const std::string& name : model.expression_names) targets.push_back(resolve(dir, name));

  model.identity_basis.resize(3 * n, options.num_identity);
  model.expression_basis.resize(3 * n, static_cast<Eigen::Index>(model.expression_names.size()));
  std::mutex error_mutex;
  std::string first_error;
  parallel_for(
      static_cast<int>(targets.size()),
      [&](int begin, int end) {
        for (int t = begin; t < end; ++t) {
          try {
            const ObjData obj = read_obj(targets[t], {.read_topology = false});
            if (obj.num_vertices() != n) {
              throw Error("model file " + targets[t].string() + " has " + std::to_string(obj.num_vertices()) +
                          " vertices, expected " + std::to_string(n));
            }
            const Eigen::VectorXf offset =
                Eigen::Map<const Eigen::VectorXf>(obj.positions.data(), 3 * n) - model.neutral;
            if (t < options.num_identity) {
              model.identity_basis.col(t) = offset;
            } else {
              model.expression_basis.col(t - options.num_identity) = offset;
            }
          } catch (const Error& e) {
            std::lock_guard lock(error_mutex);
            if (first_error.empty()) first_error = e.what();
          }
        }
      },
      1);
  if (!first_error.empty()) throw Error(first_error);

  model.landmarks.vertices = int_list(index, "idx_to_landmark_verts", dir);
  model.landmarks.rigid_landmarks = int_list(index, "idx_to_rigid_landmark_idx", dir);
  if (model.landmarks.vertices.size() != 68) {
    throw Error("model file " + (dir / kIndexFile).string() + " lists " +
                std::to_string(model.landmarks.vertices.size()) + " landmark vertices, expected 68");
  }
  for (int v : model.landmarks.vertices) {
    if (v < 0 || v >= n) throw Error("model file " + (dir / kIndexFile).string() + ": landmark vertex out of range");
  }
  model.landmarks.jaw_right = kJawRight;
  model.landmarks.jaw_left = kJawLeft;
  model.landmarks.jaw_right_extended = kJawRightExtended;
  model.landmarks.jaw_left_extended = kJawLeftExtended;
  return model;
}

}  // namespace facecap
