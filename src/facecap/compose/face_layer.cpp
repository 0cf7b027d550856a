#include "facecap/compose/face_layer.hpp"

#include "facecap/compose/laplacian_blend.hpp"

namespace facecap {

FaceLayer make_layer(const cv::Mat& frame, cv::Rect content, int margin) {
  content.x -= margin;
  content.y -= margin;
  content.width += 2 * margin;
  content.height += 2 * margin;
  FaceLayer layer;
  layer.box = content & cv::Rect(0, 0, frame.cols, frame.rows);
  layer.colour = layer.box.area() > 0 ? frame(layer.box).clone() : cv::Mat(0, 0, CV_8UC3);
  layer.mask = cv::Mat(layer.box.size(), CV_8U, cv::Scalar(0));
  return layer;
}

cv::Mat layer_blend_mask(const FaceLayer& layer, int inset, double feather) {
  return feather_mask(layer.mask, inset, feather);
}

cv::Mat layer_share(const FaceLayer& layer) { return layer.share.empty() ? layer_blend_mask(layer) : layer.share; }

void composite_layer(cv::Mat& frame, const FaceLayer& layer, int inset, double feather, int levels) {
  if (layer.box.area() == 0 || cv::countNonZero(layer.mask) == 0) return;
  cv::Mat window = frame(layer.box);
  const cv::Mat blended = laplacian_blend(window, layer.colour, layer_blend_mask(layer, inset, feather), levels);
  blended.copyTo(window);
}

}  // namespace facecap
