#pragma once
// Binary glTF 2.0 (.glb) output of one animated mesh: a mesh (one or more
// parts, each with its material) with morph targets (blend shapes) on a node whose translation, rotation and morph
// weights are keyed per frame, and optionally the perspective camera that saw
// it, at the scene's origin. Blender (File > Import > glTF 2.0) reads it as a
// mesh with shape keys, an action and a camera; three.js's GLTFLoader as a
// Mesh with a morphTargetDictionary and an AnimationClip. Written atomically.
//
// Everything is given in glTF's conventions: metres, right-handed, y up, a
// camera looking down its -z axis, UV origin at the image's top-left.
#include <Eigen/Geometry>
#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "facecap/core/mesh.hpp"

namespace facecap {

struct GltfCamera {
  double yfov_rad = 0.8;  // vertical field of view
  double aspect_ratio = 16.0 / 9.0;
  double znear = 0.01;  // metres
};

// One part of the mesh, with its own material. Every part has the mesh's
// morph targets.
struct GltfPrimitive {
  std::string name = "part";
  Positions positions;   // 3 x N
  Positions normals;     // 3 x N unit normals, or empty
  Eigen::Matrix2Xf uvs;  // 2 x N, or empty
  Positions colours;     // 3 x N linear RGB in [0, 1] (COLOR_0), or empty
  std::vector<Triangle> triangles;
  std::vector<Positions> morph_targets;           // 3 x N position offsets each
  Eigen::Vector3f base_colour{0.8f, 0.8f, 0.8f};  // linear RGB
  std::vector<uint8_t> base_colour_png;           // embedded as the base colour texture (empty: none)
};

// A PNG carried in the file that no material uses (renderers ignore it),
// found by its name (images[].name): a matte, say, that a compositing step
// applies where it wants one.
struct GltfImage {
  std::string name;
  std::vector<uint8_t> png;
};

struct GltfAnimatedMesh {
  std::string name = "mesh";
  std::vector<GltfPrimitive> primitives;
  std::vector<std::string> morph_target_names;

  // One key per frame: time (seconds, strictly increasing), the node's
  // transform, and the morph weights (targets x keys).
  std::vector<float> times;
  std::vector<Eigen::Vector3f> translations;
  std::vector<Eigen::Quaternionf> rotations;
  Eigen::MatrixXf weights;
  std::string animation_name = "animation";

  std::optional<GltfCamera> camera;
  std::map<std::string, std::string> asset_extras;  // written as asset.extras
  std::vector<GltfImage> images;                    // after the parts' textures
};

// Throws facecap::Error when the parts disagree in size, a time does not
// increase or a value is not finite; nothing is written then.
void write_glb(const std::filesystem::path& path, const GltfAnimatedMesh& mesh);

}  // namespace facecap
