// `mbgen convert DATA... -o OUT [--model MODEL.mdl] [--set ...] [--quantity ...]`: measured data written in another
// format mbgen reads, for another tool: FRFs as ASCII UFF 58 (OUT.uff or OUT.unv, with OUT.map naming the points) or
// CSV, time records as CSV (cli/data_writing.hpp, docs/data.md).
#include <iostream>

#include "cli/commands.hpp"
#include "cli/data_writing.hpp"
#include "cli/output_files.hpp"
#include "cli/run_guarded.hpp"
#include "cli/version.hpp"

namespace mbgen::cli {

int run_convert(int argc, char** argv) {
  CLI::App app{"Write measured data in another format mbgen reads: FRFs (CSV or UFF 58/58b) as UFF 58 for pyuff and "
               "other tools, or as CSV; time records as CSV. The data are read as `fit --data` reads them.",
               "mbgen convert"};
  std::vector<std::string> data_paths, sets;
  std::string output, model_path, quantity = "auto";
  app.add_option("data", data_paths,
                 "data files (CSV or UFF 58/58b, with PATH.map beside a UFF file); several FRF files with the same "
                 "lines are joined into one")
      ->required();
  app.add_option("-o,--output", output,
                 "file to write: .uff or .unv (ASCII UFF 58, with OUT.map beside it naming the points) or .csv")
      ->required();
  app.add_option("--model", model_path,
                 "check the channels against this model's inputs and outputs (as fit does) and take the UFF points "
                 "from its sensor points (inputs: nodes 1001, 1002, ...) and the ordinate type from its outputs");
  app.add_option("--set", sets, "with --model: override a parameter's value, NAME=VALUE (repeatable)");
  app.add_option("--quantity", quantity,
                 "UFF output: what the FRFs are (record 9's ordinate type): auto (the model's outputs, else the "
                 "input UFF file's), receptance, mobility or accelerance")
      ->check(CLI::IsMember({"auto", "receptance", "mobility", "accelerance"}));
  app.set_version_flag("--version", version_text());
  return run_guarded(app, argc, argv, [&] {
    const std::optional<DataFormat> format = data_format_of(output);
    if (!format)
      throw CLI::ValidationError("-o", "the name says the format: OUT.uff or OUT.unv (UFF 58) or OUT.csv, got `" +
                                           output + "`");
    if (!sets.empty() && model_path.empty()) throw CLI::ValidationError("--set", "needs --model");
    if (quantity != "auto" && *format != DataFormat::Uff)
      throw CLI::ValidationError("--quantity", "only for a UFF output (CSV does not carry it)");
    parse_set_options(sets);
    OutputPlan plan;
    plan.files = {{"-o", output}, {"-o (its UFF mapping file)", *format == DataFormat::Uff ? output + ".map" : ""}};
    plan.inputs = data_paths;
    for (const std::string& path : data_paths)
      if (path != "-") plan.inputs.push_back(path + ".map");  // a mapping file read with its data
    if (!model_path.empty()) plan.inputs.push_back(model_path);
    plan.check();

    DataWriteRequest request;
    request.format = *format;
    request.model_path = model_path;
    request.sets = sets;
    request.quantity = quantity;
    const DataSet data = read_for_writing(data_paths, model_path, sets, request.mappings);
    request.comments = carried_comments(data_paths);
    if (*format == DataFormat::Uff && !request.comments.empty())
      std::cerr << "warning: UFF 58 carries no `# time=` or `# condition` line: " << output
                << " goes without them (CSV keeps them; monitor reads them from CSV only)\n";
    const DataTexts texts = data_texts(data, request);
    OutputFiles out;
    out.add(output, texts.data);
    if (*format == DataFormat::Uff) out.add(output + ".map", texts.mapping);
    out.commit();
    return 0;
  }, &model_path);
}

}  // namespace mbgen::cli
