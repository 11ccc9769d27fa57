// A minimal indenting XML writer for generated MJCF (internal to src/scene).
#pragma once

#include <initializer_list>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "common/types.h"

namespace aerobox::scene_detail {

using Attributes = std::initializer_list<std::pair<std::string_view, std::string>>;

class XmlWriter {
 public:
  // <name attrs...> and, later, Close() writes </name>.
  void Open(std::string_view name, Attributes attributes = {});
  // <name attrs.../>
  void Leaf(std::string_view name, Attributes attributes = {});
  void Close();
  void Comment(std::string_view text);

  // The document so far; all opened elements must be closed.
  const std::string& Text() const;

 private:
  void Start(std::string_view name, Attributes attributes);

  std::string text_;
  std::vector<std::string> open_;
};

// Number and vector attribute values (shortest round-trip text).
std::string Num(double value);
std::string Vec(const Eigen::Ref<const Eigen::VectorXd>& values);

}  // namespace aerobox::scene_detail
