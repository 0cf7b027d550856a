#include "facecap/refine/displacement_problem_io.hpp"

#include <algorithm>
#include <cstring>
#include <fstream>
#include <iterator>

#include "facecap/core/atomic_file.hpp"
#include "facecap/core/binary_io.hpp"

namespace facecap {

namespace {

constexpr char kMagic[8] = {'F', 'C', 'A', 'P', 'D', 'S', 'P', '\0'};
constexpr uint32_t kVersion = 1;
constexpr uint32_t kMaxCount = 1u << 26;

void write_pairs(ByteWriter& w, const std::vector<std::array<int, 2>>& pairs) {
  std::vector<int> flat;
  flat.reserve(2 * pairs.size());
  for (const auto& [a, b] : pairs) {
    flat.push_back(a);
    flat.push_back(b);
  }
  w.ints(flat);
}

std::vector<std::array<int, 2>> read_pairs(ByteReader& r) {
  const std::vector<int> flat = r.ints(kMaxCount);
  if (flat.size() % 2) r.corrupt();
  std::vector<std::array<int, 2>> pairs(flat.size() / 2);
  for (size_t i = 0; i < pairs.size(); ++i) pairs[i] = {flat[2 * i], flat[2 * i + 1]};
  return pairs;
}

void write_mask(ByteWriter& w, const std::vector<bool>& mask) { w.ints(std::vector<int>(mask.begin(), mask.end())); }
std::vector<bool> read_mask(ByteReader& r) {
  const std::vector<int> v = r.ints(kMaxCount);
  return std::vector<bool>(v.begin(), v.end());
}

void write_matrix(ByteWriter& w, const Eigen::MatrixXf& m) {
  w.pod(static_cast<uint32_t>(m.rows()));
  w.pod(static_cast<uint32_t>(m.cols()));
  w.floats(m.data(), m.size());
}
template <typename M>
M read_matrix(ByteReader& r) {
  const uint32_t rows = r.pod<uint32_t>(), cols = r.pod<uint32_t>();
  if (uint64_t(rows) * cols > kMaxCount) r.corrupt();
  if ((M::RowsAtCompileTime != Eigen::Dynamic && rows != uint32_t(M::RowsAtCompileTime)) ||
      (M::ColsAtCompileTime != Eigen::Dynamic && cols != uint32_t(M::ColsAtCompileTime)))
    r.corrupt();
  M m(rows, cols);
  r.floats(m.data(), m.size());
  return m;
}

}  // namespace

void save_displacement_problem(const std::filesystem::path& path, const DisplacementProblem& p,
                               const Eigen::VectorXf& start, int frame, int level_index) {
  const MeshLevel& lv = *p.level;
  ByteWriter w;
  w.raw(kMagic, sizeof(kMagic));
  w.pod(kVersion);
  w.pod(static_cast<int32_t>(frame));
  w.pod(static_cast<int32_t>(level_index));
  w.pod(static_cast<int32_t>(lv.num_vertices));
  w.ints(lv.rings.offsets);
  w.ints(lv.rings.indices);
  w.ints(lv.corner_offsets);
  write_pairs(w, lv.corners);
  write_pairs(w, lv.corner_slots);
  w.ints(lv.ring_transpose);
  write_mask(w, lv.boundary);
  write_matrix(w, p.base);
  write_matrix(w, p.base_normals);
  write_matrix(w, p.albedo);
  for (int k = 0; k < 9; ++k) w.pod(p.lighting[k]);
  write_matrix(w, p.samples->colour);
  write_mask(w, p.samples->visible);
  write_matrix(w, p.prolonged);
  write_matrix(w, p.previous);
  write_mask(w, p.active);
  write_matrix(w, start);
  write_binary_file(path, w.bytes().data(), w.bytes().size());
}

std::unique_ptr<SavedDisplacementProblem> load_displacement_problem(const std::filesystem::path& path) {
  std::ifstream f(path, std::ios::binary);
  if (!f) throw Error("cannot open the displacement problem " + path.string());
  const std::string bytes((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  ByteReader r(bytes, "displacement problem", path);
  char magic[8];
  r.raw(magic, sizeof(magic));
  if (std::memcmp(magic, kMagic, sizeof(kMagic)) != 0)
    throw Error("not a facecap displacement problem: " + path.string());
  if (r.pod<uint32_t>() != kVersion) throw Error("displacement problem of another version: " + path.string());
  auto s = std::make_unique<SavedDisplacementProblem>();
  s->frame = r.pod<int32_t>();
  s->level_index = r.pod<int32_t>();
  MeshLevel& lv = s->level;
  lv.num_vertices = r.pod<int32_t>();
  const auto n = static_cast<size_t>(lv.num_vertices);
  lv.rings.offsets = r.ints(kMaxCount);
  lv.rings.indices = r.ints(kMaxCount);
  lv.corner_offsets = r.ints(kMaxCount);
  lv.corners = read_pairs(r);
  lv.corner_slots = read_pairs(r);
  lv.ring_transpose = r.ints(kMaxCount);
  lv.boundary = read_mask(r);
  DisplacementProblem& p = s->problem;
  p.base = read_matrix<Positions>(r);
  p.base_normals = read_matrix<Positions>(r);
  p.albedo = read_matrix<Positions>(r);
  for (int k = 0; k < 9; ++k) p.lighting[k] = r.pod<double>();
  s->samples.colour = read_matrix<Positions>(r);
  s->samples.visible = read_mask(r);
  p.prolonged = read_matrix<Eigen::VectorXf>(r);
  p.previous = read_matrix<Eigen::VectorXf>(r);
  p.active = read_mask(r);
  s->start = read_matrix<Eigen::VectorXf>(r);
  if (!r.done()) r.corrupt();
  // Every index the solver follows must stay inside the level.
  const auto in_range = [&](const std::vector<int>& v, int lo, int hi) {
    for (int x : v)
      if (x < lo || x >= hi) return false;
    return true;
  };
  const bool consistent =
      n > 0 && lv.rings.offsets.size() == n + 1 && lv.corner_offsets.size() == n + 1 && lv.boundary.size() == n &&
      lv.rings.offsets.front() == 0 && size_t(lv.rings.offsets.back()) == lv.rings.indices.size() &&
      lv.corner_offsets.front() == 0 && size_t(lv.corner_offsets.back()) == lv.corners.size() &&
      lv.corner_slots.size() == lv.corners.size() && lv.ring_transpose.size() == lv.rings.indices.size() &&
      std::is_sorted(lv.rings.offsets.begin(), lv.rings.offsets.end()) &&
      std::is_sorted(lv.corner_offsets.begin(), lv.corner_offsets.end()) &&
      in_range(lv.rings.indices, 0, lv.num_vertices) &&
      in_range(lv.ring_transpose, -1, static_cast<int>(lv.rings.indices.size())) &&
      std::all_of(
          lv.corners.begin(), lv.corners.end(),
          [&](const auto& c) { return c[0] >= 0 && c[0] < lv.num_vertices && c[1] >= 0 && c[1] < lv.num_vertices; }) &&
      p.base.cols() == lv.num_vertices && p.base_normals.cols() == lv.num_vertices &&
      p.albedo.cols() == lv.num_vertices && s->samples.colour.cols() == lv.num_vertices &&
      s->samples.visible.size() == n && s->start.size() == lv.num_vertices &&
      (p.prolonged.size() == 0 || p.prolonged.size() == lv.num_vertices) &&
      (p.previous.size() == 0 || p.previous.size() == lv.num_vertices) && (p.active.empty() || p.active.size() == n);
  if (!consistent) r.corrupt();
  p.level = &s->level;
  p.samples = &s->samples;
  return s;
}

std::vector<std::unique_ptr<SavedDisplacementProblem>> load_displacement_problems(const std::filesystem::path& dir) {
  if (!std::filesystem::is_directory(dir)) throw Error("no such folder of displacement problems: " + dir.string());
  std::vector<std::unique_ptr<SavedDisplacementProblem>> problems;
  for (const auto& e : std::filesystem::directory_iterator(dir))
    if (e.path().extension() == ".fcdp") problems.push_back(load_displacement_problem(e.path()));
  if (problems.empty())
    throw Error("no .fcdp problem files in " + dir.string() +
                " (write them with `facecap eval refine --video V --save-problems DIR`)");
  std::sort(problems.begin(), problems.end(), [](const auto& a, const auto& b) {
    return std::pair(a->frame, a->level_index) < std::pair(b->frame, b->level_index);
  });
  return problems;
}

}  // namespace facecap
