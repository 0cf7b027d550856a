#include "facecap/pipeline/action_unit_table.hpp"

#include "facecap/core/csv_line.hpp"

namespace facecap {

std::vector<std::string> action_unit_columns() {
  std::vector<std::string> columns;
  for (char suffix : {'r', 'c'})
    for (const ActionUnit& unit : action_units()) columns.push_back(unit.column(suffix));
  return columns;
}

std::string ActionUnitTable::header() const {
  std::string h = "frame,time,status";
  for (const std::string& column : action_unit_columns()) h += ',' + column;
  return h;
}

std::string ActionUnitTable::row(int frame, double time, const std::string& status,
                                 const Eigen::VectorXf* weights) const {
  std::string row = std::to_string(frame) + ',' + csv_number(time) + ',' + status;
  if (weights == nullptr) return row + std::string(2 * reader_.size(), ',');
  const Eigen::VectorXd intensity = reader_.intensities(*weights);
  for (double v : intensity) row += ',' + csv_number(v);
  for (double v : intensity) row += v >= kActionUnitPresentFrom ? ",1" : ",0";
  return row;
}

nlohmann::json ActionUnitTable::intensities_json(const Eigen::VectorXf& weights) const {
  const Eigen::VectorXd intensity = reader_.intensities(weights);
  nlohmann::json units = nlohmann::json::object();
  for (Eigen::Index u = 0; u < intensity.size(); ++u) units[action_units()[u].label()] = intensity[u];
  return units;
}

}  // namespace facecap
