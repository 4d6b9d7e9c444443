// The fit report's sections on validation (fit_report.cpp draws the rest): the residual tests of the records fitted
// and the scores on other data (`fit --validate`), each a table and gnuplot plots.
#pragma once

#include "mbgen/estimation/fit.hpp"
#include "mbgen/report/report_document.hpp"

#include <filesystem>
#include <string>
#include <vector>

namespace mbgen::estimation {

// "Residual tests": per record and output, the verdicts, and a plot of the correlations with their 99 % bands.
// Nothing when the fit had no time records.
void residual_test_section(report::Document& doc, const std::filesystem::path& root, const FitResult& result,
                           std::vector<std::string>& scripts);

// "Validation on other data": the fit percentages and, per channel, the validation data against the model at the
// estimate. Nothing when there are no validation data.
void validation_section(report::Document& doc, const std::filesystem::path& root, const Model& model,
                        const std::vector<DataSet>& validation, const FitResult& result,
                        std::vector<std::string>& scripts);

}  // namespace mbgen::estimation
