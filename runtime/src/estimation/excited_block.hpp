// The part of a model one data set can see, for the output-error residuals. Internal header.
//
// Only coordinates coupled to the measured inputs affect the measured outputs: if P = K + jw C - w^2 M is block
// diagonal (after permutation), X = P^-1 B vanishes outside the blocks that B's columns touch, so H = Cout X and
// its derivative dH = dCout X - Y dP X + Y dB (Y = Cout P^-1) involve only those blocks. The block structure is
// taken from the non-zero pattern of M, C, K *and* of the derivative entries of M, C, K (a parameter whose
// derivative would couple two blocks keeps them together, so the reduction is exact for the Jacobian too).
// The spindle's x-direction data thus needs only its 5-DOF x / ry / rz block instead of all 11 coordinates.
//
// The reduced problem also keeps only the inputs and outputs in use and renumbers the derivative entries to the
// Jacobian's columns, dropping parameters that are not wanted.
#pragma once

#include "mbgen/model.hpp"

#include <vector>

namespace mbgen::estimation {

struct ReducedModel {
  ModelMatrices m;
  ModelDerivatives d;            // param = Jacobian column
  std::vector<int> coordinates;  // model coordinate of each reduced coordinate
};

// `inputs`, `outputs`: model indices kept, in this order (reduced B has inputs.size() columns, Cd etc.
// outputs.size() rows). `column[p]` is the Jacobian column of model parameter p, or -1 (entries dropped);
// parameters beyond column.size() are dropped too. `d` may be null (no derivatives wanted).
// Throws FitError if a derivative entry lies outside its matrix.
ReducedModel reduce_to_excited_block(const ModelMatrices& m, const ModelDerivatives* d, const std::vector<int>& inputs,
                                     const std::vector<int>& outputs, const std::vector<int>& column);

}  // namespace mbgen::estimation
