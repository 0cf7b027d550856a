#pragma once
// Named vertex and polygon ranges of the ICT Face Model Light (FACTS.md).
#include <string_view>

namespace facecap {

struct Region {
  std::string_view name;
  int first_vertex;
  int last_vertex;  // inclusive
  int first_polygon;
  int last_polygon;  // inclusive; -1 when the region has no listed polygons
  int num_vertices() const { return last_vertex - first_vertex + 1; }
  int num_polygons() const { return last_polygon < 0 ? 0 : last_polygon - first_polygon + 1; }
};

namespace regions {
// The full face area: what the tracker fits and the refinement subdivides.
inline constexpr Region kFace{"face", 0, 9408, 0, 9229};
inline constexpr Region kNarrowFace{"narrow_face", 0, 6705, 0, 6559};
inline constexpr Region kHeadAndNeck{"head_and_neck", 9409, 11247, 9230, 11143};
inline constexpr Region kMouthSocket{"mouth_socket", 11248, 13293, 11144, 13225};
inline constexpr Region kEyeSocketLeft{"eye_socket_left", 13294, 13677, -1, -1};
inline constexpr Region kEyeSocketRight{"eye_socket_right", 13678, 14061, -1, -1};
inline constexpr Region kGumsAndTongue{"gums_and_tongue", 14062, 17038, -1, -1};
inline constexpr Region kTeeth{"teeth", 17039, 21450, -1, -1};
inline constexpr Region kEyeballLeft{"eyeball_left", 21451, 23020, -1, -1};
inline constexpr Region kEyeballRight{"eyeball_right", 23021, 24590, -1, -1};
inline constexpr Region kEyeExtras{"eye_extras", 24591, 26718, -1, -1};
}  // namespace regions

inline constexpr int kIctVertexCount = 26719;
inline constexpr int kIctPolygonCount = 26384;

}  // namespace facecap
