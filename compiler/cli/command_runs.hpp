// The work of `fit`, `diagnose` and `modal` between their command lines and their output files, as functions: the
// `mbgen` command (run_fit, run_diagnose, run_modal) and the Python module (python/) call the same code, so a
// result's JSON is the same whichever asked for it. Each takes the options as the command line gives them (checked
// where the command checks them first) and returns what the command writes from; errors are thrown as the command
// body throws them (run_guarded.hpp turns them into messages and exit statuses).
#pragma once

#include <mbgen/data_set.hpp>
#include <mbgen/fit.hpp>
#include <mbgen/methods/ekf.hpp>
#include <mbgen/methods/two_step.hpp>
#include <mbgen/modal_identification.hpp>
#include <mbgen/modal_report.hpp>
#include <mbgen/model.hpp>

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

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
  TwoStepOptions two_step;            // --two-step-model, --two-step-criterion, --two-step-weighting
  std::string two_step_route = "auto";
  EkfOptions ekf;                     // --ekf-drift
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
};

struct DiagnoseRun {
  diagnosis::DiagnosisResult result;            // with its warnings set
  std::map<std::string, std::string> set;       // --set with --fix's values (the extended model is derived with it)
};

DiagnoseRun diagnose_model(DiagnoseRequest request);

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
  std::optional<ir::ModelIr> model;           // the model file, with a model
  std::string quantity_source;
  // What the JSON, the report and the summary are made from; refers into this run, which must outlive it.
  ModalReportInput input() const { return {data, result, options, comparison ? &*comparison : nullptr, quantity_source}; }
};

ModalRun modal_identification(ModalRequest request);

}  // namespace mbgen::cli
