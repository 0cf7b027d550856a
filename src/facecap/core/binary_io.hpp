#pragma once
// Little binary records: a writer that appends plain values to a byte
// string, and a reader that takes them back with bounds checks, throwing
// facecap::Error naming the file when it is truncated or corrupt. Used by the
// model cache and the saved displacement problems.
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "facecap/core/error.hpp"

namespace facecap {

class ByteWriter {
 public:
  template <typename T>
  void pod(const T& v) {
    raw(&v, sizeof(T));
  }
  void raw(const void* p, size_t n) {
    if (n > 0) bytes_.append(static_cast<const char*>(p), n);
  }
  void floats(const float* p, size_t n) { raw(p, n * sizeof(float)); }
  void ints(const std::vector<int>& v) {
    pod(static_cast<uint32_t>(v.size()));
    for (int x : v) pod(static_cast<int32_t>(x));
  }
  void text(const std::string& s) {
    pod(static_cast<uint32_t>(s.size()));
    raw(s.data(), s.size());
  }
  const std::string& bytes() const { return bytes_; }
  // Room for `more` bytes after those written, where a record's size is known.
  void reserve(size_t more) { bytes_.reserve(bytes_.size() + more); }

 private:
  std::string bytes_;
};

class ByteReader {
 public:
  // `what` names the kind of file in the errors ("model cache").
  ByteReader(std::string_view data, std::string what, std::filesystem::path path)
      : data_(data), what_(std::move(what)), path_(std::move(path)) {}
  template <typename T>
  T pod() {
    T v;
    raw(&v, sizeof(T));
    return v;
  }
  void raw(void* p, size_t n) {
    if (n > data_.size()) throw Error(what_ + " is truncated: " + path_.string());
    if (n == 0) return;  // an empty vector's data() may be null, which memcpy must not get
    std::memcpy(p, data_.data(), n);
    data_.remove_prefix(n);
  }
  void floats(float* p, size_t n) { raw(p, n * sizeof(float)); }
  std::vector<int> ints(uint32_t max_count) {
    const uint32_t n = pod<uint32_t>();
    if (n > max_count) corrupt();
    std::vector<int> v(n);
    for (auto& x : v) x = pod<int32_t>();
    return v;
  }
  std::string text() {
    const uint32_t n = pod<uint32_t>();
    if (n > 256) corrupt();
    std::string s(n, '\0');
    raw(s.data(), n);
    return s;
  }
  bool done() const { return data_.empty(); }
  size_t remaining() const { return data_.size(); }
  [[noreturn]] void corrupt() const { throw Error(what_ + " is corrupt: " + path_.string()); }

 private:
  std::string_view data_;
  std::string what_;
  std::filesystem::path path_;
};

}  // namespace facecap
