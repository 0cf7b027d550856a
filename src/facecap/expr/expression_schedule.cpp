#include "facecap/expr/expression_schedule.hpp"

#include <algorithm>
#include <fstream>
#include <sstream>

#include "facecap/core/error.hpp"

namespace facecap {

ExpressionSchedule ExpressionSchedule::constant(Emotion target, double intensity) {
  return ExpressionSchedule({ScheduleKey{0.0, target, intensity}});
}

ExpressionSchedule::ExpressionSchedule(std::vector<ScheduleKey> keys) : keys_(std::move(keys)) {
  if (keys_.empty()) throw Error("an expression schedule needs at least one key");
  std::stable_sort(keys_.begin(), keys_.end(),
                   [](const ScheduleKey& x, const ScheduleKey& y) { return x.time < y.time; });
  for (const ScheduleKey& k : keys_) {
    if (!(k.intensity >= 0 && k.intensity <= 1)) throw Error("schedule intensities must be in [0, 1]");
  }
}

ExpressionSchedule ExpressionSchedule::read(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw Error("schedule file not found: " + path.string());
  std::vector<ScheduleKey> keys;
  std::string line;
  for (int n = 1; std::getline(in, line); ++n) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream ss(line);
    ScheduleKey k;
    std::string target;
    if (!(ss >> k.time >> target >> k.intensity)) {
      throw Error("malformed schedule " + path.string() + " line " + std::to_string(n) +
                  ": expected 'seconds target intensity'");
    }
    const auto e = parse_emotion(target);
    if (!e)
      throw Error("malformed schedule " + path.string() + " line " + std::to_string(n) + ": unknown expression '" +
                  target + "'");
    if (k.intensity < 0 || k.intensity > 1) {
      throw Error("malformed schedule " + path.string() + " line " + std::to_string(n) +
                  ": intensity must be in [0, 1]");
    }
    k.target = *e;
    keys.push_back(k);
  }
  if (keys.empty()) throw Error("schedule " + path.string() + " has no keys");
  return ExpressionSchedule(std::move(keys));
}

ScheduleState ExpressionSchedule::at(double time) const {
  ScheduleState s;
  if (time <= keys_.front().time) {
    s.a = s.b = keys_.front();
    return s;
  }
  for (size_t i = 0; i + 1 < keys_.size(); ++i) {
    if (time < keys_[i + 1].time) {
      s.a = keys_[i];
      s.b = keys_[i + 1];
      s.b_share = (time - keys_[i].time) / std::max(1e-9, keys_[i + 1].time - keys_[i].time);
      return s;
    }
  }
  s.a = s.b = keys_.back();
  return s;
}

}  // namespace facecap
