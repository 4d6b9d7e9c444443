// `mbgen MODEL.mdl -o OUT.cpp [--header OUT.hpp] [--namespace NS] [--parts N] [--function-ops N]`: the
// build-pipeline use.
#include "cli/commands.hpp"
#include "cli/output_files.hpp"
#include "cli/run_guarded.hpp"
#include "cli/version.hpp"
#include "emit/cpp_emitter.hpp"
#include "emit/cxx_text.hpp"
#include "frontend/parser.hpp"
#include "symbolic/derive.hpp"

namespace mbgen::cli {

namespace {

// OUT.cpp -> OUT.hpp (any other name gets .hpp appended).
std::string default_header_for(const std::string& source) {
  const std::size_t dot = source.find_last_of('.');
  const std::size_t slash = source.find_last_of('/');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return source + ".hpp";
  return source.substr(0, dot) + ".hpp";
}

std::string base_name(const std::string& path) { return path.substr(path.find_last_of('/') + 1); }

}  // namespace

int run_compile(int argc, char** argv) {
  CLI::App app{"Compile a model to C++: a header and a source with M, C, K, B, the output map, their parameter "
               "Jacobians, state space and transfer-function coefficients.",
               "mbgen"};
  std::string model_path, source_path, header_path, ns;
  app.add_option("model", model_path, "model file (.mdl); - reads standard input")->required();
  app.add_option("-o,--output", source_path, "C++ source to write; - writes both files to standard output")->required();
  app.add_option("--header", header_path, "header to write (default: the source's name with .hpp)");
  app.add_option("--namespace", ns, "C++ namespace (default: mbgen_models::MODEL)");
  int parts = 1;
  std::size_t function_operations = emit::CppEmitOptions{}.max_function_operations;
  app.add_option("--parts", parts,
                 "translation units: N > 1 also writes OUT_part1.cpp .. OUT_part{N-1}.cpp beside OUT.cpp, which hold "
                 "the matrix and Jacobian functions' work (compile them all)")
      ->check(CLI::Range(1, 1000));
  app.add_option("--function-ops", function_operations,
                 "largest emitted function, in operations before CSE (longer ones are split into pieces); 0: no limit");
  app.set_version_flag("--version", version_text());
  return run_guarded(app, argc, argv, [&] {
    const std::string header_option = header_path.empty() ? "-o (its header)" : "--header";
    if (header_path.empty()) header_path = source_path == "-" ? "-" : default_header_for(source_path);
    if (!ns.empty())
      if (const std::string problem = emit::namespace_problem(ns); !problem.empty())
        throw CLI::ValidationError("--namespace", "`" + ns + "` cannot name the generated namespace: " + problem);
    if (header_path != "-")
      if (const std::string problem = emit::include_name_problem(base_name(header_path)); !problem.empty())
        throw CLI::ValidationError(header_option, "the header " + header_path +
                                                      " cannot be named in the source's #include line: " + problem);
    if (parts > 1 && source_path == "-")
      throw CLI::ValidationError("--parts", "several translation units need a file name (-o OUT.cpp), not -");
    OutputPlan plan;
    plan.files = {{header_option, header_path}, {"-o", source_path}};
    for (int k = 1; k < parts; ++k) plan.files.push_back({"--parts", emit::part_file_name(source_path, k)});
    plan.inputs = {model_path};
    plan.check();
    const ir::ModelIr model = frontend::parse_file(model_path);
    const symbolic::SymbolicModel sym = symbolic::derive(model);
    emit::CppEmitOptions options;
    options.namespace_name = ns;
    options.header_file = header_path == "-" ? model.name + "_model.hpp" : header_path;
    options.source_file = source_path == "-" ? model.name + "_model.cpp" : source_path;
    options.model_file = model_path == "-" ? "<stdin>" : model_path;
    options.parts = parts;
    options.max_function_operations = function_operations;
    const emit::CppEmitResult code = emit::emit_cpp(sym, options);
    OutputFiles out;
    out.add(header_path, code.header);
    out.add(source_path, code.source);
    for (int k = 1; k < parts; ++k)
      out.add(emit::part_file_name(source_path, k), code.parts[static_cast<std::size_t>(k - 1)]);
    out.commit();
    return 0;
  });
}

}  // namespace mbgen::cli
