#include "facecap/io/gltf_writer.hpp"

#include <cmath>
#include <cstring>
#include <nlohmann/json.hpp>

#include "facecap/core/atomic_file.hpp"
#include "facecap/core/error.hpp"
#include "facecap/core/version.hpp"

namespace facecap {

namespace {

using nlohmann::json;

// glTF 2.0 enumerations (the specification's numeric codes).
constexpr int kArrayBuffer = 34962;
constexpr int kElementArrayBuffer = 34963;
constexpr int kFloat = 5126;
constexpr int kUnsignedInt = 5125;
constexpr int kTriangles = 4;
constexpr int kLinear = 9729;
constexpr int kLinearMipmapLinear = 9987;
constexpr int kClampToEdge = 33071;

void require(bool ok, const std::string& what) {
  if (!ok) throw Error("cannot write glTF: " + what);
}

const char* vector_type(int components) {
  switch (components) {
    case 1:
      return "SCALAR";
    case 2:
      return "VEC2";
    case 3:
      return "VEC3";
    default:
      return "VEC4";
  }
}

// The JSON document and the binary chunk it indexes, built together.
class GlbBuilder {
 public:
  json& doc() { return doc_; }

  // Appends `bytes` as a new buffer view, 4-byte aligned; returns its index.
  int view(const void* data, size_t bytes, int target = 0) {
    bin_.resize((bin_.size() + 3) & ~size_t(3), 0);
    json v = {{"buffer", 0}, {"byteOffset", bin_.size()}, {"byteLength", bytes}};
    if (target != 0) v["target"] = target;
    const auto* p = static_cast<const uint8_t*>(data);
    bin_.insert(bin_.end(), p, p + bytes);
    doc_["bufferViews"].push_back(v);
    return int(doc_["bufferViews"].size()) - 1;
  }

  // `count` elements of `components` floats each. `bounds`: write min and
  // max, which the specification requires of positions and animation times.
  int floats(const float* data, size_t count, int components, int target, bool bounds) {
    const int v = view(data, count * components * sizeof(float), target);
    json a = {{"bufferView", v}, {"componentType", kFloat}, {"count", count}, {"type", vector_type(components)}};
    if (bounds && count > 0) {
      json lo = json::array(), hi = json::array();
      for (int c = 0; c < components; ++c) {
        float mn = data[c], mx = data[c];
        for (size_t i = 1; i < count; ++i) {
          mn = std::min(mn, data[i * components + c]);
          mx = std::max(mx, data[i * components + c]);
        }
        lo.push_back(mn);
        hi.push_back(mx);
      }
      a["min"] = lo;
      a["max"] = hi;
    }
    return add_accessor(a);
  }

  // A morph target's offsets: where at most a third of the vertices move,
  // as a sparse accessor (the indices and offsets of the moving ones only;
  // the rest read as zero), which is smaller and exact.
  int offsets(const Positions& offsets) {
    const size_t n = size_t(offsets.cols());
    std::vector<uint32_t> moving;
    for (size_t i = 0; i < n; ++i)
      if (!offsets.col(Eigen::Index(i)).isZero(0.0f)) moving.push_back(uint32_t(i));
    if (moving.empty() || moving.size() * 3 > n) return floats(offsets.data(), n, 3, kArrayBuffer, true);
    std::vector<float> values;
    values.reserve(moving.size() * 3);
    Eigen::Vector3f lo = Eigen::Vector3f::Zero(), hi = Eigen::Vector3f::Zero();  // the zeros count too
    for (uint32_t i : moving) {
      const Eigen::Vector3f d = offsets.col(i);
      values.insert(values.end(), d.data(), d.data() + 3);
      lo = lo.cwiseMin(d);
      hi = hi.cwiseMax(d);
    }
    const int index_view = view(moving.data(), moving.size() * sizeof(uint32_t));
    const int value_view = view(values.data(), values.size() * sizeof(float));
    return add_accessor({{"componentType", kFloat},
                         {"count", n},
                         {"type", "VEC3"},
                         {"min", {lo.x(), lo.y(), lo.z()}},
                         {"max", {hi.x(), hi.y(), hi.z()}},
                         {"sparse",
                          {{"count", moving.size()},
                           {"indices", {{"bufferView", index_view}, {"componentType", kUnsignedInt}}},
                           {"values", {{"bufferView", value_view}}}}}});
  }

  int indices(const std::vector<Triangle>& triangles) {
    std::vector<uint32_t> flat;
    flat.reserve(triangles.size() * 3);
    for (const Triangle& t : triangles)
      for (int k : t) flat.push_back(uint32_t(k));
    const int v = view(flat.data(), flat.size() * sizeof(uint32_t), kElementArrayBuffer);
    return add_accessor(
        {{"bufferView", v}, {"componentType", kUnsignedInt}, {"count", flat.size()}, {"type", "SCALAR"}});
  }

