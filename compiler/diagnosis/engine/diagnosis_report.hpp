// The human report of a diagnosis: report.md and report.html with the verdict, the findings, the candidate ranking, the
// parameters, and SVG plots per channel of data vs nominal vs extended FRFs and of the residual before and after.
#pragma once

#include <string>

#include "diagnosis/engine/diagnose.hpp"

namespace mbgen::diagnosis {

// A finding's text as a reader sees it (the report, standard output): the findings name their data file by the path
// given on the command line. With one data file the path says nothing and is left out, with several the file's name
// tells them apart; the JSON keeps the full text.
std::string reader_text(const DiagnosisResult& result, const std::string& finding_text);

// Said of a selected extension that clears none of the nominal model's findings on its own (its
// DiagnosisResult::explains is empty), so that it never stands with nothing said for it: an effect taken last, once
// the others had cleared what it bears on (a loose mount after a sensor's calibration and an added mass).
inline constexpr const char* kExplainsNoFindingAlone =
    "it clears none of the nominal model's findings on its own (extensions taken before it cleared them, or they still "
    "show): it was taken for the misfit over the noise that it removes";

void write_diagnosis_report(const std::string& dir, const DiagnosisResult& result);

}  // namespace mbgen::diagnosis
