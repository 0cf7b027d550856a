#include "facecap/io/mesh_writer.hpp"

#include <cstdio>
#include <memory>
#include <sstream>

#include "facecap/core/atomic_file.hpp"
#include "facecap/core/error.hpp"

namespace facecap {

namespace {
struct FileCloser {
  void operator()(std::FILE* f) const { std::fclose(f); }
};
}  // namespace

void write_obj(const std::filesystem::path& path, const ObjMesh& mesh) {
  AtomicFile file(path);
  {
    std::unique_ptr<std::FILE, FileCloser> out(std::fopen(file.temp_path().c_str(), "w"));
    if (!out) throw Error("cannot write " + path.string());
    std::FILE* f = out.get();
    std::istringstream comment(mesh.comment);
    for (std::string line; std::getline(comment, line);) std::fprintf(f, "# %s\n", line.c_str());
    const Positions& p = *mesh.positions;
    for (Eigen::Index i = 0; i < p.cols(); ++i) std::fprintf(f, "v %.5f %.5f %.5f\n", p(0, i), p(1, i), p(2, i));
    const bool uv = mesh.uvs != nullptr && !mesh.uvs->empty();
    if (uv) {
      for (const Vec2f& t : *mesh.uvs) std::fprintf(f, "vt %.6f %.6f\n", t.x(), t.y());
    }
    for (const Polygon& poly : *mesh.polygons) {
      std::fputc('f', f);
      for (int k = 0; k < poly.size(); ++k) {
        if (uv) {
          std::fprintf(f, " %d/%d", poly.v[k] + 1, poly.uv[k] + 1);
        } else {
          std::fprintf(f, " %d", poly.v[k] + 1);
        }
      }
      std::fputc('\n', f);
    }
    if (std::ferror(f) != 0) throw Error("cannot write " + path.string());
  }
  file.commit();
}

}  // namespace facecap
