#include "map/json_document.h"

#include <cmath>
#include <limits>

#include "common/number_format.h"

namespace aerobox::map_detail {
namespace {

constexpr int kMaxDepth = 64;

class Parser {
 public:
  Parser(std::string_view text, const std::string& file) : text_(text), file_(file) {}

  JsonValue ParseDocument() {
    JsonValue root = ParseValue(0);
    SkipSpace();
    if (pos_ < text_.size()) Fail("unexpected text after the end of the document");
    return root;
  }

 private:
  [[noreturn]] void Fail(const std::string& problem) const {
    throw InputError({file_, line_}, "", "JSON: " + problem);
  }

  void SkipSpace() {
    while (pos_ < text_.size()) {
      const char c = text_[pos_];
      if (c == '\n') {
        ++line_;
      } else if (c == '\r') {
        // "\r\n" counts once, through its '\n'
        if (pos_ + 1 >= text_.size() || text_[pos_ + 1] != '\n') ++line_;
      } else if (c != ' ' && c != '\t') {
        return;
      }
      ++pos_;
    }
  }

  bool Consume(std::string_view word) {
    if (text_.substr(pos_, word.size()) != word) return false;
    pos_ += word.size();
    return true;
  }

  JsonValue ParseValue(int depth) {
    if (depth > kMaxDepth) Fail("nested deeper than 64 levels");
    SkipSpace();
    if (pos_ >= text_.size()) Fail("unexpected end of file");
    JsonValue value;
    value.line = line_;
    const char c = text_[pos_];
    if (c == '{') {
      ParseObject(depth, &value);
    } else if (c == '[') {
      ParseArray(depth, &value);
    } else if (c == '"') {
      value.kind = JsonValue::Kind::kString;
      value.text = ParseString();
    } else if (Consume("true")) {
      value.kind = JsonValue::Kind::kBool;
      value.boolean = true;
    } else if (Consume("false")) {
      value.kind = JsonValue::Kind::kBool;
    } else if (Consume("null")) {
      value.kind = JsonValue::Kind::kNull;
    } else {
      value.kind = JsonValue::Kind::kNumber;
      value.number = ParseNumberToken();
    }
    return value;
  }

  void ParseObject(int depth, JsonValue* value) {
    value->kind = JsonValue::Kind::kObject;
    ++pos_;  // '{'
    SkipSpace();
    if (Consume("}")) return;
    while (true) {
      SkipSpace();
      if (pos_ >= text_.size() || text_[pos_] != '"') Fail("expected a quoted key");
      std::string key = ParseString();
      if (value->Find(key) != nullptr) Fail("key \"" + key + "\" appears twice");
      SkipSpace();
      if (!Consume(":")) Fail("expected ':' after key \"" + key + "\"");
      value->members.emplace_back(std::move(key), ParseValue(depth + 1));
      SkipSpace();
      if (Consume("}")) return;
      if (!Consume(",")) Fail("expected ',' or '}' in an object");
    }
  }

  void ParseArray(int depth, JsonValue* value) {
    value->kind = JsonValue::Kind::kArray;
    ++pos_;  // '['
    SkipSpace();
    if (Consume("]")) return;
    while (true) {
      value->items.push_back(ParseValue(depth + 1));
      SkipSpace();
      if (Consume("]")) return;
      if (!Consume(",")) Fail("expected ',' or ']' in an array");
    }
  }

  std::string ParseString() {
    ++pos_;  // opening quote
    std::string out;
    while (true) {
      if (pos_ >= text_.size()) Fail("unterminated string");
      const char c = text_[pos_++];
      if (c == '"') return out;
      if (static_cast<unsigned char>(c) < 0x20) Fail("control character inside a string");
      if (c != '\\') {
        out += c;
        continue;
      }
      if (pos_ >= text_.size()) Fail("unterminated string");
      const char e = text_[pos_++];
      switch (e) {
        case '"':
        case '\\':
        case '/':
          out += e;
          break;
        case 'b':
          out += '\b';
          break;
        case 'f':
          out += '\f';
          break;
        case 'n':
          out += '\n';
          break;
        case 'r':
          out += '\r';
          break;
        case 't':
          out += '\t';
          break;
        case 'u':
          AppendUtf8(ParseHex4(), &out);
          break;
        default:
          Fail(std::string("unknown escape '\\") + e + "'");
      }
    }
  }

  unsigned ParseHex4() {
    if (pos_ + 4 > text_.size()) Fail("truncated \\u escape");
    unsigned code = 0;
    for (int i = 0; i < 4; ++i) {
      const char h = text_[pos_++];
      code <<= 4;
      if (h >= '0' && h <= '9')
        code |= static_cast<unsigned>(h - '0');
      else if (h >= 'a' && h <= 'f')
        code |= static_cast<unsigned>(h - 'a' + 10);
      else if (h >= 'A' && h <= 'F')
        code |= static_cast<unsigned>(h - 'A' + 10);
      else
        Fail("bad hex digit in \\u escape");
    }
    return code;
  }

  // Map keys and names are ASCII in practice; other code points are kept as UTF-8 so that a
  // message can quote them. Surrogates are not paired (they come out as two 3-byte sequences).
  static void AppendUtf8(unsigned code, std::string* out) {
    if (code < 0x80) {
      *out += static_cast<char>(code);
    } else if (code < 0x800) {
      *out += static_cast<char>(0xC0 | (code >> 6));
      *out += static_cast<char>(0x80 | (code & 0x3F));
    } else {
      *out += static_cast<char>(0xE0 | (code >> 12));
      *out += static_cast<char>(0x80 | ((code >> 6) & 0x3F));
      *out += static_cast<char>(0x80 | (code & 0x3F));
    }
  }

  double ParseNumberToken() {
    constexpr double kInf = std::numeric_limits<double>::infinity();
    if (Consume("Infinity")) return kInf;
    if (Consume("-Infinity")) return -kInf;
    if (Consume("NaN")) return std::numeric_limits<double>::quiet_NaN();
    const size_t begin = pos_;
    while (pos_ < text_.size() &&
           std::string_view("+-0123456789.eE").find(text_[pos_]) != std::string_view::npos) {
      ++pos_;
    }
    const std::string_view token = text_.substr(begin, pos_ - begin);
    double number = 0.0;
    if (token.empty() || token.front() == '+' || !ParseNumber(token, &number)) {
      const std::string shown(text_.substr(begin, std::min<size_t>(20, text_.size() - begin)));
      Fail("expected a value, found '" + shown + "'");
    }
    return number;
  }

  std::string_view text_;
  const std::string& file_;
  size_t pos_ = 0;
  int line_ = 1;
};

}  // namespace

const JsonValue* JsonValue::Find(std::string_view key) const {
  for (const auto& [name, member] : members) {
    if (name == key) return &member;
  }
  return nullptr;
}

JsonValue ParseJson(std::string_view text, const std::string& file) {
  return Parser(text, file).ParseDocument();
}

const char* KindName(JsonValue::Kind kind) {
  switch (kind) {
    case JsonValue::Kind::kNull:
      return "null";
    case JsonValue::Kind::kBool:
      return "a boolean";
    case JsonValue::Kind::kNumber:
      return "a number";
    case JsonValue::Kind::kString:
      return "a string";
    case JsonValue::Kind::kArray:
      return "an array";
    case JsonValue::Kind::kObject:
      return "an object";
  }
  return "a value";
}

}  // namespace aerobox::map_detail
