#include "facecap/pipeline/landmark_folder_eval.hpp"

#include <algorithm>

#include "facecap/core/error.hpp"
#include "facecap/core/interrupt.hpp"
#include "facecap/core/progress.hpp"
#include "facecap/core/statistics.hpp"
#include "facecap/detect/landmarks.hpp"
#include "facecap/io/input.hpp"
#include "facecap/pipeline/capture_session.hpp"
#include "facecap/pipeline/landmark_eval.hpp"

namespace facecap {

namespace fs = std::filesystem;

LandmarkScores landmark_scores(const std::vector<std::optional<double>>& nmes, double threshold) {
  LandmarkScores s;
  s.images = static_cast<int>(nmes.size());
  if (nmes.empty()) return s;
  std::vector<double> found;
  int failures = 0;
  double auc = 0;
  for (const std::optional<double>& nme : nmes) {
    if (!nme || *nme > threshold) ++failures;
    if (!nme) continue;
    found.push_back(*nme);
    // The CED curve's area: an image counts from its NME on, so it adds
    // (threshold - NME) / threshold of the unit area.
    auc += std::max(0.0, 1.0 - *nme / threshold);
  }
  s.scored = static_cast<int>(found.size());
  s.failure_rate = double(failures) / double(s.images);
  s.auc = auc / double(s.images);
  if (!found.empty()) {
    double sum = 0;
    for (const double nme : found) sum += nme;
    s.nme_mean = sum / double(found.size());
    s.nme_median = median(found);
  }
  return s;
}

namespace {

// The fitted model's landmarks projected, for an image fitted alone as a
// photo (CaptureSession on a still: its own identity and focal length), the
// face nearest `centre` chosen; none where no face was fitted.
std::optional<Landmarks> fitted_landmarks(const FaceModel& model, const fs::path& image, const Vec2f& centre) {
  const auto source = open_input(image.string());
  CaptureOptions options;
  options.quiet = true;
  options.tracker.pick = {FacePick::Rule::kNearest, centre};
  std::optional<Landmarks> fitted;
  run_capture(model, *source, options, [&](const CapturedFrame& f) {
    if (f.status != TrackStatus::kLost) fitted = f.fit.fitted;
  });
  return fitted;
}

}  // namespace

LandmarkFolderEval evaluate_landmark_folder(const FaceModel& model, const fs::path& folder, bool quiet) {
  if (!fs::is_directory(folder)) throw Error("eval landmarks: " + folder.string() + " is no folder");
  std::vector<fs::path> annotated;
  LandmarkFolderEval r;
  for (const fs::path& image : folder_images(folder)) {
    if (fs::exists(fs::path(image).replace_extension(".pts")))
      annotated.push_back(image);
    else
      ++r.unannotated;
  }
  if (annotated.empty())
    throw Error("no image in " + folder.string() + " has an annotation beside it (IMAGE with IMAGE-name.pts)");
  std::vector<std::optional<double>> dlib_nmes, fitted_nmes;
  Progress progress("annotated images", static_cast<int>(annotated.size()), quiet);
  for (const fs::path& image : annotated) {
    throw_if_interrupted();
    AnnotatedImageScore score;
    score.image = image.filename().string();
    const fs::path pts = fs::path(image).replace_extension(".pts");
    try {
      const Landmarks truth = read_pts(pts);
      const LandmarkEvalResult dlib = evaluate_landmarks(image, pts);
      score.faces = dlib.faces;
      score.nme = dlib.nme;
      const Box box = bounding_box(truth);
      if (const std::optional<Landmarks> fitted = fitted_landmarks(model, image, box.center()))
        score.fitted_nme = landmark_nme(*fitted, truth);
      else
        score.error = "the fit found no face";
    } catch (const Error& e) {  // unreadable, malformed annotation, no face: the image's failure, not the run's
      score.error = e.what();
    }
    dlib_nmes.push_back(score.nme);
    fitted_nmes.push_back(score.fitted_nme);
    r.images.push_back(std::move(score));
    progress.update(static_cast<int>(r.images.size()));
  }
  progress.finish();
  r.dlib = landmark_scores(dlib_nmes);
  r.fitted = landmark_scores(fitted_nmes);
  return r;
}

}  // namespace facecap
