// The human report of a diagnosis: report.md and report.html with the verdict, the findings, the candidate ranking, the
// parameters, and SVG plots per channel of data vs nominal vs extended FRFs and of the residual before and after.
#pragma once

#include <string>

#include "diagnosis/engine/diagnose.hpp"

namespace mbgen::diagnosis {

void write_diagnosis_report(const std::string& dir, const DiagnosisResult& result);

}  // namespace mbgen::diagnosis
