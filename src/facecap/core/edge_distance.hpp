#pragma once
// Distances over a mesh's edges: the shortest path along edges from each
// vertex to the nearest of a set of source vertices (Dijkstra). On a mesh of
// even, small triangles it is close to the geodesic distance, overestimating
// it by a few per cent where paths cut across triangles.
#include <vector>

#include "facecap/core/mesh.hpp"

namespace facecap {

// positions: 3 x N; adjacency: the mesh's one-ring neighbours
// (vertex_adjacency); sources: vertex indices at distance 0. Distances in the
// positions' units; infinity where no path reaches. Throws facecap::Error
// for a source out of range.
std::vector<double> edge_path_distances(const Positions& positions, const VertexAdjacency& adjacency,
                                        const std::vector<int>& sources);

}  // namespace facecap
