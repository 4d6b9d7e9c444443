// Candidates that are one and the same model: fitted once.
//
// Several candidates can be the same function of their parameter vectors: one of two mirror-image mounts untied
// (on either side), a moment stiffness at any of four identical mounts. Fitting each would repeat the same fit.
// Two models are taken to be the same when their parameters agree position by position in everything but the
// name (value, role, unit, bounds), they have the same inputs and outputs, and their FRFs agree at random points:
// three random parameter vectors around the defaults, each at eight frequencies across the data's band. The FRF
// is a rational function of the parameters and of s; two different rational functions agree at random points
// only by coincidence, so this is a randomized identity test.
#pragma once

#include <mbgen/estimation/fit.hpp>
#include <mbgen/model.hpp>

#include <set>
#include <string>
#include <vector>

namespace mbgen {

// Eight probe frequencies spread (logarithmically) over the band the data cover: FRF lines, or from the record
// length's reciprocal to 0.4 times the sample rate.
std::vector<double> probe_frequencies(const std::vector<DataSet>& data);

// Whether `a` and `b` give the same fit on any data: parameters alike position by position (a differing name
// only where it is not in `names_in_use`: names a fit looks up, its start values and the data sets' `# set`
// values), the same signals, and the same FRF at the probes (to 1e-8 of the largest magnitude of a channel).
// A probe that cannot be evaluated (a singular dynamic stiffness) counts as a difference.
bool same_response(const Model& a, const Model& b, const std::vector<double>& probe_hz,
                   const std::set<std::string>& names_in_use);

}  // namespace mbgen
