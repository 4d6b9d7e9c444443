// The Python module `mbgen` (docs/python.md): models derived from .mdl files through the compiler library, their
// matrices, state space, FRFs, modes, simulations and export as NumPy arrays, the data readers, and fit, diagnose,
// modal, sensitivity and monitor with the results the command writes as JSON.
#include "bindings.hpp"
#include "emit/cpp_emitter.hpp"

PYBIND11_MODULE(mbgen, m) {
  m.doc() = "mbgen: lumped-parameter mechanical models from .mdl files: matrices, FRFs, modes, simulation, "
            "export, parameter estimation, model diagnosis, experimental modal analysis, sensitivity and monitoring "
            "(docs/python.md)";
  m.attr("__version__") = mbgen::emit::mbgen_version();
  mbgen::python::register_errors(m);
  mbgen::python::register_model(m);
  mbgen::python::register_data(m);
  mbgen::python::register_commands(m);
}
