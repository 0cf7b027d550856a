#include "facecap/expr/action_units.hpp"

#include <algorithm>
#include <cstdio>

#include "facecap/core/error.hpp"

namespace facecap {

namespace {

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
