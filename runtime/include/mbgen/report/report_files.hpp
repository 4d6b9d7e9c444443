// Small pieces shared by the report directories (mbgen/report/report_document.hpp): writing a file whole, a name made
// safe for a plot's file stem, and numbers as the reports' tables print them.
#pragma once

#include <string>

namespace mbgen {

// Writes `text` to a temporary name beside `path` and renames it, so that the file appears whole or not at all.
// Throws FitError (mbgen/estimation/fit.hpp) when it cannot.
void write_report_file(const std::string& path, const std::string& text);

// `name` with every character other than a letter, a digit, `_` or `-` replaced by `_`: a file stem.
std::string file_stem(const std::string& name);

// `x` with `digits` significant digits; "n/a" when it is not finite.
std::string report_number(double x, int digits = 6);

}  // namespace mbgen
