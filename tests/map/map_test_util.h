// Reading maps from inline text in tests.
#pragma once

#include <doctest/doctest.h>

#include <sstream>
#include <string>

#include "map/map_reader.h"

namespace aerobox::testing {

inline Map ReadText(const std::string& text, const std::string& file) {
  std::istringstream in(text);
  return ReadMap(in, file, DetectMapFormat(file, text));
}

// The message of the InputError that reading `text` throws ("" and a failed check if none).
inline std::string ReadError(const std::string& text, const std::string& file) {
  try {
    ReadText(text, file);
  } catch (const InputError& error) {
    return error.what();
  }
  FAIL_CHECK("no error for: " << text);
  return "";
}

}  // namespace aerobox::testing
