// Errors for bad input: every message names the file, the line and the field at fault.
#pragma once

#include <stdexcept>
#include <string>

namespace aerobox {

// Where in a user's file something was found. `line` is 1-based; 0 means "the whole file".
struct SourceLocation {
  std::string file;
  int line = 0;
};

// Thrown for bad user input (maps, scenarios, command-line values). The CLI maps it to exit 2.
// what() reads "file:line: field: problem" (parts that are unknown are left out).
class InputError : public std::runtime_error {
 public:
  InputError(SourceLocation where, std::string field, const std::string& problem);

  const SourceLocation& where() const { return where_; }
  const std::string& field() const { return field_; }
  const std::string& problem() const { return problem_; }

 private:
  SourceLocation where_;
  std::string field_;
  std::string problem_;
};

}  // namespace aerobox
