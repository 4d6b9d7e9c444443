#include "emit/cpp_emitter.hpp"

#include <cmath>
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <map>
#include <optional>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "emit/cxx_printer.hpp"
#include "emit/cxx_text.hpp"
#include "emit/infix_printer.hpp"
#include "emit/template_engine.hpp"
#include "frontend/diagnostics.hpp"
#include "ir/identifier.hpp"
#include "symbolic/to_ginac.hpp"

#ifndef MBGEN_VERSION
#error "MBGEN_VERSION must be defined by the build"
#endif

#include "emit/ginac_text.hpp"

namespace mbgen::emit {
namespace {

using symbolic::SymbolicModel;

std::string base_name(const std::string& path) {
  const auto slash = path.find_last_of("/\\");
  return slash == std::string::npos ? path : path.substr(slash + 1);
}

std::string join(const std::vector<std::string>& items, const std::string& sep = ", ") {
  std::string out;
  for (std::size_t i = 0; i < items.size(); ++i) out += (i ? sep : "") + items[i];
  return out;
}

// A double literal that reads back to exactly x (17 significant digits), infinities spelled out.
std::string double_literal(double x) {
  if (std::isinf(x)) return x > 0 ? "std::numeric_limits<double>::infinity()" : "-std::numeric_limits<double>::infinity()";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.17g", x);
  std::string s = buf;
  if (s.find_first_of(".en") == std::string::npos) s += ".0";
  return s;
}

double to_double(const GiNaC::ex& e) {
  const GiNaC::ex v = GiNaC::evalf(e);
  if (!GiNaC::is_a<GiNaC::numeric>(v) || !GiNaC::ex_to<GiNaC::numeric>(v).is_real())
    throw std::invalid_argument("emit_cpp: value is not a real number: " + ginac_text(e));
  return GiNaC::ex_to<GiNaC::numeric>(v).to_double();
}

const char* role_text(ir::Role r) {
  switch (r) {
    case ir::Role::Known: return "mbgen::ParameterRole::Known";
    case ir::Role::Estimate: return "mbgen::ParameterRole::Estimate";
    case ir::Role::Fixed: return "mbgen::ParameterRole::Fixed";
  }
  return "mbgen::ParameterRole::Known";
}

// The statements every emitted function starts with: using-declarations for ADL and the parameters it reads.
class FunctionContext {
 public:
  explicit FunctionContext(const SymbolicModel& sm) : sm_(sm) {
    for (std::size_t i = 0; i < sm.parameters.size(); ++i) {
      names_.emplace(sm.parameters[i].sym, ir::cxx_parameter_variable(sm.parameters[i].name));
      index_.emplace(sm.parameters[i].sym, i);
    }
  }
  const SymbolNames& names() const { return names_; }

  // Indices of the parameters an expression contains, ascending: one walk over the expression, not one has() per
  // parameter (a 600-coordinate chain has 300 parameters and 11 000 non-zero entries per matrix).
  std::vector<std::size_t> parameters_in(const GiNaC::ex& e) const {
    std::vector<std::size_t> found;
    for (GiNaC::const_preorder_iterator it = e.preorder_begin(); it != e.preorder_end(); ++it)
      if (GiNaC::is_a<GiNaC::symbol>(*it))
        if (auto k = index_.find(*it); k != index_.end()) found.push_back(k->second);
    std::sort(found.begin(), found.end());
    found.erase(std::unique(found.begin(), found.end()), found.end());
    return found;
  }

  std::string prologue(const std::vector<GiNaC::ex>& used_by) const {
    std::string out =
        "  using std::abs; using std::atan; using std::cos; using std::exp; using std::log; using std::pow;\n"
        "  using std::sin; using std::sqrt; using std::tan;\n";
    bool any = false;
    std::vector<char> is_used(sm_.parameters.size(), 0);
    for (const auto& e : used_by)
      for (std::size_t k : parameters_in(e)) is_used[k] = 1;
    for (std::size_t i = 0; i < sm_.parameters.size(); ++i) {
      const auto& sym = sm_.parameters[i].sym;
      if (!is_used[i]) continue;
      any = true;
      out += "  const Scalar& " + names_.at(sym) + " = p[" + std::to_string(i) + "];\n";
    }
    if (!any) out += "  static_cast<void>(p);\n";
    return out;
  }

