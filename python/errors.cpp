// The module's exceptions: mbgen.Error (a ValueError: the input is wrong) and one subclass per kind of bad input,
// each carrying the message the command prints for it (run_guarded.hpp), e.g. "FILE:LINE:COLUMN: error: ...".
// Any other C++ exception is a bug in mbgen and reaches Python as RuntimeError, as pybind11 translates it.
#include <CLI/CLI.hpp>
#include <mbgen/data/data_error.hpp>
#include <mbgen/dynamics/dynamics_error.hpp>
#include <mbgen/estimation/fit.hpp>

#include <new>

#include "bindings.hpp"
#include "cli/output_files.hpp"
#include "cli/run_guarded.hpp"
#include "frontend/diagnostics.hpp"

namespace mbgen::python {

namespace {

// The classes live as long as the interpreter: references held without a destructor that would run after it.
PyObject* g_error = nullptr;
PyObject* g_model_error = nullptr;
PyObject* g_data_error = nullptr;
PyObject* g_fit_error = nullptr;
PyObject* g_usage_error = nullptr;

PyObject* add_class(py::module_& m, const char* name, PyObject* base, const char* doc) {
  const std::string qualified = std::string("mbgen.") + name;
  PyObject* cls = PyErr_NewExceptionWithDoc(qualified.c_str(), doc, base, nullptr);
  if (!cls) throw py::error_already_set();
  m.add_object(name, py::handle(cls));  // the module holds a reference; ours is the one PyErr_New... returned
  return cls;
}

}  // namespace

std::mutex& compiler_mutex() {
  static std::mutex m;
  return m;
}

[[noreturn]] void usage_error(const std::string& option, const std::string& message) {
  throw CLI::ValidationError(option, message);
}

void register_errors(py::module_& m) {
  g_error = add_class(m, "Error", PyExc_ValueError, "Bad input to mbgen: a model, data or argument it cannot use.");
  g_model_error = add_class(m, "ModelError", g_error,
                            "A model file mbgen cannot use; the message names FILE:LINE:COLUMN where known.");
  g_data_error = add_class(m, "DataError", g_error,
                           "A data file mbgen cannot use; the message names FILE:LINE:COLUMN where known.");
  g_fit_error = add_class(m, "FitError", g_error, "A method refusing the model or the data (e.g. a method needing "
                                                   "FRFs given a time record).");
  g_usage_error = add_class(m, "UsageError", g_error,
                            "A malformed argument: the message names the command-line option it stands for.");
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const CLI::ParseError& e) {
      PyErr_SetString(g_usage_error, ("mbgen: " + std::string(e.what())).c_str());
    } catch (const frontend::ModelError& e) {
      PyErr_SetString(g_model_error, e.what());
    } catch (const DataError& e) {
      PyErr_SetString(g_data_error, e.what());
    } catch (const FitError& e) {
      PyErr_SetString(g_fit_error, cli::error_message(e.what()).c_str());
    } catch (const DynamicsError& e) {  // of no model file (the model's calls name theirs: model_bindings.cpp)
      PyErr_SetString(g_model_error, cli::error_message(e.what()).c_str());
    } catch (const cli::OutputError& e) {
      PyErr_SetString(g_error, e.what());
    } catch (const std::bad_alloc&) {
      PyErr_SetString(PyExc_MemoryError,
                      "mbgen: error: out of memory: the input is too large for this machine (docs/limits.md)");
    }
  });
}

}  // namespace mbgen::python
