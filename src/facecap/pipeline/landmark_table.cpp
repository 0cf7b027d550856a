#include "facecap/pipeline/landmark_table.hpp"

#include "facecap/core/csv_line.hpp"

namespace facecap {

namespace {

constexpr int kPointColumns = 7 * kNumLandmarks;  // x, y, fit_x, fit_y, X, Y, Z

void append_columns(std::string& out, const char* prefix) {
  for (int i = 0; i < kNumLandmarks; ++i) out += std::string(",") + prefix + std::to_string(i);
}

}  // namespace

std::string landmark_table_header() {
  std::string h = "frame,time,status";
  for (const char* prefix : {"x_", "y_", "fit_x_", "fit_y_", "X_", "Y_", "Z_"}) append_columns(h, prefix);
  return h;
}

std::string landmark_table_row(int frame, double time, const std::string& status, const CoarseFit* fit) {
  std::string row = std::to_string(frame) + ',' + csv_number(time) + ',' + status;
  if (fit == nullptr) return row + std::string(kPointColumns, ',');
  for (const Landmarks* points : {&fit->observed, &fit->fitted})
    for (int axis = 0; axis < 2; ++axis)
      for (const Vec2f& p : *points) row += ',' + csv_number(p[axis]);
  for (int axis = 0; axis < 3; ++axis)
    for (const Vec3d& p : fit->fitted_points) row += ',' + csv_number(10.0 * p[axis]);  // cm -> mm
  return row;
}

}  // namespace facecap
