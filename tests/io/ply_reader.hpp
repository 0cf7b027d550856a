#pragma once
// Reads a binary PLY back for tests, by the format's own rules rather than
// by the writer's layout: the header's elements and properties in their
// order, each property's type, and the body decoded record by record; the
// file must end where the last record does.
#include <Eigen/Core>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace facecap::test {

struct Ply {
  std::string format;                 // as the header says it
  std::vector<std::string> comments;  // the 'comment' lines, in order
  std::vector<std::string> vertex_properties;
  // Each vertex property by name, one value a vertex (colours as 0-255).
  std::map<std::string, std::vector<double>> vertex;
  std::vector<std::vector<int>> faces;

  size_t vertices() const { return vertex.empty() ? 0 : vertex.begin()->second.size(); }
  Eigen::Vector3d point(size_t i, const char* a = "x", const char* b = "y", const char* c = "z") const {
    return {vertex.at(a)[i], vertex.at(b)[i], vertex.at(c)[i]};
  }

  static Ply read(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    const std::string d((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const size_t end = d.find("end_header\n");
    if (d.rfind("ply\n", 0) != 0 || end == std::string::npos) throw std::runtime_error("not a PLY file");
    Ply ply;
    struct Property {
      std::string name, type, count_type;  // count_type: a list's
    };
    struct Element {
      std::string name;
      size_t count = 0;
      std::vector<Property> properties;
    };
    std::vector<Element> elements;
    std::istringstream header(d.substr(4, end - 4));
    for (std::string line; std::getline(header, line);) {
      std::istringstream words(line);
      std::string word;
      words >> word;
      if (word == "format") {
        std::string version;
        words >> ply.format >> version;
        if (version != "1.0") throw std::runtime_error("PLY version " + version);
      } else if (word == "comment") {
        ply.comments.push_back(line.size() > 8 ? line.substr(8) : "");
      } else if (word == "element") {
        Element e;
        words >> e.name >> e.count;
        elements.push_back(e);
      } else if (word == "property") {
        if (elements.empty()) throw std::runtime_error("property before element");
        Property p;
        words >> p.type;
        if (p.type == "list") words >> p.count_type >> p.type;
        words >> p.name;
        elements.back().properties.push_back(p);
      } else {
        throw std::runtime_error("unknown header line: " + line);
      }
    }
    if (ply.format != "binary_little_endian") throw std::runtime_error("format " + ply.format);
    size_t at = end + 11;
    auto take = [&](const std::string& type) -> double {
      auto get = [&](auto v) {
        if (at + sizeof(v) > d.size()) throw std::runtime_error("PLY body truncated");
        std::memcpy(&v, d.data() + at, sizeof(v));
        at += sizeof(v);
        return double(v);
      };
      if (type == "float") return get(float{});
      if (type == "uchar") return get(uint8_t{});
      if (type == "int") return get(int32_t{});
      throw std::runtime_error("type " + type);
    };
    for (const Element& e : elements) {
      if (e.name == "vertex")
        for (const Property& p : e.properties) ply.vertex_properties.push_back(p.name);
      for (size_t r = 0; r < e.count; ++r) {
        for (const Property& p : e.properties) {
          if (p.count_type.empty()) {
            const double v = take(p.type);
            if (e.name == "vertex") ply.vertex[p.name].push_back(v);
          } else {
            std::vector<int> list(size_t(take(p.count_type)));
            for (int& v : list) v = int(take(p.type));
            if (e.name == "face" && p.name == "vertex_indices") ply.faces.push_back(list);
          }
        }
      }
    }
    if (at != d.size()) throw std::runtime_error("bytes after the last record");
    return ply;
  }
};

}  // namespace facecap::test
