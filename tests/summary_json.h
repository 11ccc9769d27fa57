// summary.json read back with a JSON parser (nlohmann-json), for the tests that check a run.
#pragma once

#include <doctest/doctest.h>

#include <filesystem>
#include <nlohmann/json.hpp>

#include "test_support.h"

namespace aerobox::testing {

// The parsed file; a test failure (and an empty object) when it is missing or not JSON.
inline nlohmann::json ReadSummary(const std::filesystem::path& path) {
  const std::string text = ReadFile(path);
  REQUIRE_MESSAGE(!text.empty(), path.string() << " is missing or empty");
  nlohmann::json json = nlohmann::json::parse(text, nullptr, false);
  REQUIRE_MESSAGE(!json.is_discarded(), path.string() << " is not valid JSON");
  return json;
}

// A number of the summary; null (a non-finite value) reads as +infinity.
inline double SummaryNumber(const nlohmann::json& summary, const std::string& key) {
  REQUIRE_MESSAGE(summary.contains(key), key);
  if (summary[key].is_null()) return std::numeric_limits<double>::infinity();
  REQUIRE_MESSAGE(summary[key].is_number(), key);
  return summary[key].get<double>();
}

}  // namespace aerobox::testing
