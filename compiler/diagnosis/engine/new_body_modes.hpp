// Whether the data show a resonance of the bodies a candidate adds (Extension::resonating_bodies): a compliant
// ground or a resonator explains the data by a new body's own mode, and a body whose mode nothing in the data shows
// is not evidenced by them. A heavy base on a support damped near or beyond critical adds no peak; what it fits is
// a support whose stiffness changes with frequency, which other mechanisms give as well (a Maxwell element: a
// spring in series with a damper).
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include <mbgen/model.hpp>
#include <mbgen/residuals/residual_analysis.hpp>

namespace mbgen::diagnosis {

struct NewBodyMode {
  bool oscillating = false;  // false: the bodies' modes are all overdamped (real eigenvalues)
  double f_hz = 0, zeta = 0;
  double share = 0;     // its term's share of the response at its frequency, |term| / |H|, on `channel`
  std::string channel;  // the measured channel that sees it best ("OUTPUT/INPUT"); empty when none in band
};

// The bodies' modes are the modes whose kinetic energy lies most in the bodies' coordinates, as many as they have
// coordinates. Of those that oscillate, the one a measured channel (`channels`, over its frequency range) sees
// best: the largest share of that channel's response at the mode's frequency. `p`: the model's parameter values.
NewBodyMode best_seen_new_body_mode(const Model& model, const Eigen::VectorXd& p, const std::vector<std::string>& bodies,
                                    const std::vector<ChannelResidual>& channels);

}  // namespace mbgen::diagnosis
