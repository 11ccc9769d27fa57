#include "common/schema.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "common/number_format.h"

namespace aerobox {

void Archive::Integer(const Field& field, int* value, long low, long high) {
  long wide = *value;
  Integer(field, &wide, low, high);
  *value = static_cast<int>(wide);
}

void Archive::Degrees(const Field& field, double* radians, double low, double high) {
  // in degrees, without the conversion's last-digit noise (120 deg, not 119.99999999999999)
  const double exact = *radians * 180.0 / M_PI;
  const double whole = std::round(exact * 1e9) / 1e9;
  const double given =
      std::abs(whole - exact) <= 1e-12 * std::max(1.0, std::abs(exact)) ? whole : exact;
  double degrees = given;
  Number(field, &degrees, low, high);
  if (degrees != given) *radians = degrees * (M_PI / 180.0);
}

std::string ListOfNames(const std::vector<std::string>& names) {
  std::string text;
  for (size_t i = 0; i < names.size(); ++i) {
    text += (i == 0 ? "" : i + 1 == names.size() ? " or " : ", ") + names[i];
  }
  return text;
}

std::string NearestName(const std::string& name, const std::vector<std::string>& names) {
  // Levenshtein distance, one row at a time
  const auto distance = [](const std::string& a, const std::string& b) {
    std::vector<size_t> row(b.size() + 1);
    for (size_t j = 0; j <= b.size(); ++j) row[j] = j;
    for (size_t i = 1; i <= a.size(); ++i) {
      size_t diagonal = row[0];
      row[0] = i;
      for (size_t j = 1; j <= b.size(); ++j) {
        const size_t above = row[j];
        row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] != b[j - 1])});
        diagonal = above;
      }
    }
    return row[b.size()];
  };
  std::string best;
  size_t best_distance = 3;  // at most 2 edits
  for (const std::string& candidate : names) {
    const size_t d = distance(name, candidate);
    if (d < best_distance && 2 * d < name.size()) {
      best = candidate;
      best_distance = d;
    }
  }
  return best;
}

namespace schema_detail {
namespace {

std::string Quoted(const std::string& text) { return "\"" + text + "\""; }

std::vector<std::string> QuotedAll(const std::vector<std::string>& names) {
  std::vector<std::string> quoted;
  for (const std::string& name : names) quoted.push_back(Quoted(name));
  return quoted;
}

}  // namespace

void RangeCheck::Number(const Field& field, double* value, double low, double high) {
  if (!(*value >= low && *value <= high)) {
    throw std::invalid_argument(table_ + "." + field.name +
                                " out of range: " + FormatNumber(*value));
  }
}

void RangeCheck::Integer(const Field& field, long* value, long low, long high) {
  if (!(*value >= low && *value <= high)) {
    throw std::invalid_argument(table_ + "." + field.name +
                                " out of range: " + std::to_string(*value));
  }
}

void RangeCheck::Vector(const Field& field, Vec3* value, double low, double high) {
  for (int i = 0; i < 3; ++i) {
    if (!((*value)[i] >= low && (*value)[i] <= high)) {
      throw std::invalid_argument(table_ + "." + field.name + "[" + std::to_string(i) +
                                  "] out of range: " + FormatNumber((*value)[i]));
    }
  }
}

void RangeCheck::Choice(const Field& field, std::string* value,
                        const std::vector<std::string>& choices) {
  if (std::find(choices.begin(), choices.end(), *value) == choices.end()) {
    throw std::invalid_argument(table_ + "." + field.name + " is not one of " +
                                ListOfNames(choices) + ": '" + *value + "'");
  }
}

void RangeCheck::Points(const Field& field, Vec3* points, int count, double low, double high) {
  for (int i = 0; i < count; ++i) {
    for (int k = 0; k < 3; ++k) {
      if (!(points[i][k] >= low && points[i][k] <= high)) {
        throw std::invalid_argument(table_ + "." + field.name + "[" + std::to_string(i) + "][" +
                                    std::to_string(k) +
                                    "] out of range: " + FormatNumber(points[i][k]));
      }
    }
  }
}

void RangeCheck::Signs(const Field& field, int* signs, int count) {
  for (int i = 0; i < count; ++i) {
    if (signs[i] != 1 && signs[i] != -1) {
      throw std::invalid_argument(table_ + "." + field.name + "[" + std::to_string(i) +
                                  "] is not 1 or -1: " + std::to_string(signs[i]));
    }
  }
}

void Reference::Number(const Field& field, double* value, double low, double high) {
  // an infinite default is a cap not set
  rows.push_back({table_ + "." + field.name, field.unit,
                  std::isfinite(*value) ? FormatNumber(*value) : "none",
                  FormatNumber(low) + " to " + FormatNumber(high), field.meaning});
}

void Reference::Integer(const Field& field, long* value, long low, long high) {
  rows.push_back({table_ + "." + field.name, field.unit, std::to_string(*value),
                  std::to_string(low) + " to " + std::to_string(high), field.meaning});
}

void Reference::Boolean(const Field& field, bool* value) {
  rows.push_back({table_ + "." + field.name, field.unit, *value ? "true" : "false", "true or false",
                  field.meaning});
}

void Reference::Vector(const Field& field, Vec3* value, double low, double high) {
  const Vec3& v = *value;
  rows.push_back(
      {table_ + "." + field.name, field.unit,
       "[" + FormatNumber(v.x()) + ", " + FormatNumber(v.y()) + ", " + FormatNumber(v.z()) + "]",
       "each " + FormatNumber(low) + " to " + FormatNumber(high), field.meaning});
}

void Reference::Choice(const Field& field, std::string* value,
                       const std::vector<std::string>& choices) {
  rows.push_back({table_ + "." + field.name, field.unit, Quoted(*value),
                  ListOfNames(QuotedAll(choices)), field.meaning});
}

void Reference::Text(const Field& field, std::string* value) {
  rows.push_back({table_ + "." + field.name, field.unit, Quoted(*value), "text", field.meaning});
}

void Reference::Points(const Field& field, Vec3* points, int count, double low, double high) {
  std::string text;
  for (int i = 0; i < count; ++i) {
    const Vec3& p = points[i];
    text += std::string(i == 0 ? "" : ", ") + "[" + FormatNumber(p.x()) + ", " +
            FormatNumber(p.y()) + ", " + FormatNumber(p.z()) + "]";
  }
  rows.push_back({table_ + "." + field.name, field.unit, "[" + text + "]",
                  std::to_string(count) + " points, each coordinate " + FormatNumber(low) + " to " +
                      FormatNumber(high),
                  field.meaning});
}

void Reference::Signs(const Field& field, int* signs, int count) {
  std::string text;
  for (int i = 0; i < count; ++i) text += (i == 0 ? "" : ", ") + std::to_string(signs[i]);
  rows.push_back({table_ + "." + field.name, field.unit, "[" + text + "]",
                  std::to_string(count) + " signs, 1 or -1", field.meaning});
}

}  // namespace schema_detail
}  // namespace aerobox
