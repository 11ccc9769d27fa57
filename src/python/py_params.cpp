#include "python/py_params.h"

#include <cmath>
#include <set>
#include <vector>

#include "common/number_format.h"

namespace py = pybind11;

namespace aerobox {
namespace {

class KwargsReader : public Archive {
 public:
  KwargsReader(const py::dict& kwargs, std::string who) : kwargs_(kwargs), who_(std::move(who)) {}

  void Number(const Field& f, double* value, double low, double high) override {
    if (const py::handle v = Take(f)) *value = InRange(f, ToNumber(f, v), low, high);
  }
  void Integer(const Field& f, long* value, long low, long high) override {
    if (const py::handle v = Take(f)) {
      const double x = ToNumber(f, v);
      if (x != std::floor(x)) Fail(f, FormatNumber(x), "expected a whole number");
      *value =
          static_cast<long>(InRange(f, x, static_cast<double>(low), static_cast<double>(high)));
    }
  }
  void Boolean(const Field& f, bool* value) override {
    if (const py::handle v = Take(f)) {
      if (!py::isinstance<py::bool_>(v)) Fail(f, Repr(v), "expected True or False");
      *value = v.cast<bool>();
    }
  }
  void Vector(const Field& f, Vec3* value, double low, double high) override {
    const py::handle v = Take(f);
    if (!v) return;
    if (py::isinstance<py::float_>(v) || py::isinstance<py::int_>(v)) {
      *value = Vec3::Constant(InRange(f, ToNumber(f, v), low, high));
      return;
    }
    const py::list items = ListOf(f, v, "expected three numbers");
    if (items.size() != 3) Fail(f, Repr(v), "expected three numbers");
    for (int i = 0; i < 3; ++i) (*value)[i] = InRange(f, ToNumber(f, items[i]), low, high);
  }
  void Choice(const Field& f, std::string* value,
              const std::vector<std::string>& choices) override {
    const py::handle v = Take(f);
    if (!v) return;
    const std::string text = py::isinstance<py::str>(v) ? v.cast<std::string>() : "";
    for (const std::string& c : choices) {
      if (c == text) {
        *value = c;
        return;
      }
    }
    Fail(f, Repr(v), "expected " + ListOfNames(Quoted(choices)));
  }
  void Text(const Field& f, std::string* value) override {
    const py::handle v = Take(f);
    if (!v) return;
    if (py::isinstance<py::str>(v)) {
      *value = v.cast<std::string>();
    } else if (py::hasattr(v, "__fspath__")) {  // a pathlib.Path
      *value = py::str(v.attr("__fspath__")());
    } else {
      Fail(f, Repr(v), "expected a str or a path");
    }
  }

  void Points(const Field& f, Vec3* points, int count, double low, double high) override {
    const py::handle v = Take(f);
    if (!v) return;
    const std::string expected = "expected " + std::to_string(count) + " points [x, y, z]";
    const py::list rows = ListOf(f, v, expected);
    if (static_cast<int>(rows.size()) != count) Fail(f, Repr(v), expected);
    for (int i = 0; i < count; ++i) {
      const py::list xyz = ListOf(f, rows[static_cast<size_t>(i)], expected);
      if (xyz.size() != 3) Fail(f, Repr(v), expected);
      for (int k = 0; k < 3; ++k) points[i][k] = InRange(f, ToNumber(f, xyz[k]), low, high);
    }
  }
  void Signs(const Field& f, int* signs, int count) override {
    const py::handle v = Take(f);
    if (!v) return;
    const std::string expected = "expected " + std::to_string(count) + " signs, each 1 or -1";
    const py::list items = ListOf(f, v, expected);
    if (static_cast<int>(items.size()) != count) Fail(f, Repr(v), expected);
    for (int i = 0; i < count; ++i) {
      const double x = ToNumber(f, items[static_cast<size_t>(i)]);
      if (x != 1.0 && x != -1.0) Fail(f, Repr(v), expected);
      signs[i] = static_cast<int>(x);
    }
  }

  // Every argument not taken: a TypeError naming the nearest field.
  void RefuseTheRest() const {
    for (const auto item : kwargs_) {
      const std::string key = py::str(item.first);
      if (taken_.count(key) != 0) continue;
      const std::string near = NearestName(key, names_);
      throw py::type_error(who_ + ": unknown argument '" + key + "'" +
                           (near.empty() ? "" : "; did you mean '" + near + "'?") +
                           " (arguments: " + ListOfNames(names_) + ")");
    }
  }

 private:
  py::handle Take(const Field& f) {
    names_.push_back(f.name);
    if (!kwargs_.contains(f.name)) return py::handle();
    taken_.insert(f.name);
    return kwargs_[f.name];
  }
  py::list ListOf(const Field& f, py::handle v, const std::string& expected) const {
    if (py::isinstance<py::str>(v)) Fail(f, Repr(v), expected);
    try {
      return py::list(py::reinterpret_borrow<py::object>(v));
    } catch (const py::error_already_set&) {
      Fail(f, Repr(v), expected);
    }
  }
  double ToNumber(const Field& f, py::handle v) const {
    if (py::isinstance<py::bool_>(v) ||
        !(py::isinstance<py::float_>(v) || py::isinstance<py::int_>(v) ||
          py::hasattr(v, "__float__"))) {
      Fail(f, Repr(v), "expected a number");
    }
    return py::float_(py::reinterpret_borrow<py::object>(v)).cast<double>();
  }
  double InRange(const Field& f, double x, double low, double high) const {
    if (!(x >= low && x <= high)) {
      Fail(f, FormatNumber(x), "expected " + FormatNumber(low) + " to " + FormatNumber(high));
    }
    return x;
  }
  [[noreturn]] void Fail(const Field& f, const std::string& value, const std::string& why) const {
    const std::string unit = *f.unit != '\0' ? std::string(" ") + f.unit : "";
    throw py::value_error(who_ + ": argument '" + f.name + "' = " + value + unit + ": " + why +
                          " (" + f.meaning + ")");
  }
  static std::string Repr(py::handle v) { return py::repr(v).cast<std::string>(); }
  static std::vector<std::string> Quoted(const std::vector<std::string>& names) {
    std::vector<std::string> quoted;
    for (const std::string& n : names) quoted.push_back("'" + n + "'");
    return quoted;
  }

  py::dict kwargs_;
  std::string who_;
  std::set<std::string> taken_;
  std::vector<std::string> names_;
};

}  // namespace

void ReadKwargs(const py::dict& kwargs, const std::string& who,
                const std::function<void(Archive&)>& describe) {
  KwargsReader reader(kwargs, who);
  describe(reader);
  reader.RefuseTheRest();
}

}  // namespace aerobox
