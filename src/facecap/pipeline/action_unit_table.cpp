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
                                 const Eigen::VectorXd* intensities) const {
  std::string row = std::to_string(frame) + ',' + csv_number(time) + ',' + status;
  if (intensities == nullptr) return row + std::string(2 * reader_.size(), ',');
  for (double v : *intensities) row += ',' + csv_number(v);
  for (double v : *intensities) row += v >= kActionUnitPresentFrom ? ",1" : ",0";
  return row;
}

nlohmann::json ActionUnitTable::intensities_json(const Eigen::VectorXd& intensities) {
  nlohmann::json units = nlohmann::json::object();
  for (Eigen::Index u = 0; u < intensities.size(); ++u) units[action_units()[u].label()] = intensities[u];
  return units;
}

}  // namespace facecap
