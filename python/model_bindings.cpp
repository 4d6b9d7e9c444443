// mbgen.load_model and mbgen.Model: a model derived from its .mdl file by the path `mbgen export` and `fit` take
// (parse, roles, derive, the in-process evaluator), and its numbers at its values or at values given in Python; and
// Model.export, the content of `mbgen export` (its own code).
#include <pybind11/complex.h>
#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <mbgen/dynamics/dynamics_error.hpp>
#include <mbgen/dynamics/frf.hpp>
#include <mbgen/dynamics/model_modes.hpp>
#include <mbgen/dynamics/simulate.hpp>
#include <mbgen/dynamics/state_space.hpp>
#include <mbgen/data/time_record.hpp>

#include <cmath>
#include <memory>

#include "bindings.hpp"
#include "cli/command_runs.hpp"
#include "cli/commands.hpp"
#include "evaluator/symbolic_evaluator.hpp"
#include "frontend/diagnostics.hpp"

namespace mbgen::python {

namespace {

const char* role_name(ParameterRole role) {
  return role == ParameterRole::Estimate ? "estimate" : role == ParameterRole::Fixed ? "fixed" : "known";
}

class PyModel {
 public:
  PyModel(std::string path, ModelOptions options) : path_(std::move(path)), options_(std::move(options)) {
    symbolic::DeriveOptions derive;
    derive.set = cli::parse_set_options(options_.sets);
    const ir::ModelIr model = cli::read_model_with_roles(path_, options_.roles, derive.set).model;
    evaluator_ = evaluator::make_evaluator(model, derive);
  }

  const std::string& path() const { return path_; }
  const ModelOptions& options() const { return options_; }
  const ModelInfo& info() const { return evaluator_->info(); }

  py::dict parameters() const {
    py::dict out;
    for (const ParameterInfo& p : info().parameters) {
      py::dict d;
      d["value"] = p.value;
      d["role"] = role_name(p.role);
      d["bounds"] = py::make_tuple(p.lower, p.upper);
      d["unit"] = p.unit;
      out[py::str(p.name)] = d;
    }
    return out;
  }

  // The model's values with those of `params` (a dict NAME -> number) in their place.
  Eigen::VectorXd values(const py::object& params) const {
    Eigen::VectorXd p = info().default_values();
    if (params.is_none()) return p;
    if (!py::isinstance<py::dict>(params)) cli_usage("params is a dict NAME -> value");
    for (const auto& [key, value] : params.cast<py::dict>()) {
      const std::string name = py::str(key);
      const int i = info().parameter_index(name);
      if (i < 0) cli_usage("the model has no parameter `" + name + "`" + names_hint());
      const double v = py::float_(py::reinterpret_borrow<py::object>(value));
      if (!std::isfinite(v)) cli_usage(name + ": the value must be finite, not " + py::repr(value).cast<std::string>());
      p[i] = v;
    }
    return p;
  }

  ModelMatrices matrices_at(const py::object& params) const {
    const Eigen::VectorXd p = values(params);
    ModelMatrices m;
    evaluator_->evaluate(p, m);
    return m;
  }

  // The numeric dynamics failing on the model's values is a problem of this model: named as the command names it.
  template <typename F>
  auto guarded(F f) const {
    try {
      return f();
    } catch (const DynamicsError& e) {
      throw frontend::ModelError(path_, {}, e.what());
    }
  }

  const Model& evaluator() const { return *evaluator_; }

 private:
  [[noreturn]] static void cli_usage(const std::string& message) { usage_error("params", message); }
  std::string names_hint() const {
    std::string out = " (its parameters:";
    for (const ParameterInfo& p : info().parameters) out += " " + p.name;
    return out + ")";
  }

