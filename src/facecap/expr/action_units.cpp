#include "facecap/expr/action_units.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cstdio>
#include <sstream>

#include "facecap/core/error.hpp"

namespace facecap {

namespace {

// The units' numbers, for a message: "1, 2, 4, ..., 45".
std::string describe_numbers() {
  std::string text;
  for (const ActionUnit& unit : action_units()) text += (text.empty() ? "" : ", ") + std::to_string(unit.number);
  return text;
}

// A unit performed by a shape's left and right halves.
ActionUnit both_sides(int number, const char* name, const std::string& shape) {
  return {number, name, {shape + "_L", shape + "_R"}};
}

}  // namespace

std::string ActionUnit::label() const {
  char text[16];
  std::snprintf(text, sizeof text, "AU%02d", number);
  return text;
}

std::string ActionUnit::column(char suffix) const { return label() + '_' + suffix; }

const std::vector<ActionUnit>& action_units() {
  static const std::vector<ActionUnit> units = {
      both_sides(1, "inner brow raiser", "browInnerUp"),
      both_sides(2, "outer brow raiser", "browOuterUp"),
      both_sides(4, "brow lowerer", "browDown"),
      both_sides(5, "upper lid raiser", "eyeWide"),
      both_sides(6, "cheek raiser", "cheekSquint"),
      both_sides(7, "lid tightener", "eyeSquint"),
      both_sides(9, "nose wrinkler", "noseSneer"),
      both_sides(10, "upper lip raiser", "mouthUpperUp"),
      both_sides(12, "lip corner puller", "mouthSmile"),
      both_sides(14, "dimpler", "mouthDimple"),
      both_sides(15, "lip corner depressor", "mouthFrown"),
      {17, "chin raiser", {"mouthShrugLower"}},
      {18, "lip pucker", {"mouthPucker"}},
      both_sides(20, "lip stretcher", "mouthStretch"),
      {22, "lip funneler", {"mouthFunnel"}},
      both_sides(24, "lip pressor", "mouthPress"),
      {26, "jaw drop", {"jawOpen"}},
      {28, "lip suck", {"mouthRollLower", "mouthRollUpper"}},
      both_sides(45, "blink", "eyeBlink"),
  };
  return units;
}

int action_unit_index(int number) {
  const auto& units = action_units();
  const auto it = std::find_if(units.begin(), units.end(), [&](const ActionUnit& u) { return u.number == number; });
  return it == units.end() ? -1 : static_cast<int>(it - units.begin());
}

ActionUnitReader::ActionUnitReader(const std::vector<std::string>& expression_names) {
  for (const ActionUnit& unit : action_units()) {
    std::vector<int>& indices = shape_indices_.emplace_back();
    for (const std::string& shape : unit.shapes) {
      const auto it = std::find(expression_names.begin(), expression_names.end(), shape);
      if (it == expression_names.end())
        throw Error("the face model has no expression shape " + shape + " for " + unit.column('r'));
      indices.push_back(static_cast<int>(it - expression_names.begin()));
    }
  }
}

std::vector<ActionUnitTarget> parse_action_unit_targets(const std::string& text) {
  std::vector<ActionUnitTarget> targets;
  std::stringstream items(text);
  for (std::string item; std::getline(items, item, ',');) {
    std::erase_if(item, [](unsigned char c) { return std::isspace(c); });  // "AU12=3, AU4=0"
    const size_t equals = item.find('=');
    std::string unit = item.substr(0, equals);
    if (unit.size() > 2 && (unit[0] == 'A' || unit[0] == 'a') && (unit[1] == 'U' || unit[1] == 'u')) unit.erase(0, 2);
    int number = 0;
    double intensity = -1;
    const char* end = unit.data() + unit.size();
    const bool number_ok = !unit.empty() && std::from_chars(unit.data(), end, number).ptr == end;
    const std::string value = equals == std::string::npos ? "" : item.substr(equals + 1);
    const bool value_ok = !value.empty() && std::from_chars(value.data(), value.data() + value.size(), intensity).ptr ==
                                                value.data() + value.size();
    if (!number_ok || !value_ok) throw Error("a unit is AU<number>=<intensity 0-5>, as AU12=3, not \"" + item + "\"");
    if (action_unit_index(number) < 0)
      throw Error("the face model has no shape for AU" + std::to_string(number) + " (its units: " + describe_numbers() +
                  ")");
    if (!(intensity >= 0 && intensity <= kActionUnitScale))
      throw Error("AU" + std::to_string(number) + "'s intensity must be between 0 and 5, not " + value);
    if (std::any_of(targets.begin(), targets.end(), [&](const ActionUnitTarget& t) { return t.number == number; }))
      throw Error("AU" + std::to_string(number) + " is given twice");
    targets.push_back({number, intensity});
  }
  if (targets.empty()) throw Error("no unit given: AU<number>=<intensity 0-5>, as AU12=3");
  return targets;
}

std::string describe(const std::vector<ActionUnitTarget>& targets) {
  std::string text;
  for (const ActionUnitTarget& t : targets) {
    char item[32];
    std::snprintf(item, sizeof item, "%sAU%d=%g", text.empty() ? "" : ", ", t.number, t.intensity);
    text += item;
  }
  return text;
}

std::vector<std::pair<int, float>> ActionUnitReader::shape_weights(const std::vector<ActionUnitTarget>& targets) const {
  std::vector<std::pair<int, float>> out;
  for (const ActionUnitTarget& t : targets) {
    const int u = action_unit_index(t.number);
    if (u < 0) throw Error("no action unit AU" + std::to_string(t.number));
    for (int k : shape_indices_[u]) out.emplace_back(k, float(t.intensity / kActionUnitScale));
  }
  return out;
}

Eigen::VectorXd ActionUnitReader::intensities(const Eigen::VectorXf& weights) const {
  Eigen::VectorXd out(size());
  for (int u = 0; u < size(); ++u) {
    double sum = 0;
    for (int k : shape_indices_[u]) sum += weights[k];
    out[u] = kActionUnitScale * sum / static_cast<double>(shape_indices_[u].size());
  }
  return out;
}

}  // namespace facecap
