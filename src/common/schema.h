// One schema for every parameter: a struct describes each of its fields once, by handing them
// to a visitor (an Archive) with the key, a pointer to the value, the unit, the valid range and
// one line of meaning, after Drake's Serialize(Archive*). Readers (a scenario's TOML table,
// `--set KEY=VALUE`, a sweep's grid) and writers (the key reference of `aerobox check --keys`,
// the range check of Validate) are archives, so that the keys, ranges and words of a struct are
// written in its Describe alone.
//
//   void ReplanParams::Describe(Archive& a) {
//     a.Number({"horizon", "s", "ahead of the vehicle, where the new trajectory starts"},
//              &horizon, 0, 5);
//     ...
//   }
#pragma once

#include <memory>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "common/types.h"

namespace aerobox {

// One field as every archive sees it.
struct Field {
  const char* name;     // the key in its table: "horizon"
  const char* unit;     // "s", "m/s", "deg"; "" when it has none
  const char* meaning;  // one line
};

class Archive {
 public:
  virtual ~Archive() = default;

  // A number within [low, high].
  virtual void Number(const Field& field, double* value, double low, double high) = 0;
  // A whole number within [low, high].
  virtual void Integer(const Field& field, long* value, long low, long high) = 0;
  void Integer(const Field& field, int* value, long low, long high);
  virtual void Boolean(const Field& field, bool* value) = 0;
  // Three numbers, each within [low, high] (given as one number: the same on every axis).
  virtual void Vector(const Field& field, Vec3* value, double low, double high) = 0;
  // One of `choices` (their order is the one messages and the reference give).
  virtual void Choice(const Field& field, std::string* value,
                      const std::vector<std::string>& choices) = 0;
  // Any text (a file's path, a name).
  virtual void Text(const Field& field, std::string* value) = 0;
  // `count` points [x, y, z] (a fixed-size array), each coordinate within [low, high].
  virtual void Points(const Field& field, Vec3* points, int count, double low, double high) = 0;
  // `count` signs, each 1 or -1.
  virtual void Signs(const Field& field, int* signs, int count) = 0;

  // An angle kept in radians, given in degrees within [low, high] (the value changes only when
  // the archive sets it, so that a default survives the round trip bit for bit).
  void Degrees(const Field& field, double* radians, double low, double high);
  // An enum named by `names` (value, key word), as a Choice.
  template <typename E>
  void Enum(const Field& field, E* value, const std::vector<std::pair<E, std::string>>& names);
};

namespace schema_detail {
template <typename P, typename = void>
constexpr bool kHasDescribe = false;
template <typename P>
constexpr bool
    kHasDescribe<P, std::void_t<decltype(std::declval<P&>().Describe(std::declval<Archive&>()))>> =
        true;
}  // namespace schema_detail

// A plug-in's own parameters (any copyable struct; its Describe, when it has one, gives its
// keys), carried by value without the seam knowing the type: a registry entry holds the
// defaults, a scenario's table sets its keys through the schema, and the plug-in's factory reads
// them back with Get<P>() or GetOr<P>().
class PluginParameters {
 public:
  PluginParameters() = default;
  template <typename P>
  static PluginParameters Of(P defaults);
  PluginParameters(const PluginParameters& other)
      : holder_(other.holder_ ? other.holder_->Clone() : nullptr) {}
  PluginParameters& operator=(const PluginParameters& other) {
    holder_ = other.holder_ ? other.holder_->Clone() : nullptr;
    return *this;
  }
  PluginParameters(PluginParameters&&) = default;
  PluginParameters& operator=(PluginParameters&&) = default;

  bool empty() const { return holder_ == nullptr; }
  // Hands the fields to `a` (nothing when empty).
  void Describe(Archive& a) {
    if (holder_) holder_->Describe(a);
  }
  // The parameters as their own type; throws std::logic_error when they are another type.
  template <typename P>
  const P& Get() const;
  // The same, or a default-made P when empty.
  template <typename P>
  P GetOr() const {
    return empty() ? P() : Get<P>();
  }

