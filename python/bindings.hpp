// What the files of the Python module share: each registers its part of the module, and the conversions between
// Python values and the command line's option texts live in conversions.cpp.
#pragma once

#include <pybind11/pybind11.h>

#include <map>
#include <mutex>
#include <string>
#include <vector>

#include "cli/parameter_roles.hpp"

namespace mbgen::python {

namespace py = pybind11;

void register_errors(py::module_& m);    // errors.cpp: the exception classes and the translation of C++ errors
void register_model(py::module_& m);     // model_bindings.cpp: load_model and Model
void register_data(py::module_& m);      // data_bindings.cpp: read_data
void register_commands(py::module_& m);  // commands_bindings.cpp: fit, diagnose, modal, sensitivity, monitor

// Runs `f` (which touches no Python object) with the interpreter lock released, so that other Python threads run
// meanwhile, and one call at a time: the derivation and the diagnosis use GiNaC, which is not thread-safe (the
// library keeps it on one thread, diagnose.cpp). The lock is let go before the interpreter's is taken back.
std::mutex& compiler_mutex();
template <typename F>
auto released(F f) {
  py::gil_scoped_release release;
  std::lock_guard<std::mutex> lock(compiler_mutex());
  return f();
}

// A usage error (a malformed argument): raised as mbgen.UsageError with the text the command prints for it.
[[noreturn]] void usage_error(const std::string& option, const std::string& message);

// The options of a model as the command line gives them: `set` a dict NAME -> value ("--set NAME=VALUE"), `fix` a
// dict NAME -> value or None, or a list of NAME / "NAME=VALUE" ("--fix"), `free` a list of names ("--free"),
// `bound` a dict NAME -> (LO, HI) ("--bound NAME=LO:HI", None or an infinity for no bound). None for none.
struct ModelOptions {
  std::vector<std::string> sets;  // NAME=VALUE, checked later by parse_set_options as --set's are
  cli::RoleOptions roles;
};
ModelOptions model_options(const py::object& set, const py::object& fix, const py::object& free,
                           const py::object& bound);

// A number as option text: Python's shortest round-trip repr for a float, digits for an int, a string as given.
std::string option_text(const py::handle& value);

// A JSON document (the command's --json output) as Python objects, by the json module.
py::object json_to_python(const std::string& text);

// The paths of `data`: one path (str or os.PathLike) or a list of them.
std::vector<std::string> paths(const py::object& data, const std::string& option);
std::string path_text(const py::handle& path);

}  // namespace mbgen::python

namespace mbgen::python {
// A mbgen.Model's file and the options it was loaded with (model_bindings.cpp).
bool is_model(const py::handle& value);
const std::string& model_path(const py::handle& model);
const ModelOptions& model_options_of(const py::handle& model);
}  // namespace mbgen::python
