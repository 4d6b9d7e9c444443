// Output filters (`filter` statements): signal conditioning between a sensor and the recorded output.
//
// Each filter is a transfer function T(s) = (b2 s^2 + b1 s + b0) / (s^2 + a1 s + a0) from the output's signal
// y_in (the sensor's reading, or the previous filter's output) to what is recorded. It is realised with one new
// coordinate w per second-order section, which moves no mass:
//
//     w'' + a1 w' + a0 w = y_in,      y_out = b2 y_in + (b1 - b2 a1) w' + (b0 - b2 a0) w,
//
// so that the model keeps the form M q'' + C q' + K q = B u, y = Cd q + Cv q' + Ca q'' (the rows of y_in enter
// w's equation with the opposite sign: M, C and K are no longer symmetric) and everything downstream (transfer
// functions, emitted code, FRFs, simulation, estimation) works unchanged, in exact arithmetic.
//
//   lowpass2  cutoff fc damping z:  b = (wc^2, 0, 0), a = (wc^2, 2 z wc)
//   highpass2 cutoff fc damping z:  b = (0, 0, 1),    a = (wc^2, 2 z wc)
//   highpass1 cutoff fc:  s/(s + wc) = s (s + 2 wc) / ((s + wc)(s + 2 wc)): a first-order filter in a second-order
//             section; the pole at -2 wc cancels exactly against a zero (a cancellation the transfer functions
//             report), chosen so that the section's poles are distinct.
//   delay time tau sections N:  N second-order Pade sections of tau/N each,
//             (s^2 - 6 s/t + 12/t^2)/(s^2 + 6 s/t + 12/t^2), t = tau/N: all-pass, with a phase error under 1 %
//             for w t < 1.7 (0.13 % at w t = 1): accurate for w tau < 1.7 N.
#pragma once

#include "symbolic/symbolic_model.hpp"
#include "symbolic/to_ginac.hpp"

namespace mbgen::symbolic {

// Appends the filter states to `out`'s coordinates and matrices and rewrites the filtered outputs' rows.
void add_output_filters(const ParameterTable& params, SymbolicModel& out);

}  // namespace mbgen::symbolic
