// A MATLAB level-5 .mat file assembled in memory and written by libmatio (`mbgen export --format mat`). Without
// libmatio at build time (MBGEN_HAVE_MATIO undefined) mat_file_available() is false and bytes() throws.
#pragma once

#include <Eigen/Core>

#include <complex>
#include <string>
#include <vector>

namespace mbgen::cli {

bool mat_file_available();

class MatFile {
 public:
  // Variables in the order added; names must be MATLAB identifiers.
  void matrix(const std::string& name, const Eigen::MatrixXd& m);
  // A complex array of any rank; `values` in MATLAB's (column-major) order, dims' product long.
  void complex_array(const std::string& name, const std::vector<std::size_t>& dims,
                     const std::vector<std::complex<double>>& values);
  void text(const std::string& name, const std::string& value);                // a char row
  void texts(const std::string& name, const std::vector<std::string>& values);  // a cell column of char rows

  // The file's bytes with `header` (at most 116 characters) as its descriptive text: libmatio's own names the date,
  // which would make equal inputs give different files. Uncompressed. Throws std::runtime_error when libmatio is
  // absent or fails.
  std::string bytes(const std::string& header) const;

 private:
  enum class Kind { Real, Complex, Text, Texts };
  struct Variable {
    Kind kind;
    std::string name;
    std::vector<std::size_t> dims;
    std::vector<double> re, im;
    std::vector<std::string> strings;
  };
  std::vector<Variable> variables_;
};

}  // namespace mbgen::cli
