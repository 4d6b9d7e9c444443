// The conditions a data set was measured under: `# condition temperature=21.5` lines among the comment lines
// before a CSV header (docs/interfaces.md, "Measured data"), one variable per line, which `monitor --output-only`
// learns and removes the effect of. The data readers take the lines for free comments; this reads them on its own.
#pragma once

#include <string>
#include <vector>

namespace mbgen {

struct ConditionValue {
  std::string name;  // an identifier: a letter or _, then letters, digits, _
  double value = 0;  // a finite decimal number
  int line = 0;
};

// The `# condition NAME=VALUE` lines of the CSV file at `path`, in file order (none for standard input "-" and UFF
// files). Throws DataError (file, line, column: characters from 1) for a line that starts `# condition` but is not
// of this form, or that repeats a name.
std::vector<ConditionValue> read_operating_conditions(const std::string& path);

// The variables every data set must give: the names (in the first file's order) and per file the values in that
// order. Throws DataError naming the first file that lacks a variable another has, or has one the first lacks.
struct ConditionTable {
  std::vector<std::string> names;
  std::vector<std::vector<double>> values;  // per file
};
ConditionTable condition_table(const std::vector<std::string>& paths,
                               const std::vector<std::vector<ConditionValue>>& per_file);

}  // namespace mbgen
