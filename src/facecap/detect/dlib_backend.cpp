// The only translation unit that includes dlib: detection and landmarks.
#include <dlib/image_processing.h>
#include <dlib/image_processing/frontal_face_detector.h>
#include <dlib/opencv/cv_image.h>
#include <dlib/revision.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <mutex>
#include <opencv2/imgproc.hpp>
#include <span>
#include <string>

#include "facecap/core/atomic_file.hpp"
#include "facecap/core/error.hpp"
#include "facecap/core/fingerprint.hpp"
#include "facecap/core/paths.hpp"
#include "facecap/detect/face_detector.hpp"
#include "facecap/detect/landmark_detector.hpp"
#include "facecap/detect/regression_cascade.hpp"

namespace facecap {

namespace {

cv::Mat to_grey(const cv::Mat& image) {
  if (image.channels() == 1) return image;
  cv::Mat grey;
  cv::cvtColor(image, grey, image.channels() == 4 ? cv::COLOR_BGRA2GRAY : cv::COLOR_BGR2GRAY);
  return grey;
}

}  // namespace

// ---------------------------------------------------------------- detector

// dlib ships its HOG detector compressed: decoding it takes about 0.3 s
// (290 ms on the project's VM), reading the same detector back from dlib's
// plain serialisation 2-3 ms. The first run keeps that form in the cache
// folder, written whole or not at all, and later runs read it; a cache that
// is missing, unreadable or damaged only costs the decoding again (and is
// rewritten). Loaded once per process; each FaceDetector keeps a copy (the
// detector's call is not const, so instances cannot share one).
namespace {

dlib::frontal_face_detector load_frontal_face_detector() {
  const std::filesystem::path cached =
      cache_dir() / ("dlib-frontal-face-detector-" + std::to_string(DLIB_MAJOR_VERSION) + "." +
                     std::to_string(DLIB_MINOR_VERSION) + ".dat");
  std::error_code ec;
  if (std::filesystem::is_regular_file(cached, ec)) {
    try {
      dlib::frontal_face_detector detector;
      dlib::deserialize(cached.string()) >> detector;
      if (detector.num_detectors() > 0) return detector;
    } catch (const std::exception&) {
    }
  }
  dlib::frontal_face_detector detector = dlib::get_frontal_face_detector();
  try {
    AtomicFile file(cached);
    dlib::serialize(file.temp_path().string()) << detector;
    file.commit();
  } catch (const std::exception&) {
  }
  return detector;
}

const dlib::frontal_face_detector& decoded_frontal_face_detector() {
  static const dlib::frontal_face_detector detector = load_frontal_face_detector();
  return detector;
}

}  // namespace

struct FaceDetector::Impl {
  dlib::frontal_face_detector detector = decoded_frontal_face_detector();
};

FaceDetector::FaceDetector(FaceDetectorOptions options) : impl_(std::make_unique<Impl>()), options_(options) {}
FaceDetector::~FaceDetector() = default;
FaceDetector::FaceDetector(FaceDetector&&) noexcept = default;
FaceDetector& FaceDetector::operator=(FaceDetector&&) noexcept = default;

std::vector<FaceDetection> FaceDetector::detect(const cv::Mat& image) const {
  return detect_in(image, Box{0, 0, float(image.cols), float(image.rows)});
}

std::vector<FaceDetection> FaceDetector::detect_in(const cv::Mat& image, const Box& region) const {
  if (image.empty()) return {};
  const int x0 = std::clamp(int(region.x), 0, image.cols);
  const int y0 = std::clamp(int(region.y), 0, image.rows);
  const int x1 = std::clamp(int(region.x + region.width), 0, image.cols);
  const int y1 = std::clamp(int(region.y + region.height), 0, image.rows);
  if (x1 - x0 < 20 || y1 - y0 < 20) return {};
  cv::Mat grey = to_grey(image(cv::Rect(x0, y0, x1 - x0, y1 - y0)));
  // One resize to the searched size, so that an upsampled search of a large
  // frame sees its full resolution rather than a blown-up downscale.
  double scale = 1.0;
  const int side = std::max(grey.cols, grey.rows);
  if (options_.max_side > 0 && side > options_.max_side) {
    scale = double(options_.max_side) / side;
  } else if (options_.min_side > 0 && side < options_.min_side) {
    scale = double(options_.min_side) / side;
  }
  scale = std::ldexp(scale, options_.upsample);
  if (scale != 1.0) cv::resize(grey, grey, cv::Size(), scale, scale, scale < 1.0 ? cv::INTER_AREA : cv::INTER_LINEAR);
  if (!grey.isContinuous()) grey = grey.clone();
  dlib::cv_image<unsigned char> img(grey);
  std::vector<dlib::rect_detection> dets;
  impl_->detector(img, dets, options_.adjust_threshold);
  std::vector<FaceDetection> out;
  for (const auto& d : dets) {
    const auto& r = d.rect;
    out.push_back({Box{float(r.left() / scale + x0), float(r.top() / scale + y0), float(r.width() / scale),
                       float(r.height() / scale)},
                   d.detection_confidence});
  }
  std::sort(out.begin(), out.end(),
            [](const FaceDetection& a, const FaceDetection& b) { return a.box.area() > b.box.area(); });
  return out;
}

// ---------------------------------------------------------------- landmarks

std::filesystem::path default_landmark_model_path() {
  if (const char* v = std::getenv("FACECAP_LANDMARK_MODEL"); v != nullptr && *v != '\0') return v;
  return "/usr/share/dlib/shape_predictor_68_face_landmarks.dat";
}

// dlib's shape_predictor file, read field by field into the flat layout of
// RegressionCascade (detect/regression_cascade.hpp), which also evaluates the
// trees, so that the landmarks keep their sub-pixel positions: dlib's own
// operator() rounds every point to whole pixels (full_object_detection holds
// integer points), which would add about 0.3 px of quantisation noise to
// each coordinate. Throws facecap::Error naming the file.
namespace {

RegressionCascade read_dlib_shape_predictor(const std::filesystem::path& model_path) {
  dlib::matrix<float, 0, 1> initial_shape;
  std::vector<std::vector<dlib::impl::regression_tree>> forests;
  std::vector<std::vector<unsigned long>> anchor_idx;
  std::vector<std::vector<dlib::vector<float, 2>>> deltas;
  try {
    std::ifstream in(model_path, std::ios::binary);
    int version = 0;
    dlib::deserialize(version, in);
    if (version != 1) throw dlib::serialization_error("unexpected shape_predictor version");
    dlib::deserialize(initial_shape, in);
    dlib::deserialize(forests, in);
    dlib::deserialize(anchor_idx, in);
    dlib::deserialize(deltas, in);
  } catch (const std::exception&) {
    throw Error("cannot read landmark model " + model_path.string() + ": not a dlib shape predictor or truncated");
  }
  const auto inconsistent = [&]() {
    return Error("cannot read landmark model " + model_path.string() + ": its trees are inconsistent");
  };
  if (anchor_idx.size() != forests.size() || deltas.size() != forests.size()) throw inconsistent();
  const size_t dims = size_t(initial_shape.size());
  std::vector<CascadeLevel> levels(forests.size());
  std::vector<uint32_t> tree_split_begin{0};
  std::vector<RegressionSplit> splits;
  std::vector<float> leaves;
  for (size_t l = 0; l < forests.size(); ++l) {
    CascadeLevel& level = levels[l];
    level.anchor_idx.assign(anchor_idx[l].begin(), anchor_idx[l].end());
    for (const auto& d : deltas[l]) level.deltas.insert(level.deltas.end(), {d.x(), d.y()});
    level.first_tree = uint32_t(tree_split_begin.size() - 1);
    level.num_trees = uint32_t(forests[l].size());
    for (const dlib::impl::regression_tree& tree : forests[l]) {
      if (tree.leaf_values.size() != tree.splits.size() + 1) throw inconsistent();
      for (const auto& s : tree.splits) splits.push_back({uint32_t(s.idx1), uint32_t(s.idx2), s.thresh});
      for (const auto& leaf : tree.leaf_values) {
        if (size_t(leaf.size()) != dims) throw inconsistent();
        leaves.insert(leaves.end(), leaf.begin(), leaf.end());
      }
      tree_split_begin.push_back(uint32_t(splits.size()));
    }
  }
  try {
    return RegressionCascade(std::vector<float>(initial_shape.begin(), initial_shape.end()), std::move(levels),
                             std::move(tree_split_begin), std::move(splits), std::move(leaves));
  } catch (const Error&) {
    throw inconsistent();
  }
}

// Decoding dlib's file takes about half a second (its floats are stored as
// variable-length mantissas and exponents); mapping the flat copy that the
// first run keeps in the cache folder takes a few milliseconds. The copy
// carries the source file's fingerprint (path, size, modification time) and
// a checksum; a missing, stale or damaged one costs the decoding again and is
// rewritten, an unwritable cache folder only the time.
RegressionCascade load_regression_cascade(const std::filesystem::path& canonical) {
  const uint64_t fingerprint = fnv1a(file_stamp(canonical, canonical.string()), fnv1a("facecap-landmark-cache-v1"));
  char name[64];
  std::snprintf(name, sizeof(name), "dlib-shape-predictor-%016llx.fclm",
                static_cast<unsigned long long>(fnv1a(canonical.string())));
  const std::filesystem::path cached = cache_dir() / name;
  std::error_code ec;
  if (std::filesystem::is_regular_file(cached, ec)) {
    try {
      return RegressionCascade::load(cached, fingerprint);
    } catch (const Error&) {
    }
  }
  RegressionCascade cascade = read_dlib_shape_predictor(canonical);
  try {
    cascade.save(cached, fingerprint);
  } catch (const std::exception&) {
  }
  return cascade;
}

// The cascade and the per-level feature offsets in dlib's types, as its
// feature extraction takes them. Immutable once built; every detector of the
// process that reads the same file shares one.
struct LandmarkPredictor {
  RegressionCascade cascade;
  dlib::matrix<float, 0, 1> initial_shape;
  std::vector<std::vector<unsigned long>> anchor_idx;
  std::vector<std::vector<dlib::vector<float, 2>>> deltas;

