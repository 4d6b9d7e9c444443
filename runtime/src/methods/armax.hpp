// Step one of the two-step method from a time record by ARMAX (thesis Sec. 2.2, Table 2.2; Sec. 3.6.2: its
// 40th-order ARMAX): the prediction-error method. Internal header.
//
//   A(q) y_o(k) = B_o(q) u(k) + C(q) e_o(k),   A and C common to the outputs, monic, degree n; B_o with lags 1..n
//   (zero-order hold) or 0..n (`# hold=none`); e_o white.
//
// Why ARMAX: noise on the outputs, y = (B/A) u + v, is an ARMAX process with C = A and e = v, so ARMAX is unbiased
// where ARX (C = 1) is not. For a lightly damped structure C's roots are then at |z| ~ 1 - zeta w dt (mdof2's
// second mode at 4096 Hz: 0.9999): the one-step predictor e = (A y - B u) / C is a filter that hardly decays.
// Extended least squares and Hannan-Rissanen regress on the estimated innovations and do not converge there; the
// prediction-error method minimises sum e^2 directly by Levenberg-Marquardt with the exact gradient
//
//   de_o/da_l = y_o(k-l) / C,  de_o/db_o,l = -u(k-l) / C,  de_o/dc_l = -e_o(k-l) / C   (filtered regressors),
//
// and keeps C minimum-phase by reflecting a root outside the unit circle to 1 / conj(z) after every step (the
// predictor then stays stable; the cost, which the step must lower, decides). Pre-sample values are zero: a record
// starts at rest (docs/data.md), so with output noise the predictor at the truth gives e = v exactly from k = 0.
// Outputs are weighted by their RMS (noise proportional to the signal, as the output-error fit assumes).
//
// Each order n = q .. q + extra_orders is fitted from deterministic starts: ARX(n) with C = 1; ARX(n) with C = A
// (the output-noise structure); Hannan-Rissanen (a long ARX's residuals as the innovations, then least squares with
// their lags); and for n > q the order n - 1 optimum with a zero lag appended (the same predictor, so the criterion
// can only fall). The lowest cost wins; AIC, BIC or FPE choose the order as for ARX (arx.hpp), with p the
// coefficients of A, B and C. The chosen A and B are then pruned and their residues fitted to the record exactly as
// the ARX path does (arx.hpp, prune_and_fit_residues).
#pragma once

#include "arx.hpp"

#include <Eigen/Core>

#include <complex>
#include <string>
#include <vector>

namespace mbgen::methods {

struct ArmaxOptions {
  int extra_orders = 2;           // orders q .. q + extra_orders
  std::string criterion = "aic";  // "aic", "bic" or "fpe"
  int max_iterations = 100;       // Levenberg-Marquardt iterations per start
  int long_arx_order = 20;        // Hannan-Rissanen's first step: at least this and 2n
  int threads = 1;                // the starts' searches run in parallel (the result does not depend on it)
};

// One order's prediction-error estimate, in physical units.
struct ArmaxEstimate {
  int order = 0;
  int first_lag = 1;                 // 1: zero-order hold; 0: first-order hold (`# hold=none`)
  Eigen::VectorXd a, c;              // a_1 .. a_n, c_1 .. c_n (A(q) = 1 + a_1 q^-1 + ...)
  std::vector<Eigen::VectorXd> b;    // per output b_first_lag .. b_n
  // Covariance of [a, b_0 (all lags), b_1, ..., c]: s^2 (J^T J)^-1 at the optimum, s^2 = cost / (N - p), N the real
  // prediction errors (outputs x samples), in physical units.
  Eigen::MatrixXd covariance;
  long parameters = 0;
  double cost = 0;                   // sum over outputs of sum e_o^2 / RMS(y_o)^2
  double aic = 0, bic = 0, fpe = 0;
  int iterations = 0;
  bool converged = false;
  std::string start;                 // which start reached the lowest cost
  std::vector<std::pair<std::string, double>> start_costs;
  // A in the search's second-order sections (armax.cpp: floor(n/2) of 1 + s_1 q^-1 + s_2 q^-2, then for odd n one of
  // 1 + s_1 q^-1) and their covariance: a section is a pole pair, so its covariance is the poles'.
  Eigen::VectorXd a_sections;
  Eigen::MatrixXd a_section_covariance;
  double largest_c_root = 0;         // |z| of C's root nearest the unit circle
  int reflections = 0;               // C roots reflected into the unit circle during the winning search

  // Ascending polynomials in z of degree n (A monic; B_o(z) = sum_l b_o,l z^(n-l)), as arx.hpp uses them.
  Eigen::VectorXd a_polynomial() const;
  Eigen::VectorXd b_polynomial(std::size_t output) const;
  Eigen::VectorXd c_polynomial() const;
};

// The prediction-error fit of one order n from the starts above (`previous`: the order n - 1 estimate, or null;
// `poles`: continuous-time poles, one per pair, for the output-error start at sample interval dt, or none).
// u and y in physical units, sampled on one grid from rest.
ArmaxEstimate estimate_armax(const Eigen::VectorXd& u, const std::vector<Eigen::VectorXd>& y, int n,
                             bool first_order_hold, const ArmaxOptions& options = {},
                             const ArmaxEstimate* previous = nullptr,
                             const std::vector<std::complex<double>>& poles = {}, double dt = 0);

struct ArmaxIdentification {
  ArxIdentification id;                // the transfer function, orders table (rss = cost), poles, residue fit
  std::vector<ArmaxEstimate> estimates;  // per order tried
  int selected = 0;                    // index into estimates
};

// As identify_arx (arx.hpp), by ARMAX. Throws std::invalid_argument (a message for the user) when the record is too
// short (20 prediction errors per coefficient at order q) or shows no mode.
ArmaxIdentification identify_armax(const Eigen::VectorXd& u, const std::vector<Eigen::VectorXd>& y,
                                   const std::vector<std::string>& outputs, const std::string& input, double dt,
                                   bool first_order_hold, int q, const std::vector<int>& numerator_degree,
                                   const ArmaxOptions& options = {}, const ArxOptions& pruning = {});

}  // namespace mbgen::methods
