// The direct method's data side (docs/methods.md#direct): the measured motion of every coordinate, line by line.
// Internal header.
//
// Each block is one frequency line and one excitation: the equations of motion there,
//
//     Z(w) X + [i w a + b] = (i w)^r B F,      Z(w) = (i w)^2 M + i w C + K,
//
// where X is the spectrum of the r-th derivative of the excited coordinates (r = 0: displacement), recovered from the
// measured outputs through the output map, and F the inputs' spectrum.
// - FRF data: per input column j and line, X = H_q (r = 0), the coordinates' receptances, from the measured FRFs
//   y = (Cd + i w Cv - w^2 Ca) H_q by (noise-weighted) least squares; F = e_j. No bracketed term.
// - Time records: the record's Fourier integral at w_k = 2 pi k / T (T the record's length) of the measured kind of
//   output (r = 0, 1 or 2: all displacements, all velocities or all accelerations), X = map^+ Y; the held input's
//   integral F is exact (zero- or first-order hold). Over a finite record the integral of a derivative picks up the
//   motion at the ends, FT(q') = i w Q + (q(T) - q(0)); these end terms are the bracket, i w a + b with a, b real
//   vectors per record, unknown nuisance parameters (exact columns: no noise). The sampled spectrum equals the
//   continuous one up to aliasing (Poisson summation of the periodic trapezoid sum), so only lines up to fs/10 are
//   used, where the aliased response of a mechanical system (falling at least as 1/w^2) is below 1e-3 of it.
// The noise of X per block, cov X = S S^H, is carried in shape (its overall scale is estimated by the solver).
#pragma once

#include "mbgen/estimation/fit.hpp"

#include <Eigen/Core>

#include <string>
#include <vector>

namespace mbgen::methods {

struct EquationBlock {
  int set = 0;                  // data set index
  double omega = 0;             // rad/s
  int kind = 0;                 // r: X is the spectrum of the r-th derivative of the coordinates
  std::vector<int> rows;        // indices into DirectEquations::coordinates of the excited coordinates (X's order)
  Eigen::VectorXcd x;           // their motion
  Eigen::MatrixXcd noise;       // S, cov x = S S^H in shape
  Eigen::VectorXcd force;       // per model input: F (FRF: the unit vector of input j)
  int nuisance = -1;            // time record: index of its end-term unknowns (a, b for each row), else -1
};

struct DirectEquations {
  std::vector<int> coordinates;  // model coordinates used by any block, in model order
  std::vector<EquationBlock> blocks;
  int nuisance_groups = 0;
  long lines_skipped = 0;         // lines where the output map could not give the coordinates (e.g. w = 0 with
                                  // acceleration outputs)
  std::vector<std::string> notes; // what was used and what was left out, for method_details
};

// Builds the blocks from all data sets at the parameter values `values` (the output map is evaluated there; it must
// not depend on the parameters estimated). Throws FitError, naming the file and the coordinates the outputs do not
// give, when a data set cannot be used.
DirectEquations direct_equations(const Model& model, const std::vector<DataSet>& data, const Eigen::VectorXd& values);

}  // namespace mbgen::methods
