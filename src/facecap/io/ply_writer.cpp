#include "facecap/io/ply_writer.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <sstream>
#include <string>

#include "facecap/core/atomic_file.hpp"
#include "facecap/core/binary_io.hpp"
#include "facecap/core/error.hpp"

namespace facecap {

namespace {

uint8_t to_byte(float unit) { return uint8_t(std::lround(std::clamp(unit, 0.0f, 1.0f) * 255.0f)); }

}  // namespace

void write_ply(const std::filesystem::path& path, const PlyMesh& mesh) {
  const auto fail = [&](const std::string& why) { throw Error("cannot write " + path.string() + ": " + why); };
  const Positions& p = *mesh.positions;
  const Eigen::Index n = p.cols();
  for (const Polygon& poly : *mesh.polygons)
    for (int k = 0; k < poly.size(); ++k)
      if (poly.v[k] < 0 || poly.v[k] >= n) fail("a face names a vertex the mesh does not have");
  if (!p.allFinite()) fail("a vertex is not finite");
  if (mesh.normals != nullptr && (mesh.normals->cols() != n || !mesh.normals->allFinite()))
    fail("the normals are not one finite normal a vertex");
  if (mesh.colours != nullptr && (mesh.colours->cols() != n || !mesh.colours->allFinite()))
    fail("the colours are not one finite colour a vertex");
  if (mesh.uvs != nullptr &&
      (Eigen::Index(mesh.uvs->size()) != n ||
       !std::all_of(mesh.uvs->begin(), mesh.uvs->end(), [](const Vec2f& t) { return t.allFinite(); })))
    fail("the UVs are not one finite UV a vertex");

  std::ostringstream header;
  header << "ply\nformat "
         << (std::endian::native == std::endian::little ? "binary_little_endian" : "binary_big_endian") << " 1.0\n";
  std::istringstream comment(mesh.comment);
  for (std::string line; std::getline(comment, line);) header << "comment " << line << "\n";
  header << "element vertex " << n << "\nproperty float x\nproperty float y\nproperty float z\n";
  if (mesh.normals) header << "property float nx\nproperty float ny\nproperty float nz\n";
  if (mesh.colours) header << "property uchar red\nproperty uchar green\nproperty uchar blue\n";
  if (mesh.uvs) header << "property float s\nproperty float t\n";
  header << "element face " << mesh.polygons->size() << "\nproperty list uchar int vertex_indices\nend_header\n";

  ByteWriter body;
  const std::string head = header.str();
  body.raw(head.data(), head.size());
  body.reserve(size_t(n) * (12 + (mesh.normals ? 12 : 0) + (mesh.colours ? 3 : 0) + (mesh.uvs ? 8 : 0)) +
               mesh.polygons->size() * 17);
  for (Eigen::Index i = 0; i < n; ++i) {
    for (int k = 0; k < 3; ++k) body.pod<float>(p(k, i));
    if (mesh.normals)
      for (int k = 0; k < 3; ++k) body.pod<float>((*mesh.normals)(k, i));
    if (mesh.colours)
      for (int k = 0; k < 3; ++k) body.pod<uint8_t>(to_byte((*mesh.colours)(k, i)));
    if (mesh.uvs) {
      body.pod<float>((*mesh.uvs)[size_t(i)].x());
      body.pod<float>((*mesh.uvs)[size_t(i)].y());
    }
  }
  for (const Polygon& poly : *mesh.polygons) {
    body.pod<uint8_t>(uint8_t(poly.size()));
    for (int k = 0; k < poly.size(); ++k) body.pod<int32_t>(poly.v[k]);
  }
  write_binary_file(path, body.bytes().data(), body.bytes().size());
}

}  // namespace facecap