  // The .glb container: header, JSON chunk (padded with spaces), BIN chunk
  // (padded with zeros).
  std::string assemble() {
    bin_.resize((bin_.size() + 3) & ~size_t(3), 0);
    doc_["buffers"] = json::array({{{"byteLength", bin_.size()}}});
    std::string text = doc_.dump();
    text.resize((text.size() + 3) & ~size_t(3), ' ');
    std::string out;
    auto u32 = [&out](uint32_t x) { out.append(reinterpret_cast<const char*>(&x), 4); };
    const size_t total = 12 + 8 + text.size() + 8 + bin_.size();
    require(total < (size_t(1) << 32), "the file would exceed 4 GiB");
    u32(0x46546C67u);  // "glTF"
    u32(2);
    u32(uint32_t(total));
    u32(uint32_t(text.size()));
    u32(0x4E4F534Au);  // "JSON"
    out += text;
    u32(uint32_t(bin_.size()));
    u32(0x004E4942u);  // "BIN"
    out.append(reinterpret_cast<const char*>(bin_.data()), bin_.size());
    return out;
  }

 private:
  int add_accessor(const json& a) {
    doc_["accessors"].push_back(a);
    return int(doc_["accessors"].size()) - 1;
  }

  json doc_ = json::object();
  std::vector<uint8_t> bin_;
};

void validate(const GltfPrimitive& p, size_t targets) {
  const Eigen::Index n = p.positions.cols();
  require(n > 0 && !p.triangles.empty(), "part " + p.name + " is empty");
  require(p.positions.allFinite(), "a vertex position is not finite");
  require(p.normals.size() == 0 || (p.normals.cols() == n && p.normals.allFinite()), "normals do not match the mesh");
  require(p.uvs.size() == 0 || (p.uvs.cols() == n && p.uvs.allFinite()), "UVs do not match the mesh");
  require(p.colours.size() == 0 || (p.colours.cols() == n && p.colours.allFinite()), "colours do not match the mesh");
  for (const Triangle& t : p.triangles)
    for (int k : t) require(k >= 0 && k < n, "a triangle indexes a missing vertex");
  require(p.morph_targets.size() == targets, "part " + p.name + " lacks morph targets the mesh names");
  for (const Positions& t : p.morph_targets)
    require(t.cols() == n && t.allFinite(), "a morph target does not match the mesh");
}

void validate(const GltfAnimatedMesh& m) {
  require(!m.primitives.empty(), "the mesh has no parts");
  for (const GltfPrimitive& p : m.primitives) validate(p, m.morph_target_names.size());
  const size_t keys = m.times.size();
  require(m.translations.size() == keys && m.rotations.size() == keys, "keys differ in number");
  require(m.weights.cols() == Eigen::Index(keys) && m.weights.rows() == Eigen::Index(m.morph_target_names.size()),
          "the weights are not targets x keys");
  require(m.weights.allFinite(), "a morph weight is not finite");
  for (size_t k = 0; k < keys; ++k) {
    require(std::isfinite(m.times[k]) && (k == 0 || m.times[k] > m.times[k - 1]), "key times must increase");
    require(m.translations[k].allFinite() && m.rotations[k].coeffs().allFinite(), "a key's transform is not finite");
  }
  for (const GltfImage& image : m.images) require(!image.png.empty(), "image " + image.name + " is empty");
}

// The part's accessors and its material (appended to the document).
json write_primitive(GlbBuilder& b, const GltfPrimitive& p) {
  const size_t n = size_t(p.positions.cols());
  json attributes = {{"POSITION", b.floats(p.positions.data(), n, 3, kArrayBuffer, true)}};
  if (p.normals.size() > 0) attributes["NORMAL"] = b.floats(p.normals.data(), n, 3, kArrayBuffer, false);
  if (p.uvs.size() > 0) attributes["TEXCOORD_0"] = b.floats(p.uvs.data(), n, 2, kArrayBuffer, false);
  if (p.colours.size() > 0) attributes["COLOR_0"] = b.floats(p.colours.data(), n, 3, kArrayBuffer, false);
  json& doc = b.doc();
  // The factor multiplies the texture: white when there is one.
  const Eigen::Vector3f factor = p.base_colour_png.empty() ? p.base_colour : Eigen::Vector3f::Ones();
  json pbr = {{"metallicFactor", 0.0},
              {"roughnessFactor", 0.7},
              {"baseColorFactor", {factor.x(), factor.y(), factor.z(), 1.0}}};
  if (!p.base_colour_png.empty()) {
    const int v = b.view(p.base_colour_png.data(), p.base_colour_png.size());
    if (!doc.contains("samplers"))
      doc["samplers"] = json::array({{{"magFilter", kLinear},
                                      {"minFilter", kLinearMipmapLinear},
                                      {"wrapS", kClampToEdge},
                                      {"wrapT", kClampToEdge}}});
    doc["images"].push_back({{"bufferView", v}, {"mimeType", "image/png"}});
    doc["textures"].push_back({{"source", doc["images"].size() - 1}, {"sampler", 0}});
    pbr["baseColorTexture"] = {{"index", doc["textures"].size() - 1}};
  }
  doc["materials"].push_back({{"name", p.name}, {"pbrMetallicRoughness", pbr}});
  json primitive = {{"attributes", attributes},
                    {"indices", b.indices(p.triangles)},
                    {"material", doc["materials"].size() - 1},
                    {"mode", kTriangles}};
  if (!p.morph_targets.empty()) {
    json targets = json::array();
    for (const Positions& t : p.morph_targets) targets.push_back({{"POSITION", b.offsets(t)}});
    primitive["targets"] = targets;
  }
  return primitive;
}

json node_transform(const Eigen::Vector3f& t, const Eigen::Quaternionf& q) {
  return {{"translation", {t.x(), t.y(), t.z()}}, {"rotation", {q.x(), q.y(), q.z(), q.w()}}};
}

}  // namespace

void write_glb(const std::filesystem::path& path, const GltfAnimatedMesh& m) {
  validate(m);
  GlbBuilder b;
  json& doc = b.doc();
  doc["asset"] = {{"version", "2.0"}, {"generator", std::string("facecap ") + kFacecapVersion}};
  if (!m.asset_extras.empty()) doc["asset"]["extras"] = m.asset_extras;

  json mesh = {{"name", m.name}, {"primitives", json::array()}};
  for (const GltfPrimitive& p : m.primitives) mesh["primitives"].push_back(write_primitive(b, p));
  if (!m.morph_target_names.empty()) {
    mesh["weights"] = std::vector<float>(m.morph_target_names.size(), 0.0f);
    mesh["extras"] = {{"targetNames", m.morph_target_names}};  // read by Blender and three.js
  }
  doc["meshes"] = json::array({mesh});
  for (const GltfImage& image : m.images) {
    const int v = b.view(image.png.data(), image.png.size());
    doc["images"].push_back({{"name", image.name}, {"bufferView", v}, {"mimeType", "image/png"}});
  }

  json node = {{"name", m.name}, {"mesh", 0}};
  if (!m.times.empty()) node.update(node_transform(m.translations[0], m.rotations[0]));
  doc["nodes"] = json::array({node});
  if (m.camera) {
    doc["cameras"] = json::array(
        {{{"type", "perspective"},
          {"perspective",
           {{"yfov", m.camera->yfov_rad}, {"aspectRatio", m.camera->aspect_ratio}, {"znear", m.camera->znear}}}}});
    doc["nodes"].push_back({{"name", "camera"}, {"camera", 0}});
  }
  json scene_nodes = json::array();
  for (size_t i = 0; i < doc["nodes"].size(); ++i) scene_nodes.push_back(i);
  doc["scenes"] = json::array({{{"nodes", scene_nodes}}});
  doc["scene"] = 0;

  if (!m.times.empty()) {
    const size_t keys = m.times.size();
    const int times = b.floats(m.times.data(), keys, 1, 0, true);
    std::vector<float> t(keys * 3), r(keys * 4);
    for (size_t k = 0; k < keys; ++k) {
      for (int c = 0; c < 3; ++c) t[k * 3 + c] = m.translations[k][c];
      const Eigen::Vector4f q = m.rotations[k].coeffs();  // x, y, z, w: glTF's order
      for (int c = 0; c < 4; ++c) r[k * 4 + c] = q[c];
    }
    json samplers = json::array(), channels = json::array();
    auto animate = [&](int output, const char* property) {
      samplers.push_back({{"input", times}, {"output", output}, {"interpolation", "LINEAR"}});
      channels.push_back({{"sampler", samplers.size() - 1}, {"target", {{"node", 0}, {"path", property}}}});
    };
    animate(b.floats(t.data(), keys, 3, 0, false), "translation");
    animate(b.floats(r.data(), keys, 4, 0, false), "rotation");
    if (!m.morph_target_names.empty())
      animate(b.floats(m.weights.data(), keys * m.weights.rows(), 1, 0, false), "weights");
    doc["animations"] = json::array({{{"name", m.animation_name}, {"samplers", samplers}, {"channels", channels}}});
  }

  const std::string bytes = b.assemble();
  write_binary_file(path, bytes.data(), bytes.size());
}

}  // namespace facecap
