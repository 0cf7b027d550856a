#pragma once
// Reads a .glb back for tests: the container's header and chunks, checked
// against the specification's layout, and float accessors decoded.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <vector>

namespace facecap::test {

struct Glb {
  nlohmann::json doc;
  std::string bin;

  static Glb read(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    const std::string d((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    auto u32 = [&d](size_t at) {
      if (at + 4 > d.size()) throw std::runtime_error("glb truncated");
      uint32_t v;
      std::memcpy(&v, d.data() + at, 4);
      return v;
    };
    if (u32(0) != 0x46546C67u || u32(4) != 2 || u32(8) != d.size()) throw std::runtime_error("bad glb header");
    const uint32_t json_length = u32(12);
    if (u32(16) != 0x4E4F534Au || json_length % 4 != 0) throw std::runtime_error("bad JSON chunk");
    Glb g;
    g.doc = nlohmann::json::parse(d.substr(20, json_length));
    const size_t bin_at = 20 + json_length;
    const uint32_t bin_length = u32(bin_at);
    if (u32(bin_at + 4) != 0x004E4942u || bin_length % 4 != 0 || bin_at + 8 + bin_length != d.size())
      throw std::runtime_error("bad BIN chunk");
    g.bin = d.substr(bin_at + 8, bin_length);
    return g;
  }

  // The accessor's floats, element after element (a sparse accessor's
  // zeros filled in).
  std::vector<float> floats(int accessor) const {
    const auto& a = doc.at("accessors").at(accessor);
    if (a.at("componentType") != 5126) throw std::runtime_error("not a float accessor");
    const std::string type = a.at("type");
    const size_t n = type == "SCALAR" ? 1 : type == "VEC2" ? 2 : type == "VEC3" ? 3 : 4;
    const size_t count = size_t(a.at("count"));
    std::vector<float> out(count * n, 0.0f);
    if (a.contains("bufferView"))
      copy(a.at("bufferView"), size_t(a.value("byteOffset", 0)), out.data(), out.size() * 4);
    if (a.contains("sparse")) {
      const auto& sp = a.at("sparse");
      const size_t moving = sp.at("count");
      if (sp.at("indices").at("componentType") != 5125) throw std::runtime_error("sparse indices not uint32");
      std::vector<uint32_t> index(moving);
      std::vector<float> values(moving * n);
      copy(sp.at("indices").at("bufferView"), 0, index.data(), moving * 4);
      copy(sp.at("values").at("bufferView"), 0, values.data(), values.size() * 4);
      for (size_t k = 0; k < moving; ++k) {
        if (index[k] >= count || (k > 0 && index[k] <= index[k - 1])) throw std::runtime_error("bad sparse index");
        std::copy(values.begin() + k * n, values.begin() + (k + 1) * n, out.begin() + index[k] * n);
      }
    }
    return out;
  }

  // The output of the first animation's channel on `path` ("translation",
  // "rotation", "weights"), key after key.
  std::vector<float> channel(const std::string& path) const {
    const auto& anim = doc.at("animations").at(0);
    for (const auto& ch : anim.at("channels"))
      if (ch.at("target").at("path") == path) return floats(anim.at("samplers").at(int(ch.at("sampler"))).at("output"));
    throw std::runtime_error("no " + path + " channel");
  }

  // What a glTF player computes for every vertex of the first mesh's
  // primitive `part` at key `key`: the rest position plus the weighted morph
  // offsets, under the node's rotation and translation (metres).
  Eigen::Matrix3Xf played_part(int part, int key) const {
    const auto& prim = doc.at("meshes").at(0).at("primitives").at(part);
    const std::vector<float> rest = floats(prim.at("attributes").at("POSITION"));
    Eigen::Matrix3Xf p = Eigen::Map<const Eigen::Matrix3Xf>(rest.data(), 3, Eigen::Index(rest.size() / 3));
    const std::vector<float> weights = channel("weights");
    const size_t targets = prim.at("targets").size();
    for (size_t j = 0; j < targets; ++j) {
      const float w = weights.at(key * targets + j);
      if (w == 0) continue;
      const std::vector<float> t = floats(prim.at("targets").at(j).at("POSITION"));
      p += w * Eigen::Map<const Eigen::Matrix3Xf>(t.data(), 3, p.cols());
    }
    const std::vector<float> r = channel("rotation"), t = channel("translation");
    const Eigen::Quaternionf q(r.at(key * 4 + 3), r[key * 4], r[key * 4 + 1], r[key * 4 + 2]);
    return (q.toRotationMatrix() * p).colwise() + Eigen::Vector3f(t.at(key * 3), t[key * 3 + 1], t[key * 3 + 2]);
  }

  // Where the first camera (at the origin, looking down -z, y up) sees a
  // point given in metres: pixel coordinates in a width x height image whose
  // pixel centres lie at integers.
  Eigen::Vector2d camera_pixel(const Eigen::Vector3f& world, int width, int height) const {
    const auto& perspective = doc.at("cameras").at(0).at("perspective");
    const double t = std::tan(0.5 * double(perspective.at("yfov")));
    const double aspect = perspective.at("aspectRatio");
    const double xn = world.x() / -world.z() / (t * aspect), yn = world.y() / -world.z() / t;
    return {(xn + 1) * 0.5 * width - 0.5, (1 - yn) * 0.5 * height - 0.5};
  }

  // The encoded bytes of image `image` (stored in a buffer view).
  std::string image_bytes(int image) const {
    const int view = doc.at("images").at(image).at("bufferView");
    std::string out(size_t(doc.at("bufferViews").at(view).at("byteLength")), '\0');
    copy(view, 0, out.data(), out.size());
    return out;
  }

  std::vector<uint32_t> indices(int accessor) const {
    const auto& a = doc.at("accessors").at(accessor);
    std::vector<uint32_t> out(size_t(a.at("count")));
    copy(a.at("bufferView"), size_t(a.value("byteOffset", 0)), out.data(), out.size() * 4);
    return out;
  }

 private:
  // `bytes` from buffer view `view` at `offset`, checked to lie inside it.
  void copy(int view, size_t offset, void* to, size_t bytes) const {
    const auto& v = doc.at("bufferViews").at(view);
    const size_t begin = size_t(v.value("byteOffset", 0)) + offset;
    if (offset + bytes > size_t(v.at("byteLength")) || begin + bytes > bin.size())
      throw std::runtime_error("accessor outside its view");
    std::memcpy(to, bin.data() + begin, bytes);
  }
};

}  // namespace facecap::test
