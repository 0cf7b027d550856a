#pragma once
// FACS action units (Ekman and Friesen) read off the fitted ICT expression
// weights, for scripts written for OpenFace's AU columns (AU01_r ... AU45_r,
// AU01_c ... AU45_c).
//
// Each unit is the ICT/ARKit shape (or the left and right halves of one) that
// performs it (the table in FACTS.md, but for AU10, below), and its intensity
// is the shapes' mean weight on FACS's 0-5 scale (OpenFace's): a weight of 1,
// the model's full extent of the movement, is 5 (FACS's E, maximum). A unit
// is present (_c = 1) from intensity 1 (a weight of 0.2), FACS's trace level.
// These are the fit's own weights renamed and scaled, not a regressor trained
// on FACS-coded faces as OpenFace's are, so the two scales need not agree.
//
// Of OpenFace's units, ICT has no lip tightener (AU23) and no shape whose
// weight says that the lips part (AU25: jawOpen parts them unless
// mouthClose holds them, and other shapes move the lip landmarks without
// parting them), so those two are left out rather than guessed. ICT adds
// the lip pucker (AU18), funnel (AU22), presser (AU24) and suck (AU28, whose
// presence OpenFace also reports).
//
// AU10 (upper lip raiser) is mouthUpperUp_L/R, as ARKit describes that shape
// ("upward movement of the upper lip") and as the disgust prototype of
// emotions.hpp uses it; FACTS.md pairs AU10 with mouthShrugUpper, which in
// ICT lifts the whole upper lip's middle instead.
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

namespace facecap {

struct ActionUnit {
  int number = 0;                         // FACS number: 1 for AU1
  std::string name;                       // FACS name: "inner brow raiser"
  std::vector<std::string> shapes;        // ICT shapes whose mean weight it is
  std::string label() const;              // "AU01", as OpenFace numbers them
  std::string column(char suffix) const;  // OpenFace's column: "AU01_r" for 'r'
};

// The units, in FACS order.
const std::vector<ActionUnit>& action_units();
// Where the unit numbered `number` (12 for AU12) is in action_units(); -1 where it is not there.
int action_unit_index(int number);

// Intensity (0-5) from a shape weight, and where a unit counts as present.
inline constexpr double kActionUnitScale = 5.0;
inline constexpr double kActionUnitPresentFrom = 1.0;

// A FACS edit (`transform --units AU12=3,AU4=0`): each named unit set to an
// intensity (0-5).
struct ActionUnitTarget {
  int number = 0;
  double intensity = 0;
};
// "AU12=3,AU4=0" (or "12=3,4=0"); throws facecap::Error naming what is wrong
// (a unit the table lacks, an intensity outside 0-5, a malformed item).
std::vector<ActionUnitTarget> parse_action_unit_targets(const std::string& text);
// "AU12=3, AU4=0", for messages and the synthetic-media marks.
std::string describe(const std::vector<ActionUnitTarget>& targets);

// The units of one model: each unit's shapes found once by name.
class ActionUnitReader {
 public:
  // Throws facecap::Error when the model lacks a unit's shape.
  explicit ActionUnitReader(const std::vector<std::string>& expression_names);

  int size() const { return static_cast<int>(shape_indices_.size()); }
  // Each unit's intensity (0-5), in action_units() order, from the model's weights.
  Eigen::VectorXd intensities(const Eigen::VectorXf& weights) const;
  // The model's shapes (index, weight) that set each target unit to its
  // intensity: every shape of the unit at intensity / 5.
  std::vector<std::pair<int, float>> shape_weights(const std::vector<ActionUnitTarget>& targets) const;

 private:
  std::vector<std::vector<int>> shape_indices_;
};

}  // namespace facecap
