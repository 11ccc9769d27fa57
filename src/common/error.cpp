#include "common/error.h"

#include <utility>

namespace aerobox {
namespace {

// The length of the well-formed UTF-8 sequence starting at text[i] (1 for ASCII), or 0.
size_t Utf8Length(const std::string& text, size_t i) {
  const auto byte = static_cast<unsigned char>(text[i]);
  const size_t length = byte < 0x80         ? 1
                        : (byte >> 5) == 6  ? 2
                        : (byte >> 4) == 14 ? 3
                        : (byte >> 3) == 30 ? 4
                                            : 0;
  if (length == 0 || i + length > text.size()) return 0;
  for (size_t k = 1; k < length; ++k) {
    if ((static_cast<unsigned char>(text[i + k]) >> 6) != 2) return 0;
  }
  return length;
}

// Control characters and bytes that are not UTF-8 (binary junk in a file) written as \xNN,
// so that a message cannot garble the terminal.
std::string Printable(const std::string& text) {
  std::string shown;
  for (size_t i = 0; i < text.size();) {
    const auto byte = static_cast<unsigned char>(text[i]);
    const size_t length = Utf8Length(text, i);
    if (length == 0 || byte < 0x20 || byte == 0x7f) {
      static const char kHex[] = "0123456789abcdef";
      shown += "\\x";
      shown += kHex[byte >> 4];
      shown += kHex[byte & 15];
      ++i;
    } else {
      shown.append(text, i, length);
      i += length;
    }
  }
  return shown;
}

std::string Compose(const SourceLocation& where, const std::string& field,
                    const std::string& problem) {
  std::string text;
  if (!where.file.empty()) {
    text += where.file;
    if (where.line > 0) text += ":" + std::to_string(where.line);
    text += ": ";
  }
  if (!field.empty()) text += Printable(field) + ": ";
  return text + Printable(problem);
}

}  // namespace

InputError::InputError(SourceLocation where, std::string field, const std::string& problem)
    : std::runtime_error(Compose(where, field, problem)),
      where_(std::move(where)),
      field_(std::move(field)),
      problem_(problem) {}

}  // namespace aerobox