 private:
  const SymbolicModel& sm_;
  SymbolNames names_;
  std::map<GiNaC::ex, std::size_t, GiNaC::ex_is_less> index_;
};

struct MatrixSpec {
  const char* function;
  const char* symbol;
  const char* type;
  const char* description;
  const GiNaC::matrix* matrix;
  bool in_model;     // part of mbgen::ModelMatrices
  const char* dims;  // its size in the generated constants, for dynamic-size matrices
};

// A piece of an emitted function (a function of bounded size), defined in the main source or in a part file.
struct Chunk {
  std::string name, params, param_types, body;
  std::size_t operations = 0;  // after CSE: how the pieces are spread over the parts
};

// What every emitted function body shares: the parameters' names, the size bound, the pieces made so far and
// the operation counts of the banner.
struct BodyEmitter {
  const FunctionContext& ctx;
  std::size_t max_operations;  // per function before CSE; 0: no bound
  bool always_chunk;           // several parts: every function's work goes to pieces the parts can hold
  std::vector<Chunk> chunks;
  OperationCounts counts;
  OperationCounter counter;

  // Consecutive runs of assignments of at most max_operations each: an assignment costs its operations before CSE
  // plus one (the store: a run of many constant entries is long too). A single larger assignment is a run of its
  // own.
  std::vector<std::vector<CxxAssignment>> groups(const std::vector<CxxAssignment>& values) {
    std::vector<std::vector<CxxAssignment>> out(1);
    std::size_t ops = 0;
    for (const auto& a : values) {
      const std::size_t n = 1 + counter.count(a.rhs);
      if (max_operations > 0 && !out.back().empty() && ops + n > max_operations) {
        out.emplace_back();
        ops = 0;
      }
      out.back().push_back(a);
      ops += n;
    }
    return out;
  }

