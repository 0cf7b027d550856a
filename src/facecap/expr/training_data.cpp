#include "facecap/expr/training_data.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <unordered_map>

#include "facecap/core/atomic_file.hpp"
#include "facecap/core/csv_line.hpp"
#include "facecap/core/error.hpp"

namespace facecap {

namespace {

// Column index of each name in a header.
std::vector<int> columns(const std::vector<std::string>& header, const std::vector<std::string>& names,
                         const std::filesystem::path& path) {
  std::unordered_map<std::string, int> at;
  for (size_t i = 0; i < header.size(); ++i) at[header[i]] = static_cast<int>(i);
  std::vector<int> out;
  for (const std::string& n : names) {
    const auto it = at.find(n);
    if (it == at.end()) throw Error(path.string() + " has no column '" + n + "'");
    out.push_back(it->second);
  }
  return out;
}

float parse_weight(const std::string& s, const std::filesystem::path& path, int line) {
  try {
    size_t used = 0;
    const float v = std::stof(s, &used);
    if (used != s.size() || !std::isfinite(v)) throw std::invalid_argument(s);
    return v;
  } catch (const std::exception&) {
    throw Error("malformed " + path.string() + " line " + std::to_string(line) + ": '" + s + "' is not a number");
  }
}

}  // namespace

std::vector<Eigen::VectorXf> read_tracked_weights(const std::filesystem::path& csv,
                                                  const std::vector<std::string>& names, double from_seconds,
                                                  double to_seconds) {
  std::ifstream in(csv);
  if (!in) throw Error("tracking file not found: " + csv.string());
  std::string line;
  if (!std::getline(in, line)) throw Error("empty tracking file: " + csv.string());
  const std::vector<std::string> header = split_csv_line(line);
  const std::vector<int> cols = columns(header, names, csv);
  const std::vector<int> status_col = columns(header, {"status"}, csv);
  const std::vector<int> time_col = columns(header, {"time"}, csv);
  std::vector<Eigen::VectorXf> out;
  for (int n = 2; std::getline(in, line); ++n) {
    const std::vector<std::string> cells = split_csv_line(line);
    if (cells.size() != header.size()) throw Error("malformed " + csv.string() + " line " + std::to_string(n));
    if (cells[status_col[0]] == "lost") continue;
    const double time = parse_weight(cells[time_col[0]], csv, n);
    if (time < from_seconds || time > to_seconds) continue;
    Eigen::VectorXf w(static_cast<Eigen::Index>(names.size()));
    for (size_t k = 0; k < names.size(); ++k) w[k] = parse_weight(cells[cols[k]], csv, n);
    out.push_back(w);
  }
  return out;
}

std::vector<LabeledWeights> make_emotion_samples(Emotion emotion, const std::vector<Eigen::VectorXf>& speech,
                                                 const std::vector<std::string>& names, int count, uint64_t seed) {
  std::mt19937_64 rng(seed ^ (0x9e3779b97f4a7c15ull * (static_cast<uint64_t>(emotion) + 1)));
  std::uniform_real_distribution<float> intensity(0.35f, 1.0f), asym(-0.15f, 0.15f), u(0.0f, 1.0f);
  std::unordered_map<std::string, int> index;
  for (size_t i = 0; i < names.size(); ++i) index[names[i]] = static_cast<int>(i);
  std::vector<LabeledWeights> out;
  for (int s = 0; s < count; ++s) {
    Eigen::VectorXf w = speech.empty() ? Eigen::VectorXf::Zero(static_cast<Eigen::Index>(names.size()))
                                       : speech[static_cast<size_t>(u(rng) * speech.size()) % speech.size()];
    const float i = intensity(rng), a = asym(rng);
    for (const auto& [name, weight] : emotion_prototype(emotion)) {
      const auto it = index.find(name);
      if (it == index.end()) continue;
      const float side = name.ends_with("_L") ? 1 + a : name.ends_with("_R") ? 1 - a : 1;
      w[it->second] = std::max(w[it->second], std::clamp(float(weight) * i * side, 0.0f, 1.0f));
    }
    out.push_back({emotion, w});
  }
  return out;
}

void write_dataset_csv(const std::filesystem::path& path, const std::vector<LabeledWeights>& rows,
                       const std::vector<std::string>& names) {
  std::ostringstream o;
  o << "label";
  for (const std::string& n : names) o << ',' << n;
  o << '\n';
  for (const LabeledWeights& r : rows) {
    o << to_string(r.label);
    for (Eigen::Index k = 0; k < r.weights.size(); ++k) o << ',' << r.weights[k];
    o << '\n';
  }
  write_text_file(path, o.str());
}

std::vector<LabeledWeights> read_dataset_csv(const std::filesystem::path& path, const std::vector<std::string>& names) {
  std::ifstream in(path);
  if (!in) throw Error("training data not found: " + path.string());
  std::string line;
  if (!std::getline(in, line)) throw Error("empty training data: " + path.string());
  const std::vector<std::string> header = split_csv_line(line);
  const std::vector<int> cols = columns(header, names, path);
  const std::vector<int> label_col = columns(header, {"label"}, path);
  std::vector<LabeledWeights> out;
  for (int n = 2; std::getline(in, line); ++n) {
    if (line.empty()) continue;
    const std::vector<std::string> cells = split_csv_line(line);
    if (cells.size() != header.size()) throw Error("malformed " + path.string() + " line " + std::to_string(n));
    const auto label = parse_emotion(cells[label_col[0]]);
    if (!label)
      throw Error("malformed " + path.string() + " line " + std::to_string(n) + ": unknown label '" +
                  cells[label_col[0]] + "'");
    LabeledWeights r{*label, Eigen::VectorXf(static_cast<Eigen::Index>(names.size()))};
    for (size_t k = 0; k < names.size(); ++k)
      r.weights[k] = std::clamp(parse_weight(cells[cols[k]], path, n), 0.0f, 1.0f);
    out.push_back(std::move(r));
  }
  return out;
}

}  // namespace facecap
