#include "facecap/detect/aligned_face.hpp"

#include <complex>

#include <opencv2/imgproc.hpp>

namespace facecap {

namespace {

// ArcFace's template for 112x112: the image-left eye, the image-right eye,
// the nose tip, the image-left and image-right mouth corners.
constexpr double kTemplate112[5][2] = {
    {38.2946, 51.6963}, {73.5318, 51.5014}, {56.0252, 71.7366}, {41.5493, 92.3655}, {70.7299, 92.2041}};

Vec2f mean_of(const Landmarks& lm, int first, int count) {
  Vec2f sum = Vec2f::Zero();
  for (int i = first; i < first + count; ++i) sum += lm[i];
  return sum / float(count);
}

}  // namespace

std::array<Vec2f, 5> aligned_face_template(int size) {
  // Scaled about the origin, as the models' own code scales it for other
  // crop sizes (2x for 224x224); pixel centres at integers, as warpAffine's.
  const double scale = double(size) / kAlignedFaceSize;
  std::array<Vec2f, 5> points;
  for (int k = 0; k < 5; ++k) points[k] = Vec2f(float(scale * kTemplate112[k][0]), float(scale * kTemplate112[k][1]));
  return points;
}

std::array<Vec2f, 5> five_face_points(const Landmarks& lm) {
  return {mean_of(lm, 36, 6), mean_of(lm, 42, 6), lm[30], lm[48], lm[54]};
}

Eigen::Matrix<double, 2, 3> aligned_face_transform(const Landmarks& lm, int size) {
  // With points as complex numbers, a similarity is w = a z + t (a: scale
  // and rotation). About the centroids, the least-squares a is
  // sum(conj(z) w) / sum(|z|^2) (Umeyama 1991, without reflection).
  using C = std::complex<double>;
  const std::array<Vec2f, 5> from = five_face_points(lm), to = aligned_face_template(size);
  C from_mean = 0, to_mean = 0;
  for (int k = 0; k < 5; ++k) {
    from_mean += C(from[k].x(), from[k].y()) / 5.0;
    to_mean += C(to[k].x(), to[k].y()) / 5.0;
  }
  C cross = 0;
  double norm = 0;
  for (int k = 0; k < 5; ++k) {
    const C z = C(from[k].x(), from[k].y()) - from_mean, w = C(to[k].x(), to[k].y()) - to_mean;
    cross += std::conj(z) * w;
    norm += std::norm(z);
  }
  const C a = norm > 0 ? cross / norm : C(0);
  const C t = to_mean - a * from_mean;
  Eigen::Matrix<double, 2, 3> m;
  m << a.real(), -a.imag(), t.real(), a.imag(), a.real(), t.imag();
  return m;
}

cv::Mat aligned_face(const cv::Mat& image, const Landmarks& lm, int size) {
  const Eigen::Matrix<double, 2, 3> m = aligned_face_transform(lm, size);
  cv::Mat transform(2, 3, CV_64F);
  for (int r = 0; r < 2; ++r)
    for (int c = 0; c < 3; ++c) transform.at<double>(r, c) = m(r, c);
  cv::Mat crop;
  cv::warpAffine(image, crop, transform, cv::Size(size, size), cv::INTER_LINEAR, cv::BORDER_CONSTANT, cv::Scalar());
  return crop;
}

}  // namespace facecap
