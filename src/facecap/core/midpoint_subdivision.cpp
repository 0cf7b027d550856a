#include "facecap/core/midpoint_subdivision.hpp"

#include <map>
#include <utility>

namespace facecap {

MidpointSubdivision subdivide_midpoint(const std::vector<Triangle>& triangles, int num_vertices, int levels) {
  MidpointSubdivision s;
  s.num_coarse = num_vertices;
  s.num_vertices = num_vertices;
  s.triangles = triangles;
  for (int level = 0; level < levels; ++level) {
    std::map<std::pair<int, int>, int> midpoint;
    auto mid = [&](int a, int b) {
      const auto key = std::minmax(a, b);
      const auto it = midpoint.find(key);
      if (it != midpoint.end()) return it->second;
      const int v = s.num_vertices++;
      s.parents.push_back({a, b});
      midpoint.emplace(key, v);
      return v;
    };
    std::vector<Triangle> finer;
    finer.reserve(s.triangles.size() * 4);
    for (const Triangle& t : s.triangles) {
      const int ab = mid(t[0], t[1]), bc = mid(t[1], t[2]), ca = mid(t[2], t[0]);
      finer.push_back({t[0], ab, ca});
      finer.push_back({ab, t[1], bc});
      finer.push_back({ca, bc, t[2]});
      finer.push_back({ab, bc, ca});
    }
    s.triangles = std::move(finer);
  }
  return s;
}

Positions MidpointSubdivision::prolong(const Positions& coarse) const {
  Positions fine(3, num_vertices);
  fine.leftCols(num_coarse) = coarse;
  for (int v = num_coarse; v < num_vertices; ++v) {
    const auto& p = parents[v - num_coarse];
    fine.col(v) = 0.5f * (fine.col(p[0]) + fine.col(p[1]));
  }
  return fine;
}

std::vector<Vec2f> MidpointSubdivision::prolong(const std::vector<Vec2f>& coarse) const {
  std::vector<Vec2f> fine(coarse);
  fine.resize(num_vertices);
  for (int v = num_coarse; v < num_vertices; ++v) {
    const auto& p = parents[v - num_coarse];
    fine[v] = 0.5f * (fine[p[0]] + fine[p[1]]);
  }
  return fine;
}

}  // namespace facecap
