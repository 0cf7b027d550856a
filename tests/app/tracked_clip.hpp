#pragma once
// A short clip tracked by the facecap binary, for the tests that hand its
// output to another tool (Blender, three.js) and compare what the tool makes
// of it with the fit.
#include <filesystem>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "app/command.hpp"
#include "test_support.hpp"

namespace facecap::test {

// The first 20 frames of `video` tracked into `dir` by facecap with `flags`.
inline CommandResult track_20_frames(const std::filesystem::path& video, const std::filesystem::path& dir,
                                     const std::string& flags) {
  return run_command(std::string(FACECAP_BINARY) + " -q track " + video.string() + " -o " + dir.string() +
                     " --max-frames 20 " + flags + " 2>&1");
}

// The fitted landmarks of `frame` (frames.jsonl), in pixels times `scale`.
inline std::vector<cv::Point2f> fitted_landmarks(const std::filesystem::path& frames_jsonl, int frame, float scale) {
  const nlohmann::json row = nlohmann::json::parse(read_lines(frames_jsonl).at(size_t(frame)));
  std::vector<cv::Point2f> points;
  for (const auto& p : row["fitted_landmarks"])
    points.emplace_back(p[0].get<float>() * scale, p[1].get<float>() * scale);
  return points;
}

}  // namespace facecap::test
