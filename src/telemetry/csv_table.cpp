#include "telemetry/csv_table.h"

#include <stdexcept>

#include "common/number_format.h"

namespace aerobox {

CsvTable::CsvTable(std::vector<std::string> columns) : columns_(columns.size()) {
  if (columns.empty()) throw std::invalid_argument("CsvTable: no columns");
  for (size_t i = 0; i < columns.size(); ++i) {
    if (columns[i].find_first_of(",\"\n") != std::string::npos) {
      throw std::invalid_argument("CsvTable: bad column name '" + columns[i] + "'");
    }
    text_ += (i > 0 ? "," : "") + columns[i];
  }
  text_ += '\n';
}

void CsvTable::AddRow(std::initializer_list<double> values) {
  AddRow(
      Eigen::Map<const Eigen::VectorXd>(values.begin(), static_cast<Eigen::Index>(values.size())));
}

void CsvTable::AddRow(const Eigen::Ref<const Eigen::VectorXd>& values) {
  if (static_cast<size_t>(values.size()) != columns_) {
    throw std::invalid_argument("CsvTable: row of " + std::to_string(values.size()) +
                                " values for " + std::to_string(columns_) + " columns");
  }
  AppendVector(values, ",", &text_);
  text_ += '\n';
  ++rows_;
}

std::string PathCsv(const std::vector<Vec3>& path) {
  CsvTable table({"x", "y", "z"});
  for (const Vec3& p : path) table.AddRow(p);
  return table.Text();
}

}  // namespace aerobox
