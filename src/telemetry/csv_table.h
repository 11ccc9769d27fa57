// CSV text with one header row and numeric rows, written so that the same numbers always give
// the same bytes (shortest round-trip number text, '\n' line ends, no locale).
#pragma once

#include <initializer_list>
#include <string>
#include <vector>

#include "common/types.h"

namespace aerobox {

class CsvTable {
 public:
  // Column names; throws std::invalid_argument for an empty list or a name with ',' or '"'.
  explicit CsvTable(std::vector<std::string> columns);

  // One row; throws std::invalid_argument when the count differs from the header's.
  void AddRow(std::initializer_list<double> values);
  void AddRow(const Eigen::Ref<const Eigen::VectorXd>& values);

  size_t rows() const { return rows_; }
  // The whole table, header first.
  const std::string& Text() const { return text_; }

 private:
  size_t columns_;
  size_t rows_ = 0;
  std::string text_;
};

// path.csv: "x,y,z" and one row per waypoint [m].
std::string PathCsv(const std::vector<Vec3>& path);

}  // namespace aerobox
