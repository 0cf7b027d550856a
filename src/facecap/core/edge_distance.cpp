#include "facecap/core/edge_distance.hpp"

#include <functional>
#include <limits>
#include <queue>
#include <utility>

#include "facecap/core/error.hpp"

namespace facecap {

std::vector<double> edge_path_distances(const Positions& positions, const VertexAdjacency& adjacency,
                                        const std::vector<int>& sources) {
  const int n = int(positions.cols());
  std::vector<double> distance(size_t(n), std::numeric_limits<double>::infinity());
  using Entry = std::pair<double, int>;  // (distance, vertex), nearest first
  std::priority_queue<Entry, std::vector<Entry>, std::greater<>> frontier;
  for (const int s : sources) {
    if (s < 0 || s >= n) throw Error("edge_path_distances: source vertex " + std::to_string(s) + " out of range");
    distance[size_t(s)] = 0;
    frontier.emplace(0.0, s);
  }
  while (!frontier.empty()) {
    const auto [d, v] = frontier.top();
    frontier.pop();
    if (d > distance[size_t(v)]) continue;  // an older, longer entry
    for (int k = adjacency.offsets[size_t(v)]; k < adjacency.offsets[size_t(v) + 1]; ++k) {
      const int w = adjacency.indices[size_t(k)];
      const double through = d + double((positions.col(w) - positions.col(v)).norm());
      if (through < distance[size_t(w)]) {
        distance[size_t(w)] = through;
        frontier.emplace(through, w);
      }
    }
  }
  return distance;
}

}  // namespace facecap