  explicit LandmarkPredictor(RegressionCascade c) : cascade(std::move(c)) {
    const std::vector<float>& s = cascade.initial_shape();
    initial_shape.set_size(long(s.size()));
    std::copy(s.begin(), s.end(), initial_shape.begin());
    for (const CascadeLevel& level : cascade.levels()) {
      anchor_idx.emplace_back(level.anchor_idx.begin(), level.anchor_idx.end());
      auto& d = deltas.emplace_back(level.num_features());
      for (size_t i = 0; i < d.size(); ++i) d[i] = dlib::vector<float, 2>(level.deltas[2 * i], level.deltas[2 * i + 1]);
    }
  }
};

std::shared_ptr<const LandmarkPredictor> shared_landmark_predictor(const std::filesystem::path& model_path) {
  std::error_code ec;
  std::filesystem::path canonical = std::filesystem::canonical(model_path, ec);
  if (ec) canonical = model_path;
  static std::mutex mutex;
  static std::map<std::filesystem::path, std::weak_ptr<const LandmarkPredictor>> loaded;
  const std::lock_guard lock(mutex);
  if (auto p = loaded[canonical].lock()) return p;
  auto p = std::make_shared<const LandmarkPredictor>(load_regression_cascade(canonical));
  loaded[canonical] = p;
  return p;
}

}  // namespace

struct LandmarkDetector::Impl {
  std::shared_ptr<const LandmarkPredictor> predictor;

