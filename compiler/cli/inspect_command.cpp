// `mbgen inspect MODEL.mdl [--format markdown|latex|json] [--set NAME=VALUE ...]`: the symbolic matrices,
// transfer-function coefficients and modes, for reading.
#include "cli/commands.hpp"
#include "cli/output_files.hpp"
#include "cli/run_guarded.hpp"
#include "cli/version.hpp"
#include "emit/inspect.hpp"
#include "frontend/parser.hpp"
#include "symbolic/derive.hpp"

namespace mbgen::cli {

int run_inspect(int argc, char** argv) {
  CLI::App app{"Print a model's symbolic M, C, K, B and output map, its transfer-function coefficients, exact "
               "pole-zero cancellations and its modes at the current parameter values.",
               "mbgen inspect"};
  std::string model_path, format = "markdown", output = "-";
  std::vector<std::string> sets;
  app.add_option("model", model_path, "model file (.mdl); - reads standard input")->required();
  app.add_option("--format", format, "markdown, latex or json (schema mbgen-inspect/1)")
      ->check(CLI::IsMember({"markdown", "latex", "json"}));
  app.add_option("--set", sets, "override a parameter's value: NAME=VALUE (repeatable)");
  app.add_option("-o,--output", output, "file to write (default: standard output)");
  app.set_version_flag("--version", version_text());
  return run_guarded(app, argc, argv, [&] {
    symbolic::DeriveOptions options;
    options.set = parse_set_options(sets);
    OutputPlan plan;
    plan.files = {{"-o", output}};
    plan.inputs = {model_path};
    plan.check();
    const ir::ModelIr model = frontend::parse_file(model_path);
    const symbolic::SymbolicModel sym = symbolic::derive(model, options);
    OutputFiles out;
    out.add(output, emit::emit_inspect(sym, emit::parse_inspect_format(format)));
    out.commit();
    return 0;
  }, &model_path);
}

}  // namespace mbgen::cli
