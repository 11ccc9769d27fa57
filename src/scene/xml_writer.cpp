#include "scene/xml_writer.h"

#include <cassert>

#include "common/number_format.h"
#include "common/quoting.h"

namespace aerobox::scene_detail {

void XmlWriter::Start(std::string_view name, Attributes attributes) {
  text_.append(2 * open_.size(), ' ');
  text_ += '<';
  text_ += name;
  for (const auto& [key, value] : attributes) {
    text_ += ' ';
    text_ += key;
    text_ += "=\"";
    text_ += XmlEscaped(value);
    text_ += '"';
  }
}

void XmlWriter::Open(std::string_view name, Attributes attributes) {
  Start(name, attributes);
  text_ += ">\n";
  open_.emplace_back(name);
}

void XmlWriter::Leaf(std::string_view name, Attributes attributes) {
  Start(name, attributes);
  text_ += "/>\n";
}

void XmlWriter::Close() {
  assert(!open_.empty());
  const std::string name = open_.back();
  open_.pop_back();
  text_.append(2 * open_.size(), ' ');
  text_ += "</" + name + ">\n";
}

void XmlWriter::Comment(std::string_view text) {
  text_.append(2 * open_.size(), ' ');
  // "--" may not appear inside an XML comment
  std::string safe(text);
  for (size_t at = safe.find("--"); at != std::string::npos; at = safe.find("--", at)) {
    safe.replace(at, 2, "- -");
  }
  text_ += "<!-- " + safe + " -->\n";
}

const std::string& XmlWriter::Text() const {
  assert(open_.empty());
  return text_;
}

std::string Num(double value) { return FormatNumber(value); }
std::string Vec(const Eigen::Ref<const Eigen::VectorXd>& values) { return FormatVector(values); }

}  // namespace aerobox::scene_detail
