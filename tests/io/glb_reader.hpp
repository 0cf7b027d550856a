#pragma once
// Reads a .glb back for tests: the container's header and chunks, checked
// against the specification's layout, and float accessors decoded.
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

  // The accessor's floats, element after element.
  std::vector<float> floats(int accessor) const {
    const auto& a = doc.at("accessors").at(accessor);
    if (a.at("componentType") != 5126) throw std::runtime_error("not a float accessor");
    const std::string type = a.at("type");
    const size_t n = type == "SCALAR" ? 1 : type == "VEC2" ? 2 : type == "VEC3" ? 3 : 4;
    const auto& v = doc.at("bufferViews").at(int(a.at("bufferView")));
    const size_t at = size_t(v.value("byteOffset", 0)) + size_t(a.value("byteOffset", 0));
    const size_t count = size_t(a.at("count")) * n;
    if (at + count * 4 > size_t(v.value("byteOffset", 0)) + size_t(v.at("byteLength")) || at + count * 4 > bin.size())
      throw std::runtime_error("accessor outside its view");
    std::vector<float> out(count);
    std::memcpy(out.data(), bin.data() + at, count * 4);
    return out;
  }

  std::vector<uint32_t> indices(int accessor) const {
    const auto& a = doc.at("accessors").at(accessor);
    const auto& v = doc.at("bufferViews").at(int(a.at("bufferView")));
    const size_t at = size_t(v.value("byteOffset", 0)) + size_t(a.value("byteOffset", 0));
    std::vector<uint32_t> out(size_t(a.at("count")));
    std::memcpy(out.data(), bin.data() + at, out.size() * 4);
    return out;
  }
};

}  // namespace facecap::test
