#include "facecap/model/model_cache.hpp"

#include <zlib.h>

#include <chrono>
#include <cstring>
#include <fstream>
#include <string_view>

#include "facecap/core/atomic_file.hpp"
#include "facecap/core/binary_io.hpp"
#include "facecap/core/error.hpp"
#include "facecap/core/fingerprint.hpp"
#include "facecap/core/mapped_file.hpp"
#include "facecap/core/paths.hpp"
#include "facecap/model/ict_loader.hpp"

namespace facecap {

namespace fs = std::filesystem;

namespace {

constexpr char kMagic[8] = {'F', 'C', 'A', 'P', 'M', 'D', 'L', '\0'};

#pragma pack(push, 1)
struct CacheHeader {
  char magic[8];
  uint32_t version;
  uint32_t num_vertices;
  uint32_t num_uvs;
  uint32_t num_polygons;
  uint32_t num_identity;
  uint32_t num_expressions;
  uint64_t source_fingerprint;
  uint64_t payload_bytes;
  uint32_t payload_crc32;
};
#pragma pack(pop)

}  // namespace

uint64_t model_source_fingerprint(const fs::path& model_dir) {
  uint64_t h = fnv1a("facecap-model-v" + std::to_string(kModelCacheVersion));
  for (const fs::path& f : ict_source_files(model_dir)) h = fnv1a(file_stamp(f, f.filename().string()), h);
  return h;
}

fs::path model_cache_path(const fs::path& model_dir) {
  std::error_code ec;
  const fs::path canonical = fs::weakly_canonical(model_dir, ec);
  const uint64_t h = fnv1a((ec ? model_dir : canonical).string());
  char name[64];
  std::snprintf(name, sizeof(name), "ict-model-%016llx.fcm", static_cast<unsigned long long>(h));
  return cache_dir() / name;
}

void write_model_cache(const FaceModel& model, uint64_t source_fingerprint, const fs::path& path) {
  ByteWriter w;
  w.floats(model.neutral.data(), model.neutral.size());
  w.floats(model.identity_basis.data(), model.identity_basis.size());
  w.floats(model.expression_basis.data(), model.expression_basis.size());
  for (const Vec2f& uv : model.uvs) w.floats(uv.data(), 2);
  for (const Polygon& p : model.polygons) {
    for (int k = 0; k < 4; ++k) w.pod(static_cast<int32_t>(p.v[k]));
    for (int k = 0; k < 4; ++k) w.pod(static_cast<int32_t>(p.uv[k]));
  }
  for (const std::string& name : model.expression_names) w.text(name);
  const LandmarkMap& lm = model.landmarks;
  for (const auto* list : {&lm.vertices, &lm.rigid_landmarks, &lm.jaw_right, &lm.jaw_left, &lm.jaw_right_extended,
                           &lm.jaw_left_extended}) {
    w.ints(*list);
  }
  const std::string& payload = w.bytes();

  CacheHeader header{};
  std::memcpy(header.magic, kMagic, sizeof(kMagic));
  header.version = kModelCacheVersion;
  header.num_vertices = static_cast<uint32_t>(model.num_vertices);
  header.num_uvs = static_cast<uint32_t>(model.uvs.size());
  header.num_polygons = static_cast<uint32_t>(model.polygons.size());
  header.num_identity = static_cast<uint32_t>(model.num_identity());
  header.num_expressions = static_cast<uint32_t>(model.num_expressions());
  header.source_fingerprint = source_fingerprint;
  header.payload_bytes = payload.size();
  header.payload_crc32 = static_cast<uint32_t>(
      crc32(0L, reinterpret_cast<const Bytef*>(payload.data()), static_cast<uInt>(payload.size())));

  write_file(path, [&](std::ostream& out) {
    out.write(reinterpret_cast<const char*>(&header), sizeof(header));
    out.write(payload.data(), static_cast<std::streamsize>(payload.size()));
  });
}

FaceModel read_model_cache(const fs::path& path, uint64_t expected_fingerprint) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) throw Error("model cache not found: " + path.string());
  // Mapped rather than read: the 50 MB go once from the page cache into the
  // model's matrices, with no buffer to clear and fill first.
  const MappedFile file(path);
  const std::span<const std::byte> bytes = file.bytes();
  CacheHeader header{};
  if (bytes.size() < sizeof(header)) throw Error("model cache is truncated: " + path.string());
  std::memcpy(&header, bytes.data(), sizeof(header));
  if (std::memcmp(header.magic, kMagic, sizeof(kMagic)) != 0)
    throw Error("not a facecap model cache: " + path.string());
  if (header.version != kModelCacheVersion) {
    throw Error("model cache " + path.string() + " has version " + std::to_string(header.version) + ", expected " +
                std::to_string(kModelCacheVersion));
  }
  if (expected_fingerprint != 0 && header.source_fingerprint != expected_fingerprint) {
    throw Error("model cache is stale: " + path.string());
  }
  if (header.num_vertices == 0 || header.num_vertices > 10'000'000 || header.num_identity > 1000 ||
      header.num_expressions > 1000 || header.num_uvs > 10'000'000 || header.num_polygons > 10'000'000) {
    throw Error("model cache is corrupt (impossible counts): " + path.string());
  }
  const uint64_t n3 = 3ull * header.num_vertices;
  const uint64_t fixed_bytes = 4ull * (n3 * (1 + header.num_identity + header.num_expressions) + 2ull * header.num_uvs +
                                       8ull * header.num_polygons);
  if (header.payload_bytes < fixed_bytes || header.payload_bytes > fixed_bytes + (1u << 20)) {
    throw Error("model cache is corrupt (payload size): " + path.string());
  }
  if (bytes.size() - sizeof(header) < header.payload_bytes) throw Error("model cache is truncated: " + path.string());
  const std::string_view payload(reinterpret_cast<const char*>(bytes.data()) + sizeof(header), header.payload_bytes);
  const auto crc = static_cast<uint32_t>(
      crc32(0L, reinterpret_cast<const Bytef*>(payload.data()), static_cast<uInt>(payload.size())));
  if (crc != header.payload_crc32) throw Error("model cache is corrupt (checksum mismatch): " + path.string());

  ByteReader r(payload, "model cache", path);
  FaceModel m;
  m.num_vertices = static_cast<int>(header.num_vertices);
  m.neutral.resize(static_cast<Eigen::Index>(n3));
  m.identity_basis.resize(static_cast<Eigen::Index>(n3), header.num_identity);
  m.expression_basis.resize(static_cast<Eigen::Index>(n3), header.num_expressions);
  r.floats(m.neutral.data(), m.neutral.size());
  r.floats(m.identity_basis.data(), m.identity_basis.size());
  r.floats(m.expression_basis.data(), m.expression_basis.size());
  m.uvs.resize(header.num_uvs);
  for (Vec2f& uv : m.uvs) r.floats(uv.data(), 2);
  m.polygons.resize(header.num_polygons);
  for (Polygon& p : m.polygons) {
    for (int k = 0; k < 4; ++k) p.v[k] = r.pod<int32_t>();
    for (int k = 0; k < 4; ++k) p.uv[k] = r.pod<int32_t>();
  }
  m.expression_names.resize(header.num_expressions);
  for (std::string& name : m.expression_names) name = r.text();
  LandmarkMap& lm = m.landmarks;
  for (auto* list : {&lm.vertices, &lm.rigid_landmarks, &lm.jaw_right, &lm.jaw_left, &lm.jaw_right_extended,
                     &lm.jaw_left_extended}) {
    *list = r.ints(1000);
  }
  if (!r.done()) throw Error("model cache is corrupt (trailing bytes): " + path.string());
  return m;
}

FaceModel load_face_model(const fs::path& model_dir, ModelLoadReport* report) {
  const auto start = std::chrono::steady_clock::now();
  ModelLoadReport local;
  ModelLoadReport& rep = report ? *report : local;
  const uint64_t fingerprint = model_source_fingerprint(model_dir);
  rep.cache_file = model_cache_path(model_dir);
  FaceModel model;
  bool loaded = false;
  std::error_code ec;
  if (fs::exists(rep.cache_file, ec)) {
    try {
      model = read_model_cache(rep.cache_file, fingerprint);
      loaded = rep.from_cache = true;
    } catch (const Error&) {
      // Stale or damaged cache: rebuilt below.
    }
  }
  if (!loaded) {
    model = load_ict_model(model_dir);
    try {
      fs::create_directories(rep.cache_file.parent_path(), ec);
      write_model_cache(model, fingerprint, rep.cache_file);
      rep.cache_written = true;
    } catch (const Error&) {
      rep.cache_written = false;
    }
  }
  rep.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return model;
}

}  // namespace facecap
