#include "facecap/model/obj_reader.hpp"

#include <zlib.h>

#include <charconv>
#include <cmath>
#include <cstring>
#include <memory>
#include <string>
#include <string_view>

#include "facecap/core/error.hpp"

namespace facecap {

namespace {

struct GzCloser {
  void operator()(gzFile f) const { gzclose(f); }
};
using GzHandle = std::unique_ptr<gzFile_s, GzCloser>;

// Reads the whole (possibly compressed) file into memory.
std::string read_all(const std::filesystem::path& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw Error("model file not found: " + path.string());
  if (std::filesystem::is_directory(path, ec)) throw Error("model file is a directory: " + path.string());
  GzHandle file(gzopen(path.c_str(), "rb"));
  if (!file) throw Error("cannot open model file: " + path.string());
  gzbuffer(file.get(), 1 << 18);
  std::string data;
  std::vector<char> chunk(1 << 20);
  for (;;) {
    const int n = gzread(file.get(), chunk.data(), static_cast<unsigned>(chunk.size()));
    if (n < 0) {
      int code = 0;
      const char* msg = gzerror(file.get(), &code);
      throw Error("corrupt or truncated model file " + path.string() + " (" + (msg ? msg : "zlib error") + ")");
    }
    if (n == 0) break;
    data.append(chunk.data(), static_cast<size_t>(n));
  }
  int code = 0;
  gzerror(file.get(), &code);
  if (code != Z_OK && code != Z_STREAM_END) {
    throw Error("corrupt or truncated model file " + path.string());
  }
  return data;
}

class LineParser {
 public:
  LineParser(std::string_view line, const std::filesystem::path& path, int line_no)
      : s_(line), path_(path), line_no_(line_no) {}

  float next_float() {
    skip_space();
    float value = 0.0f;
    const auto [ptr, ec] = std::from_chars(s_.data(), s_.data() + s_.size(), value);
    if (ec != std::errc()) fail("expected a number");
    s_.remove_prefix(static_cast<size_t>(ptr - s_.data()));
    if (!std::isfinite(value)) fail("non-finite coordinate");
    return value;
  }

  // Parses "v", "v/vt", "v//vn" or "v/vt/vn"; returns false at end of line.
  bool next_corner(int& v, int& vt) {
    skip_space();
    if (s_.empty()) return false;
    v = next_int();
    vt = 0;
    if (!s_.empty() && s_.front() == '/') {
      s_.remove_prefix(1);
      if (!s_.empty() && s_.front() != '/') vt = next_int();
      if (!s_.empty() && s_.front() == '/') {
        s_.remove_prefix(1);
        next_int();
      }
    }
    return true;
  }

  [[noreturn]] void fail(const std::string& what) const {
    throw Error("corrupt model file " + path_.string() + ": " + what + " on line " + std::to_string(line_no_));
  }

 private:
  int next_int() {
    int value = 0;
    const auto [ptr, ec] = std::from_chars(s_.data(), s_.data() + s_.size(), value);
    if (ec != std::errc()) fail("expected an index");
    s_.remove_prefix(static_cast<size_t>(ptr - s_.data()));
    return value;
  }
  void skip_space() {
    while (!s_.empty() && (s_.front() == ' ' || s_.front() == '\t' || s_.front() == '\r')) s_.remove_prefix(1);
  }

  std::string_view s_;
  const std::filesystem::path& path_;
  int line_no_;
};

}  // namespace

ObjData read_obj(const std::filesystem::path& path, const ObjReadOptions& options) {
  const std::string text = read_all(path);
  if (text.empty()) throw Error("model file is empty: " + path.string());
  ObjData obj;
  obj.positions.reserve(3 * 27000);
  std::string_view rest(text);
  int line_no = 0;
  while (!rest.empty()) {
    const size_t eol = rest.find('\n');
    const std::string_view line = rest.substr(0, eol);
    rest = eol == std::string_view::npos ? std::string_view() : rest.substr(eol + 1);
    ++line_no;
    if (line.size() < 2) continue;
    if (line[0] == 'v' && line[1] == ' ') {
      LineParser p(line.substr(2), path, line_no);
      for (int k = 0; k < 3; ++k) obj.positions.push_back(p.next_float());
    } else if (!options.read_topology) {
      continue;
    } else if (line[0] == 'v' && line[1] == 't' && line.size() > 2 && line[2] == ' ') {
      LineParser p(line.substr(3), path, line_no);
      const float u = p.next_float();
      const float v = p.next_float();
      obj.uvs.emplace_back(u, v);
    } else if (line[0] == 'f' && line[1] == ' ') {
      LineParser p(line.substr(2), path, line_no);
      Polygon poly;
      int count = 0;
      int v = 0;
      int vt = 0;
      while (p.next_corner(v, vt)) {
        if (count == 4) p.fail("polygon with more than 4 corners");
        poly.v[count] = v - 1;
        poly.uv[count] = vt - 1;
        ++count;
      }
      if (count < 3) p.fail("polygon with fewer than 3 corners");
      obj.polygons.push_back(poly);
    }
  }
  const int nv = obj.num_vertices();
  const int nuv = static_cast<int>(obj.uvs.size());
  for (const Polygon& poly : obj.polygons) {
    for (int k = 0; k < poly.size(); ++k) {
      if (poly.v[k] < 0 || poly.v[k] >= nv)
        throw Error("corrupt model file " + path.string() + ": face index out of range");
      if (poly.uv[k] >= nuv) throw Error("corrupt model file " + path.string() + ": UV index out of range");
    }
  }
  return obj;
}

}  // namespace facecap
