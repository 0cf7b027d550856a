#pragma once
// What expression to show when: keys of (time, target, intensity), with
// linear transitions between consecutive keys (the paper lists transitions
// between expressions as missing). A file has one key per line,
// "seconds target intensity", e.g.
//   0    neutral   0
//   1.5  happiness 1
//   4    sadness   0.8
// Lines starting with # are comments.
#include <filesystem>
#include <vector>

#include "facecap/expr/emotions.hpp"

namespace facecap {

struct ScheduleKey {
  double time = 0;
  Emotion target = Emotion::kNeutral;
  double intensity = 1.0;  // 0: the source expression, 1: the full mapping
};

// At a time: two targets and their blend (b_share of the second).
struct ScheduleState {
  ScheduleKey a, b;
  double b_share = 0.0;
};

class ExpressionSchedule {
 public:
  static ExpressionSchedule constant(Emotion target, double intensity);
  // Throws facecap::Error naming the file and line when it is malformed.
  static ExpressionSchedule read(const std::filesystem::path& path);
  explicit ExpressionSchedule(std::vector<ScheduleKey> keys);
  ExpressionSchedule() = default;

  ScheduleState at(double time) const;
  const std::vector<ScheduleKey>& keys() const { return keys_; }

 private:
  std::vector<ScheduleKey> keys_;
};

}  // namespace facecap