  // The cascade of dlib's shape_predictor::operator(), without its rounding.
  template <typename Image>
  std::vector<dlib::vector<double, 2>> predict(const Image& img, const dlib::rectangle& rect) const {
    const LandmarkPredictor& p = *predictor;
    dlib::matrix<float, 0, 1> shape = p.initial_shape;
    std::vector<float> feature_pixel_values;
    for (size_t level = 0; level < p.cascade.levels().size(); ++level) {
      dlib::impl::extract_feature_pixel_values(img, rect, shape, p.initial_shape, p.anchor_idx[level], p.deltas[level],
                                               feature_pixel_values);
      p.cascade.add_level(level, feature_pixel_values, std::span(&shape(0), size_t(shape.size())));
    }
    const dlib::point_transform_affine to_image = dlib::impl::unnormalizing_tform(rect);
    std::vector<dlib::vector<double, 2>> parts(p.cascade.num_parts());
    for (unsigned long i = 0; i < parts.size(); ++i) parts[i] = to_image(dlib::impl::location(shape, i));
    return parts;
  }
};

LandmarkDetector::LandmarkDetector(const std::filesystem::path& model_path) : impl_(std::make_unique<Impl>()) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(model_path, ec)) {
    throw Error("landmark model not found: " + model_path.string() + " (install the Debian package libdlib-data)");
  }
  impl_->predictor = shared_landmark_predictor(model_path);
  if (impl_->predictor->cascade.num_parts() != kNumLandmarks) {
    throw Error("landmark model " + model_path.string() + " predicts " +
                std::to_string(impl_->predictor->cascade.num_parts()) + " points, expected 68");
  }
}
LandmarkDetector::~LandmarkDetector() = default;
LandmarkDetector::LandmarkDetector(LandmarkDetector&&) noexcept = default;
LandmarkDetector& LandmarkDetector::operator=(LandmarkDetector&&) noexcept = default;