  std::string path_;
  ModelOptions options_;
  std::unique_ptr<Model> evaluator_;
};

py::dict names(const ModelInfo& info) {
  py::dict d;
  d["coordinates"] = info.coordinates;
  d["inputs"] = info.inputs;
  d["outputs"] = info.outputs;
  return d;
}

py::dict matrices(const PyModel& model, const py::object& params) {
  const ModelMatrices m = model.guarded([&] { return model.matrices_at(params); });
  py::dict d = names(model.info());
  d["M"] = m.M, d["C"] = m.C, d["K"] = m.K, d["B"] = m.B, d["Cd"] = m.Cd, d["Cv"] = m.Cv, d["Ca"] = m.Ca;
  return d;
}

py::dict state_space_of(const PyModel& model, const py::object& params) {
  const StateSpace ss = model.guarded([&] { return state_space(model.matrices_at(params)); });
  py::dict d = names(model.info());
  d["A"] = ss.A, d["B"] = ss.B, d["C"] = ss.C, d["D"] = ss.D;
  return d;
}

// lines x outputs x inputs, as the FRF CSV columns OUTPUT/INPUT are laid out per line.
py::array_t<std::complex<double>> frf_of(const PyModel& model, const std::vector<double>& f_hz,
                                         const py::object& params) {
  for (double f : f_hz)
    if (!std::isfinite(f) || f < 0) usage_error("f_hz", "frequencies are finite and >= 0 Hz, not " + std::to_string(f));
  const Eigen::VectorXd p = model.values(params);
  const FrfResult r = model.guarded([&] { return frf(model.evaluator(), p, f_hz); });
  const auto outputs = static_cast<py::ssize_t>(model.info().outputs.size());
  const auto inputs = static_cast<py::ssize_t>(model.info().inputs.size());
  py::array_t<std::complex<double>> out({static_cast<py::ssize_t>(f_hz.size()), outputs, inputs});
  auto h = out.mutable_unchecked<3>();
  for (std::size_t k = 0; k < r.H.size(); ++k)
    for (py::ssize_t o = 0; o < outputs; ++o)
      for (py::ssize_t i = 0; i < inputs; ++i) h(static_cast<py::ssize_t>(k), o, i) = r.H[k](o, i);
  return out;
}

py::dict modes_of(const PyModel& model, const py::object& params) {
  const std::vector<Mode> modes = model.guarded([&] {
    const ModelMatrices m = model.matrices_at(params);
    return modal_analysis(m.M, m.C, m.K);
  });
  const auto n = static_cast<Eigen::Index>(model.info().coordinates.size());
  const auto count = static_cast<Eigen::Index>(modes.size());
  Eigen::VectorXd f(count), zeta(count);
  Eigen::VectorXcd eigenvalues(count);
  Eigen::MatrixXcd shapes(n, count);  // one column per mode, as modal_analysis scales it (largest entry 1)
  for (Eigen::Index k = 0; k < count; ++k) {
    const Mode& mode = modes[static_cast<std::size_t>(k)];
    f[k] = mode.f_hz, zeta[k] = mode.zeta, eigenvalues[k] = mode.eigenvalue;
    shapes.col(k) = mode.shape;
  }
  py::dict d;
  d["f_hz"] = f, d["zeta"] = zeta, d["eigenvalues"] = eigenvalues, d["shapes"] = shapes;
  d["coordinates"] = model.info().coordinates;
  return d;
}

// Outputs (samples x outputs) from rest for inputs u (samples x inputs; a 1-D array for a model of one input) on
// the uniform time grid t, the input held (zero-order) or interpolated (first-order) between samples.
Eigen::MatrixXd simulate_of(const PyModel& model, const Eigen::VectorXd& t, const py::object& u,
                            const py::object& params, const std::string& hold) {
  if (hold != "zero-order" && hold != "first-order") usage_error("hold", "zero-order or first-order, not " + hold);
  const Eigen::Index n = t.size();
  if (n < 2) usage_error("t", "a simulation needs at least 2 samples");
  const double dt = (t[n - 1] - t[0]) / static_cast<double>(n - 1);
  if (!(dt > 0) || !std::isfinite(dt)) usage_error("t", "the times must increase and be finite");
  // The time records' rule (docs/data.md): every sample within a fraction of the interval of the uniform grid.
  for (Eigen::Index k = 0; k < n; ++k)
    if (!(std::abs(t[k] - (t[0] + static_cast<double>(k) * dt)) <= kTimeGridTolerance * dt))
      usage_error("t", "the times must be uniformly spaced (sample " + std::to_string(k) + " is off the grid)");
  const auto inputs = static_cast<Eigen::Index>(model.info().inputs.size());
  const auto array = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(u);
  if (!array) usage_error("u", "the inputs are an array of numbers");
  Eigen::MatrixXd in;
  if (array.ndim() == 1 && inputs == 1) {
    in = Eigen::Map<const Eigen::VectorXd>(array.data(), array.shape(0));
  } else if (array.ndim() == 2) {
    in = Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(
        array.data(), array.shape(0), array.shape(1));
  } else {
    usage_error("u", "the inputs are samples x inputs (" + std::to_string(inputs) + " inputs)");
  }
  if (in.rows() != n || in.cols() != inputs)
    usage_error("u", "expected " + std::to_string(n) + " samples x " + std::to_string(inputs) + " inputs, got " +
                         std::to_string(in.rows()) + " x " + std::to_string(in.cols()));
  if (!in.allFinite()) usage_error("u", "the inputs must be finite");
  const Eigen::VectorXd p = model.values(params);
  return model.guarded([&] {
    return simulate(model.evaluator(), p, in, dt, hold == "first-order" ? InputHold::FirstOrder : InputHold::ZeroOrder);
  });
}


// ---- Model.export: `mbgen export --format json` (cli::export_model) ---------------------------------------------

// A matrix of the export's JSON (a list of rows) as a rows x cols NumPy array (the shape given: a matrix with no rows
// is an empty list in the JSON).
py::object matrix_array(const py::handle& rows, py::ssize_t r, py::ssize_t c) {
  const py::module_ np = py::module_::import("numpy");
  return np.attr("array")(rows, py::arg("dtype") = "float64").attr("reshape")(r, c);
}

// {"re": [...], "im": [...]} as a complex vector.
Eigen::VectorXcd complex_vector(const py::handle& parts) {
  const auto re = parts["re"].cast<std::vector<double>>(), im = parts["im"].cast<std::vector<double>>();
  Eigen::VectorXcd v(static_cast<Eigen::Index>(re.size()));
  for (std::size_t k = 0; k < re.size(); ++k) v[static_cast<Eigen::Index>(k)] = {re[k], im.at(k)};
  return v;
}

// The JSON's content with its numbers as NumPy arrays: each matrix an array; "modes" a dict of f_hz, zeta,
// eigenvalues and shapes (coordinates x modes), as Model.modes(); "frf" a dict of f_hz and H (lines x outputs x
// inputs, complex), as Model.frf().
py::dict export_arrays(py::dict d) {
  const std::string what = d["what"].cast<std::string>();
  const auto ni = static_cast<py::ssize_t>(py::len(d["inputs"])), no = static_cast<py::ssize_t>(py::len(d["outputs"]));
  const auto maps = [&](const char* square, const char* input_map, const std::vector<const char*>& output_maps) {
    const auto n = static_cast<py::ssize_t>(py::len(d[square]));
    d[input_map] = matrix_array(d[input_map], n, ni);
    for (const char* c : output_maps) d[c] = matrix_array(d[c], no, n);
    return n;
  };
  if (what == "matrices") {
    const py::ssize_t n = maps("M", "B", {"Cd", "Cv", "Ca"});
    for (const char* name : {"M", "C", "K"}) d[name] = matrix_array(d[name], n, n);
  } else if (what == "state-space") {
    const py::ssize_t n = maps("A", "B", {"C"});
    d["A"] = matrix_array(d["A"], n, n);
    d["D"] = matrix_array(d["D"], no, ni);
  } else if (what == "modes") {
    const py::list modes = d["modes"];
    const auto count = static_cast<Eigen::Index>(py::len(modes));
    Eigen::VectorXd f(count), zeta(count);
    Eigen::VectorXcd eigenvalues(count);
    Eigen::MatrixXcd shapes(static_cast<Eigen::Index>(py::len(d["coordinates"])), count);
    for (Eigen::Index k = 0; k < count; ++k) {
      const py::handle m = modes[static_cast<std::size_t>(k)];
      f[k] = m["f_hz"].cast<double>(), zeta[k] = m["zeta"].cast<double>();
      eigenvalues[k] = {m["eigenvalue"]["re"].cast<double>(), m["eigenvalue"]["im"].cast<double>()};
      shapes.col(k) = complex_vector(m["shape"]);
    }
    py::dict out;
    out["f_hz"] = f, out["zeta"] = zeta, out["eigenvalues"] = eigenvalues, out["shapes"] = shapes;
    d["modes"] = out;
  } else {
    const py::dict frf = d["frf"];
    const auto f = frf["f_hz"].cast<std::vector<double>>();
    const auto outputs = d["outputs"].cast<std::vector<std::string>>();
    const auto inputs = d["inputs"].cast<std::vector<std::string>>();
    py::array_t<std::complex<double>> h({static_cast<py::ssize_t>(f.size()), no, ni});
    auto view = h.mutable_unchecked<3>();
    for (py::ssize_t o = 0; o < no; ++o)
      for (py::ssize_t i = 0; i < ni; ++i) {
        const Eigen::VectorXcd v = complex_vector(
            frf["channels"][py::str(outputs[static_cast<std::size_t>(o)] + "/" + inputs[static_cast<std::size_t>(i)])]);
        for (py::ssize_t k = 0; k < static_cast<py::ssize_t>(f.size()); ++k) view(k, o, i) = v[k];
      }
    py::dict out;
    out["f_hz"] = Eigen::VectorXd(Eigen::Map<const Eigen::VectorXd>(f.data(), static_cast<Eigen::Index>(f.size())));
    out["H"] = h;
    d["frf"] = out;
  }
  return d;
}

// The grid of --frf: "LO:HI:N" or (LO, HI, N).
std::string grid_text(const py::object& grid) {
  if (py::isinstance<py::str>(grid)) return grid.cast<std::string>();
  const py::sequence s = py::reinterpret_borrow<py::sequence>(grid);
  if (!py::isinstance<py::sequence>(grid) || py::len(s) != 3)
    usage_error("--frf", "the grid is \"LO:HI:N\" or (LO, HI, N)");
  return option_text(s[0]) + ":" + option_text(s[1]) + ":" + py::str(s[2]).cast<std::string>();
}

py::object export_of(const PyModel& model, const std::string& what, const py::object& frf_grid,
                     const py::object& fit_result, bool as_json) {
  if (what != "matrices" && what != "state-space" && what != "modes" && what != "frf")
    usage_error("--what", "`" + what + "` is none of matrices, state-space, modes, frf");
  cli::ExportRequest request;
  request.model_path = model.path();
  request.what = what;
  if (!frf_grid.is_none()) request.grid = grid_text(frf_grid);
  if (py::isinstance<py::dict>(fit_result)) {  // a result of mbgen.fit
    request.fit_result = "fit_result";
    request.fit_result_text = py::module_::import("json").attr("dumps")(fit_result).cast<std::string>();
  } else if (!fit_result.is_none()) {
    request.fit_result = path_text(fit_result);
  }
  // The values the model was loaded with: --set's, and those --fix gave (export takes no roles).
  std::vector<std::string> sets = model.options().sets;
  for (const std::string& f : model.options().roles.fix)
    if (f.find('=') != std::string::npos) sets.push_back(f);
  request.set = cli::parse_set_options(sets);
  const std::string text = released([&] { return model.guarded([&] { return cli::export_model(request).data; }); });
  py::dict d = json_to_python(text);
  return as_json ? d : export_arrays(d);
}

}  // namespace

void register_model(py::module_& m) {
  py::class_<PyModel>(m, "Model", "A model derived from its .mdl file (mbgen.load_model).")
      .def_property_readonly("path", &PyModel::path, "the model file")
      .def_property_readonly("name", [](const PyModel& s) { return s.info().name; })
      .def_property_readonly("parameters", &PyModel::parameters,
                             "dict NAME -> {value, role (known, estimate, fixed), bounds (lo, hi), unit}, in model "
                             "order; derived parameters are not listed")
      .def_property_readonly("coordinates", [](const PyModel& s) { return s.info().coordinates; })
      .def_property_readonly("inputs", [](const PyModel& s) { return s.info().inputs; })
      .def_property_readonly("outputs", [](const PyModel& s) { return s.info().outputs; })
      .def("matrices", &matrices, py::arg("params") = py::none(),
           "dict of M, C, K, B and the output maps Cd, Cv, Ca (y = Cd q + Cv q' + Ca q''), as `mbgen export`")
      .def("state_space", &state_space_of, py::arg("params") = py::none(),
           "dict of A, B, C, D of x = [q; q']")
      .def("frf", &frf_of, py::arg("f_hz"), py::arg("params") = py::none(),
           "complex FRFs at the frequencies f_hz: lines x outputs x inputs")
      .def("modes", &modes_of, py::arg("params") = py::none(),
           "dict of f_hz, zeta, eigenvalues and shapes (coordinates x modes), sorted by frequency")
      .def("simulate", &simulate_of, py::arg("t"), py::arg("u"), py::arg("params") = py::none(),
           py::arg("hold") = "zero-order", "outputs (samples x outputs) from rest for inputs u (samples x inputs)")
      .def("export", &export_of, py::arg("what") = "matrices", py::kw_only(), py::arg("frf") = py::none(),
           py::arg("fit_result") = py::none(), py::arg("json") = false,
           "`mbgen export`'s mbgen-export/1 content at the model's values (or a fit's estimate: fit_result, a path or "
           "the dict mbgen.fit returns): what = matrices, state-space, modes or frf (frf = \"LO:HI:N\" or (LO, HI, "
           "N)); its numbers as NumPy arrays, or as the JSON gives them with json=True")
      .def("__repr__", [](const PyModel& s) { return "<mbgen.Model " + s.info().name + " from " + s.path() + ">"; });

  m.def(
      "load_model",
      [](const py::object& path, const py::object& set, const py::object& fix, const py::object& free,
         const py::object& bound) {
        std::string file = path_text(path);
        ModelOptions options = model_options(set, fix, free, bound);
        return released([&] { return PyModel(std::move(file), std::move(options)); });  // derives: GiNaC
      },
      py::arg("path"), py::arg("set") = py::none(), py::arg("fix") = py::none(), py::arg("free") = py::none(),
      py::arg("bound") = py::none(),
      "Derives the model of a .mdl file. set: dict NAME -> value (--set); fix: dict NAME -> value or None, or list "
      "of names (--fix); free: list of names (--free); bound: dict NAME -> (lo, hi) (--bound).");
}

// The model's file and options, for the commands given a Model (commands_bindings.cpp).
const std::string& model_path(const py::handle& model) { return model.cast<const PyModel&>().path(); }
const ModelOptions& model_options_of(const py::handle& model) { return model.cast<const PyModel&>().options(); }
bool is_model(const py::handle& value) { return py::isinstance<PyModel>(value); }

}  // namespace mbgen::python
