#pragma once
// `track --action-units`: DIR/action_units.csv, each frame's FACS action
// units (expr/action_units.hpp) in OpenFace's columns, so that scripts
// written for OpenFace's AU output read ours:
//   frame, time, status,
//   AU01_r ... AU45_r   intensity, 0-5
//   AU01_c ... AU45_c   presence, 0 or 1
// A frame without a face has its fields empty. frames.jsonl (and so
// `--stream`) gives a tracked frame's intensities as "action_units".
#include <string>
#include <vector>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "facecap/expr/action_units.hpp"

namespace facecap {

// The unit columns, after frame, time and status: AU01_r ... AU45_r, AU01_c ... AU45_c.
std::vector<std::string> action_unit_columns();

class ActionUnitTable {
 public:
  explicit ActionUnitTable(const std::vector<std::string>& expression_names) : reader_(expression_names) {}

  std::string header() const;
  // Each unit's intensity (0-5) from a frame's weights, for row() and intensities_json().
  Eigen::VectorXd intensities(const Eigen::VectorXf& weights) const { return reader_.intensities(weights); }
  // A frame's row, without its newline; `intensities` null for a frame without a face.
  std::string row(int frame, double time, const std::string& status, const Eigen::VectorXd* intensities) const;
  // The same units as JSON for frames.jsonl: {"AU01": intensity, ...}.
  static nlohmann::json intensities_json(const Eigen::VectorXd& intensities);

 private:
  ActionUnitReader reader_;
};

}  // namespace facecap
