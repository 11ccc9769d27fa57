#include "common/error.h"

#include <utility>

namespace aerobox {
namespace {

std::string Compose(const SourceLocation& where, const std::string& field,
                    const std::string& problem) {
  std::string text;
  if (!where.file.empty()) {
    text += where.file;
    if (where.line > 0) text += ":" + std::to_string(where.line);
    text += ": ";
  }
  if (!field.empty()) text += field + ": ";
  return text + problem;
}

}  // namespace

InputError::InputError(SourceLocation where, std::string field, const std::string& problem)
    : std::runtime_error(Compose(where, field, problem)),
      where_(std::move(where)),
      field_(std::move(field)) {}

}  // namespace aerobox