namespace {

// dlib's rectangle of a box (inclusive pixel bounds).
dlib::rectangle dlib_rect(const Box& box) {
  return {long(std::lround(box.x)), long(std::lround(box.y)), long(std::lround(box.x + box.width - 1)),
          long(std::lround(box.y + box.height - 1))};
}

// Each iBUG point's mirror image across the face's midline (jaw 0 <-> 16,
// brows 17 <-> 26, nose wings 31 <-> 35, eye corners 36 <-> 45, mouth
// corners 48 <-> 54 ...; the midline's points are their own).
constexpr std::array<int, kNumLandmarks> kMirroredLandmark = {
    16, 15, 14, 13, 12, 11, 10, 9,  8,  7,  6,  5,  4,  3,  2,  1,  0,  26, 25, 24, 23, 22, 21,
    20, 19, 18, 17, 27, 28, 29, 30, 35, 34, 33, 32, 31, 45, 44, 43, 42, 47, 46, 39, 38, 37, 36,
    41, 40, 54, 53, 52, 51, 50, 49, 48, 59, 58, 57, 56, 55, 64, 63, 62, 61, 60, 67, 66, 65};

}  // namespace

Landmarks LandmarkDetector::detect_once(const cv::Mat& grey_in, const Box& box) const {
  const cv::Mat grey = to_grey(grey_in);
  const auto parts = impl_->predict(dlib::cv_image<unsigned char>(grey), dlib_rect(box));
  Landmarks lm;
  for (int i = 0; i < kNumLandmarks; ++i) lm[i] = Vec2f(float(parts[i].x()), float(parts[i].y()));
  return lm;
}

Landmarks LandmarkDetector::detect(const cv::Mat& image, const Box& box) const {
  const cv::Mat grey = to_grey(image);  // once for both passes (a colour image would be converted twice)
  return average_with_mirror(grey, box, detect_once(grey, box));
}

Landmarks LandmarkDetector::average_with_mirror(const cv::Mat& grey_in, const Box& box, const Landmarks& once) const {
  const cv::Mat grey = to_grey(grey_in);
  Landmarks lm = once;
  // The mirror is of a crop twice the box's size about it, wider than every
  // pixel the cascade reads (LandmarkDetector tests: the same points as the
  // whole image mirrored).
  const int x0 = std::clamp(int(std::floor(box.x - 0.5f * box.width)), 0, grey.cols);
  const int x1 = std::clamp(int(std::ceil(box.x + 1.5f * box.width)), x0, grey.cols);
  const int y0 = std::clamp(int(std::floor(box.y - 0.5f * box.height)), 0, grey.rows);
  const int y1 = std::clamp(int(std::ceil(box.y + 1.5f * box.height)), y0, grey.rows);
  if (x1 - x0 < 2 || y1 - y0 < 2) return lm;
  cv::Mat mirrored;
  cv::flip(grey(cv::Rect(x0, y0, x1 - x0, y1 - y0)), mirrored, 1);
  // The crop's column u shows the image's column x1 - 1 - u.
  const Box mirrored_box{float(x1) - box.x - box.width, box.y - float(y0), box.width, box.height};
  const auto mirrored_parts = impl_->predict(dlib::cv_image<unsigned char>(mirrored), dlib_rect(mirrored_box));
  for (int i = 0; i < kNumLandmarks; ++i) {
    const auto& q = mirrored_parts[kMirroredLandmark[i]];
    lm[i] = 0.5f * (lm[i] + Vec2f(float(x1 - 1 - q.x()), float(q.y() + y0)));
  }
  return lm;
}

}  // namespace facecap