 private:
  struct Base {
    virtual ~Base() = default;
    virtual void Describe(Archive& a) = 0;
    virtual std::unique_ptr<Base> Clone() const = 0;
  };
  template <typename P>
  struct Holder : Base {
    explicit Holder(P v) : value(std::move(v)) {}
    void Describe(Archive& a) override {
      if constexpr (schema_detail::kHasDescribe<P>) value.Describe(a);
    }
    std::unique_ptr<Base> Clone() const override { return std::make_unique<Holder>(value); }
    P value;
  };
  std::unique_ptr<Base> holder_;
};

// The names of the fields `params` describes, in order.
template <typename Params>
std::vector<std::string> FieldNames(Params& params);

// Checks every field of `params` against its range; throws std::invalid_argument reading
// "<table>.<key> out of range: <value>" for the first that is not within it.
template <typename Params>
void ValidateFields(const Params& params, const std::string& table);

// One row of the key reference: a field, its default (the value the struct was made with) and
// its range, as text.
struct KeyRow {
  std::string key;  // "replan.horizon"
  std::string unit;
  std::string value;  // the default: "0.3", "true", "\"omni\""
  std::string range;  // "0 to 5", "true or false", "\"omni\" or \"camera\""
  std::string meaning;
};
// The rows of a default-made `Params` under `table` ("replan", "sensors.imu").
template <typename Params>
std::vector<KeyRow> KeyRows(const std::string& table);
// The rows of `params` as they are (a plug-in's registered defaults).
template <typename Params>
std::vector<KeyRow> KeyRowsOf(Params& params, const std::string& table);

// "a, b or c" (empty for none).
std::string ListOfNames(const std::vector<std::string>& names);
// The name of `names` nearest to `name` when it is near enough to be a misspelling ("" else):
// at most 2 edits, and fewer than half its length.
std::string NearestName(const std::string& name, const std::vector<std::string>& names);

// ---- implementation of the templates ----

namespace schema_detail {
// Throws std::invalid_argument for the first field out of its range.
class RangeCheck : public Archive {
 public:
  explicit RangeCheck(std::string table) : table_(std::move(table)) {}
  using Archive::Integer;
  void Number(const Field& field, double* value, double low, double high) override;
  void Integer(const Field& field, long* value, long low, long high) override;
  void Boolean(const Field&, bool*) override {}
  void Vector(const Field& field, Vec3* value, double low, double high) override;
  void Choice(const Field& field, std::string* value,
              const std::vector<std::string>& choices) override;
  void Text(const Field&, std::string*) override {}
  void Points(const Field& field, Vec3* points, int count, double low, double high) override;
  void Signs(const Field& field, int* signs, int count) override;

 private:
  std::string table_;
};

class Reference : public Archive {
 public:
  explicit Reference(std::string table) : table_(std::move(table)) {}
  using Archive::Integer;
  void Number(const Field& field, double* value, double low, double high) override;
  void Integer(const Field& field, long* value, long low, long high) override;
  void Boolean(const Field& field, bool* value) override;
  void Vector(const Field& field, Vec3* value, double low, double high) override;
  void Choice(const Field& field, std::string* value,
              const std::vector<std::string>& choices) override;
  void Text(const Field& field, std::string* value) override;
  void Points(const Field& field, Vec3* points, int count, double low, double high) override;
  void Signs(const Field& field, int* signs, int count) override;
  std::vector<KeyRow> rows;

 private:
  std::string table_;
};
}  // namespace schema_detail

template <typename E>
void Archive::Enum(const Field& field, E* value,
                   const std::vector<std::pair<E, std::string>>& names) {
  std::string text;
  std::vector<std::string> choices;
  for (const auto& [e, name] : names) {
    choices.push_back(name);
    if (e == *value) text = name;
  }
  Choice(field, &text, choices);
  for (const auto& [e, name] : names) {
    if (name == text) *value = e;
  }
}

template <typename P>
PluginParameters PluginParameters::Of(P defaults) {
  PluginParameters parameters;
  parameters.holder_ = std::make_unique<Holder<P>>(std::move(defaults));
  return parameters;
}

template <typename P>
const P& PluginParameters::Get() const {
  const auto* holder = dynamic_cast<const Holder<P>*>(holder_.get());
  if (holder == nullptr) throw std::logic_error("plug-in parameters of another type");
  return holder->value;
}

template <typename Params>
std::vector<std::string> FieldNames(Params& params) {
  schema_detail::Reference reference("");
  params.Describe(reference);
  std::vector<std::string> names;
  for (const KeyRow& row : reference.rows) names.push_back(row.key.substr(1));
  return names;
}

template <typename Params>
void ValidateFields(const Params& params, const std::string& table) {
  Params copy = params;
  schema_detail::RangeCheck check(table);
  copy.Describe(check);
}

template <typename Params>
std::vector<KeyRow> KeyRowsOf(Params& params, const std::string& table) {
  schema_detail::Reference reference(table);
  params.Describe(reference);
  return reference.rows;
}

template <typename Params>
std::vector<KeyRow> KeyRows(const std::string& table) {
  Params defaults;
  return KeyRowsOf(defaults, table);
}

}  // namespace aerobox
