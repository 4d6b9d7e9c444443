// Output of a fit: the `mbgen-fit/1` JSON (docs/interfaces.md) and a report directory with Markdown and gnuplot plots.
#pragma once

#include "mbgen/estimation/fit.hpp"

#include <iosfwd>
#include <string>

namespace mbgen {

// The JSON document, deterministic (keys sorted, numbers in shortest round-trip form).
std::string fit_result_json(const FitResult& result);
void write_fit_json(std::ostream& out, const FitResult& result);

// Writes DIR/report.md and DIR/report.html (mbgen/report/report_document.hpp), per data set the data files (*.dat) and
// gnuplot scripts (*.gp) for Bode overlays (magnitude and phase) of data vs model at the prior and at the estimate and
// for the residuals, and renders them to SVG with `gnuplot` when it is installed (otherwise the report says so). The
// Bode overlays carry the estimate's +-2 std band where the result has a covariance (frf_confidence.hpp); the result's
// residual tests and validation scores get a section each, the validation data (`validation`, as scored) plotted
// against the model at the estimate. Creates DIR if needed. Throws FitError if DIR cannot be written.
void write_fit_report(const std::string& dir, const Model& model, const std::vector<DataSet>& data,
                      const FitResult& result, const std::vector<DataSet>& validation = {});

}  // namespace mbgen
