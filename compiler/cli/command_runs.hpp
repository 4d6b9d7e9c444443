// The work of `fit`, `diagnose`, `modal`, `sensitivity`, `monitor` and `export` between their command lines and their
// output files, as functions: the `mbgen` command (run_fit, run_diagnose, ...) and the Python module (python/) call
// the same code, so a
// result's JSON is the same whichever asked for it. Each takes the options as the command line gives them (checked
// where the command checks them first) and returns what the command writes from; errors are thrown as the command
// body throws them (run_guarded.hpp turns them into messages and exit statuses).
#pragma once

#include <mbgen/data/data_set.hpp>
#include <mbgen/estimation/fit.hpp>
#include <mbgen/methods/method_table.hpp>
#include <mbgen/modal_identification/modal_identification.hpp>
#include <mbgen/modal_identification/modal_report.hpp>
#include <mbgen/model.hpp>
#include <mbgen/report/mode_shape_svg.hpp>
#include <mbgen/monitoring/monitor.hpp>
#include <mbgen/monitoring/operational_report.hpp>
#include <mbgen/sensitivity/sensitivity_report.hpp>

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "cli/monitor_output_only.hpp"
#include "cli/parameter_roles.hpp"
#include "diagnosis/engine/diagnose.hpp"

namespace mbgen::cli {

// ---- fit ---------------------------------------------------------------------------------------------------------

struct FitRequest {
  std::string model_path;
  std::vector<std::string> data_paths;
  std::string method = "auto";        // as --method
  std::map<std::string, std::string> set;  // --set, already checked by parse_set_options
  RoleOptions roles;                  // --fix, --free, --bound
  FitOptions options;                 // --starts, --seed; progress as the caller wants it
  bool start_from_modes = false;      // --start-from-modes (output error only)
  std::string band;                   // --band LO:HI, "" for every line
  MethodOptions method_options;       // the methods' own options (--two-step-route, --ekf-drift, ...)
  std::vector<std::string> validate_paths;  // --validate: data scored at the estimate, not fitted
  int residual_lags = 25;             // the residual tests' largest lag L
};

struct FitRun {
  std::unique_ptr<Model> model;  // the evaluator fitted (the report draws with it)
  std::vector<DataSet> data;     // as fitted (within --band)
  std::vector<DataSet> validation;  // --validate's data sets
  FitResult result;              // with its model file, seed, warnings, residual tests and validation scores set
};

FitRun fit_model(FitRequest request);

// ---- diagnose ----------------------------------------------------------------------------------------------------

struct DiagnoseRequest {
  std::string model_path;
  std::vector<std::string> data_paths;
  RoleOptions roles;
  diagnosis::DiagnoseOptions options;  // its `set` already checked by parse_set_options; progress as wanted
  std::string fit_band;                // --fit-band LO:HI, "" for every line
  // --method: a method beside output error runs first on the data the nominal fit sees, and its estimate is one more
  // start of that fit ("auto" or another output-error name: nothing added).
  std::string method = "auto";
  MethodOptions method_options;        // the methods' own options (--two-step-route, --ekf-drift, ...)
};

struct DiagnoseRun {
  diagnosis::DiagnosisResult result;            // with its warnings set
  std::map<std::string, std::string> set;       // --set with --fix's values (the extended model is derived with it)
};

DiagnoseRun diagnose_model(DiagnoseRequest request);

// The run's mbgen-diagnosis/1 JSON (`extended_model_path`: where the extended model is written, "" for nowhere).
std::string diagnose_run_json(const DiagnoseRun& run, const std::string& extended_model_path);

// ---- modal -------------------------------------------------------------------------------------------------------

struct ModalRequest {
  std::vector<std::string> data_paths;
  FrequencyBand band;                 // --band, already parsed
  std::string model_path;             // --model, "" for none
  std::vector<std::string> sets;      // --set (with --model), checked here as the command checks them
  ModalOptions options;               // --max-order, --select, --no-refine; progress as wanted
  std::string quantity = "auto";      // --quantity
};

struct ModalRun {
  ModalData data;
  ModalIdentification result;
  ModalOptions options;
  std::optional<ModelComparison> comparison;  // with a model
  std::optional<ir::ModelIr> declared;        // the model file as parsed (the IR), with a model
  std::string quantity_source;
  // What the JSON, the report and the summary are made from; refers into this run, which must outlive it.
  ModalReportInput input() const { return {data, result, options, comparison ? &*comparison : nullptr, quantity_source}; }
};

ModalRun modal_identification(ModalRequest request);

// ---- sensitivity -------------------------------------------------------------------------------------------------

struct SensitivityRequest {
  std::string model_path;
  std::map<std::string, std::string> set;  // --set, already checked by parse_set_options
  RoleOptions roles;
  bool global = false;                     // --global
  bool bounds = false;                     // --bounds
  double spread = 0.2;                     // --spread
  SobolOptions sobol;                      // --samples, --seed
  std::vector<std::string> sweeps;         // --sweep NAME=LO:HI:N, checked here as the command checks them
  bool geometry = false;                   // the mode shapes' geometry, for a report
};

struct SensitivityRun {
  std::string model_path;
  ir::ModelIr declared;
  std::unique_ptr<Model> model;
  LocalSensitivity local;
  ModeVisibility visibility;
  bool global = false;
  GlobalSensitivity global_result;
  SobolOptions sobol;
  std::string range_text;
  std::vector<FeatureMap> maps;
  std::optional<ShapeGeometry> geometry;
  // What the JSON, the report and the summary are made from; refers into this run, which must outlive it.
  SensitivityReportInput input() const;
};

SensitivityRun sensitivity_analysis(SensitivityRequest request);

// ---- monitor -----------------------------------------------------------------------------------------------------

// The settings of one monitoring run with a measured force, apart from its model and data.
struct MonitorSettings {
  MonitorOptions options;          // --baseline, --run-length, --structural-ratio, --starts, --warm-starts, --seed
  std::vector<std::string> sets;   // --set, checked here
  RoleOptions roles;
  bool no_diagnosis = false;
  // --method: a method beside output error runs first on each data set, and its estimate is one more start of that
  // set's fit ("auto" or another output-error name: nothing added).
  std::string method = "auto";
  MethodOptions method_options;
};

// Monitors one machine: its model (path, or "-" for standard input) and its data sets, ordered by time; progress on
// standard error as the command prints it.
MonitorResult monitor_machine(const std::string& model_path, const std::vector<std::string>& data_paths,
                              MonitorSettings settings);

// `monitor --output-only`: the records' modes, monitored (and explained with a model); the outputs are left to the
// caller (run_monitor_output_only writes them).
struct OperationalRun {
  OperationalMonitorResult result, raw;  // raw: without compensation, when compensated
  bool compensated = false;
  std::vector<std::string> channels;
  std::string method;
  std::string model_path;
  std::optional<OperationalModelModes> model_modes;
  std::vector<ChangeExplanation> explanations;
  // What the JSON, the report and the summary are made from; refers into this run, which must outlive it.
  OperationalReportInput input() const;
};

OperationalRun monitor_output_only(const OperationalRequest& request);

// ---- export ------------------------------------------------------------------------------------------------------

struct ExportRequest {
  std::string model_path;
  std::string what = "matrices";           // --what: matrices, state-space, modes, frf
  std::string format = "json";             // --format: json, csv, uff, mat
  std::string grid;                        // --frf LO:HI:N, with --what frf only
  std::string fit_result;                  // --fit-result FIT.json, "" for none
  std::optional<std::string> fit_result_text;  // the fit result's JSON itself (Python's), named fit_result in messages
  std::map<std::string, std::string> set;  // --set, already checked by parse_set_options
  std::string output;                      // -o, for the checks of what it can hold; "" when no file is written
};

// Refuses, with the command's messages, the combinations the command refuses and a malformed --frf grid.
void check_export_request(const ExportRequest& request);

// The file's text and, for UFF, its mapping file's (OUT.map); checked by check_export_request first.
struct ExportText {
  std::string data, mapping;
};

ExportText export_model(const ExportRequest& request);

}  // namespace mbgen::cli
