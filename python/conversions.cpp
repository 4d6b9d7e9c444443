// Python arguments turned into the command line's option texts, so that the command's own checks (parse_set_options,
// read_model_with_roles) judge them and their messages are the command's; and JSON results turned into Python objects.
#include <cmath>

#include "bindings.hpp"

namespace mbgen::python {

std::string option_text(const py::handle& value) {
  if (py::isinstance<py::bool_>(value))  // True would read as 1: no parameter value is a truth value
    usage_error("--set", "a parameter value is a number, not " + py::repr(value).cast<std::string>());
  if (py::isinstance<py::str>(value)) return value.cast<std::string>();
  if (py::isinstance<py::int_>(value)) return py::str(value).cast<std::string>();
  // repr of a float is the shortest text that reads back as the same double ("1.262", "1.3e+06"); an infinity or
  // NaN ("inf", "nan") is then refused by the command's check of decimal numbers.
  if (py::isinstance<py::float_>(value) || py::hasattr(value, "__float__"))
    return py::repr(py::float_(py::reinterpret_borrow<py::object>(value))).cast<std::string>();
  usage_error("--set", "a parameter value is a number, not " + py::repr(value).cast<std::string>());
}

namespace {

std::string bound_text(const py::handle& value) {
  if (value.is_none()) return "inf";  // sign added by the caller
  const double v = py::float_(py::reinterpret_borrow<py::object>(value));
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  return option_text(value);
}

}  // namespace

ModelOptions model_options(const py::object& set, const py::object& fix, const py::object& free,
                           const py::object& bound) {
  ModelOptions out;
  if (!set.is_none()) {
    if (!py::isinstance<py::dict>(set)) usage_error("--set", "set is a dict NAME -> value");
    for (const auto& [name, value] : set.cast<py::dict>())
      out.sets.push_back(py::str(name).cast<std::string>() + "=" + option_text(value));
  }
  if (!fix.is_none()) {
    if (py::isinstance<py::dict>(fix)) {
      for (const auto& [name, value] : fix.cast<py::dict>())
        out.roles.fix.push_back(py::str(name).cast<std::string>() + (value.is_none() ? "" : "=" + option_text(value)));
    } else if (py::isinstance<py::str>(fix)) {
      out.roles.fix.push_back(fix.cast<std::string>());
    } else {
      for (const py::handle& f : fix) out.roles.fix.push_back(py::str(f).cast<std::string>());
    }
  }
  if (!free.is_none()) {
    if (py::isinstance<py::str>(free)) out.roles.free.push_back(free.cast<std::string>());
    else
      for (const py::handle& f : free) out.roles.free.push_back(py::str(f).cast<std::string>());
  }
  if (!bound.is_none()) {
    if (!py::isinstance<py::dict>(bound)) usage_error("--bound", "bound is a dict NAME -> (LO, HI)");
    for (const auto& [name, range] : bound.cast<py::dict>()) {
      const py::sequence lo_hi = py::reinterpret_borrow<py::sequence>(range);
      if (!py::isinstance<py::sequence>(range) || py::len(lo_hi) != 2)
        usage_error("--bound", py::str(name).cast<std::string>() + ": expected (LO, HI)");
      const std::string lo = lo_hi[0].is_none() ? "-inf" : bound_text(lo_hi[0]);
      out.roles.bound.push_back(py::str(name).cast<std::string>() + "=" + lo + ":" + bound_text(lo_hi[1]));
    }
  }
  return out;
}

py::object json_to_python(const std::string& text) { return py::module_::import("json").attr("loads")(text); }

std::string path_text(const py::handle& path) {
  return py::module_::import("os").attr("fspath")(path).cast<std::string>();
}

std::vector<std::string> paths(const py::object& data, const std::string& option) {
  std::vector<std::string> out;
  if (py::isinstance<py::str>(data) || py::hasattr(data, "__fspath__")) out.push_back(path_text(data));
  else
    for (const py::handle& p : data) out.push_back(path_text(p));
  if (out.empty()) usage_error(option, "no data file given");
  return out;
}

}  // namespace mbgen::python
