// Step one of the two-step method from a time record: an ARX model by least squares, its order chosen by an
// information criterion, its poles pruned to the model's order, the residues of the kept poles fitted to the
// record. Internal header.
//
//   A(q) y_o(k) = B_o(q) u(k) + e_o(k),  A common to the outputs (one input's channels share their poles),
//   B_o with lags 1..n for a zero-order hold (y(k) is sampled before u(k) acts) or 0..n for `# hold=none`.
//
// All orders n = q .. max_order come from one Householder QR of the regressor matrix of the highest order: the
// columns are ordered by lag, so the leading columns are the lower order's regressors and its residual is
// |y|^2 - |(Q^T y)_1..p|^2 (order-recursive least squares). AIC = N ln(RSS/N) + 2p, BIC = N ln(RSS/N) + p ln N,
// FPE = RSS/N (N + p)/(N - p), N real equations, p coefficients (thesis Sec. 4.7).
//
// ARX is biased when the noise is on the output (the equation error is then coloured: A(q) v(k)); a high order
// lets A whiten it, at the price of phantom poles (thesis Sec. 3.6.2, 4.7). The poles of the chosen model are
// mapped to continuous time (lambda = ln z / dt) and pruned by the thesis's rules: unstable, real (no
// vibration), overdamped (rule 3), above the band the sampling supports (rule 1), cancelled by a zero in every
// channel (rule 2); of the rest, the model's q/2 most dominant pairs are kept (dominance: a pole's peak
// contribution |r| / |Re lambda| relative to the channel's largest). The residues of the kept poles are then fitted
// to the record by linear least squares (each pole's response to the record's input, under the record's hold,
// simulated exactly), constrained to the model's numerator degree; continuous-time coefficients follow.
#pragma once

#include "identified_tf.hpp"

#include <Eigen/Core>

#include <complex>
#include <functional>
#include <string>
#include <vector>

namespace mbgen::methods {

struct ArxOptions {
  int max_order = 40;            // the thesis's ARMAX order
  std::string criterion = "aic";  // "aic", "bic" or "fpe"
  double max_zeta = 0.3;         // rule 3: more damping than a mechanical mode shows
  double band_fraction = 0.4;    // rule 1: poles above this fraction of the sample rate
  double cancellation = 1.0;     // rule 2: a zero within this many |Re lambda| of the pole, in every channel
};

struct ArxOrder {
  int order = 0;
  long parameters = 0;
  double rss = 0, aic = 0, bic = 0, fpe = 0;
};

struct ArxPole {
  std::complex<double> lambda;  // continuous time, rad/s (the member with Im >= 0)
  double f_hz = 0, zeta = 0;
  double dominance = 0;         // 0 .. 1
  double nearest_zero = 0;      // smallest over channels of min |zero - lambda| / |Re lambda|
  bool kept = false;
  std::vector<std::string> findings;  // why it was pruned
};

struct ArxIdentification {
  std::string model = "ARX";  // or "ARMAX" (armax.hpp), in messages
  IdentifiedTf tf;
  std::vector<ArxOrder> orders;
  int selected_order = 0;
  std::vector<ArxPole> poles;  // of the selected model, by frequency
  double residue_nrmse = 0;    // of the kept poles' fit to the record
  long samples = 0;
};

// u: the input; y: per output; dt the sample interval; q the model's order (even); numerator_degree per output: the
// model's. Throws std::invalid_argument (a message for the user) when the record is too short or shows no mode, and
// std::logic_error (a bug of the caller) for arguments that break these rules.
ArxIdentification identify_arx(const Eigen::VectorXd& u, const std::vector<Eigen::VectorXd>& y,
                               const std::vector<std::string>& outputs, const std::string& input, double dt,
                               bool first_order_hold, int q, const std::vector<int>& numerator_degree,
                               const ArxOptions& options = {});

// The part after the regression, shared with ARMAX (armax.hpp): the poles of A(z) (ascending in z, monic, degree n)
// mapped to continuous time and pruned, using the zeros of each B_o(z) (ascending, degree at most n, physical
// units) for rule 2; the kept poles' residues fitted to the record; fills out.tf, out.poles, out.residue_nrmse.
// With `pole_covariance` (the covariance of the kept poles' Re and Im, pole by pole, given their continuous-time
// values), also out.tf.covariance: the poles' covariance through the fit plus the residues' given the poles. Throws
// std::invalid_argument when no pole is kept.
using PoleCovariance = std::function<Eigen::MatrixXd(const std::vector<std::complex<double>>& lambda)>;
void prune_and_fit_residues(const Eigen::VectorXd& A, const std::vector<Eigen::VectorXd>& B, const Eigen::VectorXd& u,
                            const std::vector<Eigen::VectorXd>& y, const std::vector<std::string>& outputs,
                            const std::string& input, double dt, bool first_order_hold, int q,
                            const std::vector<int>& numerator_degree, const ArxOptions& options,
                            ArxIdentification& out, const PoleCovariance& pole_covariance = {});

}  // namespace mbgen::methods