  // The body of `function`: `prelude`, then the assignments. When they exceed the bound (or parts are wanted),
  // they go to pieces `detail::FUNCTION_chunk_K(args)`, each with its own CSE, and the body calls them in order.
  // Rows in order keep the pieces local: a chain's body i fills rows of its own, so little sharing is lost.
  std::string body(const std::string& function, const std::string& params, const std::string& param_types,
                   const std::string& args, const std::string& prelude, const std::vector<CxxAssignment>& values,
                   const std::string& if_empty) {
    std::vector<GiNaC::ex> used;
    for (const auto& a : values) used.push_back(a.rhs);
    const auto runs = groups(values);
    if (values.empty() || (runs.size() == 1 && !always_chunk))
      return ctx.prologue(used) + prelude + (values.empty() ? if_empty : "") +
             cxx_assignments(values, ctx.names(), "  ", &counts);
    std::string out = prelude;
    for (std::size_t k = 0; k < runs.size(); ++k) {
      std::vector<GiNaC::ex> run_used;
      for (const auto& a : runs[k]) run_used.push_back(a.rhs);
      OperationCounts run_counts;
      Chunk c;
      c.name = function + "_chunk_" + std::to_string(k);
      c.params = params;
      c.param_types = param_types;
      c.body = ctx.prologue(run_used) + cxx_assignments(runs[k], ctx.names(), "  ", &run_counts);
      c.operations = run_counts.after_cse;
      counts.before_cse += run_counts.before_cse;
      counts.after_cse += run_counts.after_cse;
      out += "  detail::" + c.name + "(" + args + ");\n";
      chunks.push_back(std::move(c));
    }
    return out;
  }
};

TemplateDict matrix_dict(const SymbolicModel& sm, const FunctionContext& ctx, const MatrixSpec& spec,
                         BodyEmitter& emitter, bool dynamic_size) {
  const GiNaC::matrix& m = *spec.matrix;
  std::vector<CxxAssignment> values;
  for (unsigned r = 0; r < m.rows(); ++r)
    for (unsigned c = 0; c < m.cols(); ++c)
      if (!m(r, c).is_zero())
        values.push_back({std::string(spec.symbol) + "(" + std::to_string(r) + ", " + std::to_string(c) + ")", m(r, c)});
  const std::string matrix_type = std::string(spec.type) + "<Scalar>&";
  const std::string set_zero =
      "  " + std::string(spec.symbol) + ".setZero(" + (dynamic_size ? spec.dims : "") + ");\n";
  std::string body = emitter.body(spec.function, "const Scalar* p, " + matrix_type + " " + spec.symbol,
                                  "const Scalar*, " + matrix_type, std::string("p, ") + spec.symbol, set_zero, values,
                                  "");

  std::vector<std::string> pattern;
  std::vector<CxxAssignment> derivatives;
  // Parameter-major, then row and column, as before; each parameter visits only the entries that contain it.
  std::vector<std::vector<std::pair<unsigned, unsigned>>> entries_with(sm.parameters.size());
  for (unsigned r = 0; r < m.rows(); ++r)
    for (unsigned c = 0; c < m.cols(); ++c)
      if (!m(r, c).is_zero())
        for (std::size_t j : ctx.parameters_in(m(r, c))) entries_with[j].emplace_back(r, c);
  for (std::size_t j = 0; j < sm.parameters.size(); ++j)
    for (const auto& [r, c] : entries_with[j]) {
      const GiNaC::ex d = m(r, c).diff(sm.parameters[j].sym);
      if (d.is_zero()) continue;
      derivatives.push_back({"values[" + std::to_string(pattern.size()) + "]", d});
      pattern.push_back("JacobianEntry{" + std::to_string(j) + ", " + std::to_string(r) + ", " + std::to_string(c) + "}");
    }
  std::string jacobian_body =
      emitter.body(std::string(spec.function) + "_jacobian", "const Scalar* p, Scalar* values", "const Scalar*, Scalar*",
                   "p, values", "", derivatives, "  static_cast<void>(values);\n");

  TemplateList in_model;
  if (spec.in_model) in_model.emplace_back();
  return {{"function", spec.function},
          {"symbol", spec.symbol},
          {"type", spec.type},
          {"description", spec.description},
          {"body", body},
          {"jacobian_body", jacobian_body},
          {"jacobian_size", std::to_string(pattern.size())},
          {"jacobian_pattern", join(pattern)},
          {"in_model", in_model}};
}

// Emitted expressions for a transfer function whose coefficients are exact expressions (or exactly zero).
void symbolic_tf_bodies(const SymbolicModel& sm, const FunctionContext& ctx, const symbolic::TransferFunction& tf,
                        std::string& body, std::string& jacobian_body, OperationCounts& counts) {
  std::vector<CxxAssignment> values;
  std::vector<GiNaC::ex> all;
  for (std::size_t k = 0; k < tf.numerator.size(); ++k) {
    values.push_back({"numerator[" + std::to_string(k) + "]", tf.numerator[k]});
    all.push_back(tf.numerator[k]);
  }
  for (std::size_t k = 0; k < tf.denominator.size(); ++k) {
    values.push_back({"denominator[" + std::to_string(k) + "]", tf.denominator[k]});
    all.push_back(tf.denominator[k]);
  }
  body = ctx.prologue(all) + "  numerator.resize(" + std::to_string(tf.numerator.size()) + ");\n" +
         "  denominator.resize(" + std::to_string(tf.denominator.size()) + ");\n" +
         cxx_assignments(values, ctx.names(), "  ", &counts);

  const std::size_t nn = tf.numerator.size(), nd = tf.denominator.size(), np = sm.parameters.size();
  std::vector<CxxAssignment> derivatives;
  std::vector<GiNaC::ex> used;
  auto add = [&](const std::vector<GiNaC::ex>& coeffs, const std::string& target, std::size_t size) {
    for (std::size_t j = 0; j < np; ++j)
      for (std::size_t k = 0; k < coeffs.size(); ++k) {
        const GiNaC::ex d = coeffs[k].diff(sm.parameters[j].sym);
        if (d.is_zero()) continue;
        derivatives.push_back({target + "[" + std::to_string(j * size + k) + "]", d});
        used.push_back(d);
      }
  };
  add(tf.numerator, "d_numerator", nn);
  add(tf.denominator, "d_denominator", nd);
  jacobian_body = ctx.prologue(used) + "  d_numerator.assign(" + std::to_string(np * nn) + ", Scalar(0));\n" +
                  "  d_denominator.assign(" + std::to_string(np * nd) + ", Scalar(0));\n" +
                  cxx_assignments(derivatives, ctx.names(), "  ", &counts);
}

TemplateList transfer_function_dicts(const SymbolicModel& sm, const FunctionContext& ctx,
                                     const std::vector<std::string>& inputs, const std::vector<std::string>& outputs,
                                     OperationCounts& counts) {
  TemplateList list;
  for (std::size_t i = 0; i < sm.transfer_functions.size(); ++i) {
    const auto& tf = sm.transfer_functions[i];
    std::vector<std::string> coords;
    for (int c : tf.coordinates) coords.push_back(std::to_string(c));
    const bool emitted = tf.symbolic || tf.coordinates.empty();
    std::string body, jacobian_body, comment;
    std::size_t nn = tf.numerator.size(), nd = tf.denominator.size();
    if (emitted) {
      symbolic_tf_bodies(sm, ctx, tf, body, jacobian_body, counts);
      comment = ": exact expressions";
    } else {
      const TemplateDict d = {{"output", std::to_string(tf.output)}, {"input", std::to_string(tf.input)},
                              {"coordinates", join(coords)}};
      body = render_embedded("cpp/tf_runtime.tmpl", d);
      jacobian_body = render_embedded("cpp/tf_runtime_jacobian.tmpl", d);
      nn = nd = 2 * tf.coordinates.size() + 1;
      comment = ": computed at run time on coordinates " + join(coords);
    }
    list.push_back({{"index", std::to_string(i)},
                    {"output", std::to_string(tf.output)},
                    {"input", std::to_string(tf.input)},
                    {"output_name", outputs.at(static_cast<std::size_t>(tf.output))},
                    {"input_name", inputs.at(static_cast<std::size_t>(tf.input))},
                    {"symbolic", emitted ? "true" : "false"},
                    {"numerator_size", std::to_string(nn)},
                    {"denominator_size", std::to_string(nd)},
                    {"comment", comment},
                    {"body", body},
                    {"jacobian_body", jacobian_body}});
  }
  return list;
}

// Bounds of the free parameters as doubles (infinite when absent or when the model is not at hand). One parameter
// table and one map of values for all (one per parameter made the emitter cubic in the number of parameters).
std::vector<std::pair<double, double>> bounds_of(const SymbolicModel& sm) {
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<std::pair<double, double>> bounds(sm.parameters.size(), {-inf, inf});
  if (!sm.model) return bounds;
  std::optional<symbolic::ParameterTable> table;
  GiNaC::exmap table_values, values;
  for (std::size_t i = 0; i < sm.parameters.size(); ++i) {
    const symbolic::FreeParameter& p = sm.parameters[i];
    if (!p.ir || (!p.ir->lower && !p.ir->upper)) continue;
    if (!table) {
      table.emplace(*sm.model);
      table_values = table->values();
      values = sm.values();
    }
    // Substituted without pattern matching: GiNaC then looks each symbol up in the maps, where with patterns it
    // tries every entry at every node (100 000 bounded parameters took hours: quadratic).
    const auto at_values = [&](const ir::Expr& bound) {
      const GiNaC::ex e = table->convert(bound);
      if (GiNaC::is_a<GiNaC::numeric>(e)) return to_double(e);
      return to_double(e.subs(table_values, GiNaC::subs_options::no_pattern).subs(values, GiNaC::subs_options::no_pattern));
    };
    if (p.ir->lower) bounds[i].first = at_values(*p.ir->lower);
    if (p.ir->upper) bounds[i].second = at_values(*p.ir->upper);
  }
  return bounds;
}

// The header as the source's #include line names it: its path relative to the source's directory, so that
// `-o src/m.cpp --header include/m.hpp` compiles without an extra include path.
std::string include_path(const std::string& header, const std::string& source) {
  namespace fs = std::filesystem;
  if (header.find('/') == std::string::npos && source.find('/') == std::string::npos) return header;
  std::error_code ec;
  const fs::path h = fs::absolute(header, ec).lexically_normal();
  const fs::path s = fs::absolute(source, ec).lexically_normal();
  const fs::path relative = h.lexically_relative(s.parent_path());
  return ec || relative.empty() ? base_name(header) : relative.generic_string();
}

}  // namespace

const char* mbgen_version() { return MBGEN_VERSION; }

std::string part_file_name(const std::string& source_file, int k) {
  const std::size_t slash = source_file.find_last_of("/\\");
  const std::size_t dot = source_file.find_last_of('.');
  const bool has_extension = dot != std::string::npos && (slash == std::string::npos || dot > slash);
  const std::string stem = has_extension ? source_file.substr(0, dot) : source_file;
  const std::string extension = has_extension ? source_file.substr(dot) : ".cpp";
  return stem + "_part" + std::to_string(k) + extension;
}

CppEmitResult emit_cpp(const SymbolicModel& sm, const CppEmitOptions& options) {
  std::string model_name = options.model_name;
  if (model_name.empty()) {
    if (!sm.model) throw std::invalid_argument("emit_cpp: no model name");
    model_name = sm.model->name;
  }
  std::string ns = options.namespace_name;
  if (ns.empty()) {
    ns = "mbgen_models::" + ir::to_identifier(model_name);
    // The model's own name: a problem with the model (the command line checks --namespace before).
    if (const std::string problem = namespace_problem(ns); !problem.empty())
      throw frontend::ModelError(sm.model ? sm.model->file : "", sm.model ? sm.model->name_loc : ir::SourceLoc{},
                                 "the model's name `" + model_name + "` cannot name its C++ namespace " + ns + ": " +
                                     problem + "; rename the model (`model NAME`) or give mbgen --namespace");
  }
  if (const std::string problem = namespace_problem(ns); !problem.empty())
    throw std::invalid_argument("emit_cpp: invalid C++ namespace `" + ns + "`: " + problem);
  const std::string header_file = include_path(options.header_file, options.source_file),
                    source_file = base_name(options.source_file);
  if (const std::string problem = include_name_problem(header_file); !problem.empty())
    throw std::invalid_argument("emit_cpp: header name `" + header_file + "` cannot be #included: " + problem);

  std::vector<std::string> inputs, outputs, coordinates;
  if (sm.model) {
    for (const auto& in : sm.model->inputs) inputs.push_back(in.name);
    for (const auto& out : sm.model->outputs) outputs.push_back(out.name);
  } else {
    for (unsigned j = 0; j < sm.B.cols(); ++j) inputs.push_back("u" + std::to_string(j));
    for (unsigned i = 0; i < sm.Cd.rows(); ++i) outputs.push_back("y" + std::to_string(i));
  }
  for (const auto& c : sm.coordinates) coordinates.push_back(c.name());

  FunctionContext ctx(sm);
  const char* const kSquare = "num_coordinates, num_coordinates";
  const MatrixSpec specs[] = {
      {"mass_matrix", "M", "CoordinateMatrix", "Mass matrix M.", &sm.M, true, kSquare},
      {"damping_matrix", "C", "CoordinateMatrix", "Damping matrix C, including the gyroscopic matrix G.", &sm.C_total, true, kSquare},
      {"gyroscopic_matrix", "G", "CoordinateMatrix", "Gyroscopic matrix G alone (skew-symmetric, part of C).", &sm.G, false, kSquare},
      {"stiffness_matrix", "K", "CoordinateMatrix", "Stiffness matrix K.", &sm.K, true, kSquare},
      {"input_matrix", "B", "InputMatrix", "Input matrix B.", &sm.B, true, "num_coordinates, num_inputs"},
      {"output_displacement_matrix", "Cd", "OutputMatrix", "Output map of displacements Cd.", &sm.Cd, true, "num_outputs, num_coordinates"},
      {"output_velocity_matrix", "Cv", "OutputMatrix", "Output map of velocities Cv.", &sm.Cv, true, "num_outputs, num_coordinates"},
      {"output_acceleration_matrix", "Ca", "OutputMatrix", "Output map of accelerations Ca.", &sm.Ca, true, "num_outputs, num_coordinates"},
  };
  if (options.parts < 1) throw std::invalid_argument("emit_cpp: parts must be at least 1");
  const bool dynamic_size = sm.coordinates.size() > kMaxFixedSizeCoordinates || sm.coordinates.size() < 2;
  BodyEmitter emitter{ctx, options.max_function_operations, options.parts > 1, {}, {}, {}};
  TemplateList matrices;
  for (const auto& spec : specs) matrices.push_back(matrix_dict(sm, ctx, spec, emitter, dynamic_size));
  const TemplateList transfer_functions = transfer_function_dicts(sm, ctx, inputs, outputs, emitter.counts);

  // The pieces: in the main source when it is the only one; otherwise spread over the parts (each piece to the
  // part with the fewest operations so far, in order: deterministic), the main source declaring them.
  const int parts = options.parts;
  std::vector<TemplateList> part_chunks(static_cast<std::size_t>(parts));
  std::vector<std::size_t> part_load(static_cast<std::size_t>(parts), 0);
  TemplateList declarations;
  for (const Chunk& c : emitter.chunks) {
    std::size_t target = 0;
    if (parts > 1) {
      target = 1;
      for (std::size_t k = 2; k < part_load.size(); ++k)
        if (part_load[k] < part_load[target]) target = k;
      declarations.push_back({{"name", c.name}, {"params", c.params}});
    }
    part_load[target] += c.operations;
    part_chunks[target].push_back(
        {{"name", c.name}, {"params", c.params}, {"param_types", c.param_types}, {"body", c.body}});
  }
  TemplateList chunk_section, part_files, fixed_size, dynamic_size_list;
  if (!emitter.chunks.empty()) chunk_section.emplace_back();
  std::vector<std::string> part_names;
  for (int k = 1; k < parts; ++k) {
    part_names.push_back(base_name(part_file_name(options.source_file, k)));
    part_files.push_back({{"file", cxx_comment_text(part_names.back())}});
  }
  (dynamic_size ? dynamic_size_list : fixed_size).emplace_back();
  std::string parts_line;
  if (parts > 1) parts_line = "// Split into " + std::to_string(parts) + " translation units: this file and " +
                              cxx_comment_text(join(part_names)) + ".\n";

  TemplateList parameters;
  std::vector<std::string> names, roles, units, lower, upper;
  const std::vector<std::pair<double, double>> bounds = bounds_of(sm);
  for (const auto& p : sm.parameters) {
    parameters.push_back({{"name", p.name}, {"value", double_literal(to_double(p.value))}, {"exact", infix_text(p.value)}});
    names.push_back(cxx_string_literal(p.name));
    roles.push_back(role_text(p.ir ? p.ir->role : ir::Role::Known));
    units.push_back(cxx_string_literal(p.ir ? p.ir->unit : ""));
    const auto [lo, hi] = bounds[static_cast<std::size_t>(&p - sm.parameters.data())];
    lower.push_back(double_literal(lo));
    upper.push_back(double_literal(hi));
  }
  auto quoted = [](const std::vector<std::string>& v) {
    std::vector<std::string> q;
    for (const auto& s : v) q.push_back(cxx_string_literal(s));
    return join(q);
  };

  const TemplateDict values = {
      {"version", MBGEN_VERSION},
      {"model_file", cxx_comment_text(base_name(options.model_file))},
      {"model_name", cxx_comment_text(model_name)},
      {"namespace", ns},
      {"header_file", header_file},
      {"header_file_comment", cxx_comment_text(header_file)},
      {"source_file", cxx_comment_text(source_file)},
      {"num_parameters", std::to_string(sm.parameters.size())},
      {"num_coordinates", std::to_string(sm.coordinates.size())},
      {"num_inputs", std::to_string(inputs.size())},
      {"num_outputs", std::to_string(outputs.size())},
      {"parameters", parameters},
      {"parameter_names", join(names)},
      {"parameter_roles", join(roles)},
      {"parameter_units", join(units)},
      {"parameter_lower", join(lower)},
      {"parameter_upper", join(upper)},
      {"coordinate_names", quoted(coordinates)},
      {"input_names", quoted(inputs)},
      {"output_names", quoted(outputs)},
      {"matrices", matrices},
      {"num_transfer_functions", std::to_string(sm.transfer_functions.size())},
      {"transfer_functions", transfer_functions},
      // Without inputs or outputs there is no transfer function: the dispatchers then mark their arguments used.
      {"no_transfer_functions", transfer_functions.empty() ? TemplateList{TemplateDict{}} : TemplateList{}},
      {"operations_before_cse", std::to_string(emitter.counts.before_cse)},
      {"operations_after_cse", std::to_string(emitter.counts.after_cse)},
      {"function_bound", options.max_function_operations == 0
                             ? std::string("Function size not bounded.")
                             : "Functions of at most " + std::to_string(options.max_function_operations) +
                                   " operations and\n// stores before it (longer ones are split into pieces)."},
      {"parts_line", parts_line},
      {"part_files", part_files},
      {"chunk_section", chunk_section},
      {"chunk_declarations", declarations},
      {"chunks", part_chunks[0]},
      {"fixed_size", fixed_size},
      {"max_fixed_size_coordinates", std::to_string(kMaxFixedSizeCoordinates)},
      {"dynamic_size", dynamic_size_list},
  };
  CppEmitResult result{render_embedded("cpp/model.hpp.tmpl", values), render_embedded("cpp/model.cpp.tmpl", values), {}};
  for (int k = 1; k < parts; ++k) {
    TemplateDict part = values;
    part["part"] = std::to_string(k);
    part["part_chunks"] = part_chunks[static_cast<std::size_t>(k)];
    result.parts.push_back(render_embedded("cpp/model_part.cpp.tmpl", part));
  }
  return result;
}

}  // namespace mbgen::emit
