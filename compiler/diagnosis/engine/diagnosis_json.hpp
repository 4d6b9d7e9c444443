// The diagnosis result as JSON, schema `mbgen-diagnosis/1` (docs/interfaces.md). Extra fields beyond
// the schema (documented in docs/diagnosis.md): discrepancy band, size and data set; each candidate's
// description, round, plausibility doubts and whether it qualified; the findings left after extension.
#pragma once

#include <string>

#include "diagnosis/engine/diagnose.hpp"

namespace mbgen::diagnosis {

// `extended_model_path`: where the extended .mdl was written (empty when not extended or not written).
std::string diagnosis_json(const DiagnosisResult& result, const std::string& extended_model_path);

}  // namespace mbgen::diagnosis
