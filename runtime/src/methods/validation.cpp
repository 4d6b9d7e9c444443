#include "validation.hpp"

#include "numerics/polynomial_roots.hpp"
#include "numerics/constants.hpp"

#include <cmath>
#include <limits>

namespace mbgen::methods {

namespace {

using Complex = std::complex<double>;

nlohmann::json number(double x) { return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(nullptr); }

std::vector<Complex> upper(const std::vector<Complex>& roots) {
  std::vector<Complex> out;
  for (const Complex& r : roots)
    if (r.imag() >= 0) out.push_back(r);
  return out;
}

double f_hz(Complex r) { return std::abs(r) / numerics::kTwoPi; }
double zeta(Complex r) { return std::abs(r) > 0 ? -r.real() / std::abs(r) : 1.0; }

// The nearest of `candidates` to r, relative to |r|; index -1 when there are none.
std::pair<int, double> nearest(Complex r, const std::vector<Complex>& candidates) {
  int best = -1;
  double d = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    const double di = std::abs(candidates[i] - r) / std::max(std::abs(r), 1e-300);
    if (di < d) {
      d = di;
      best = static_cast<int>(i);
    }
  }
  return {best, d};
}

nlohmann::json root_json(Complex r) {
  return {{"re", number(r.real())}, {"im", number(r.imag())}, {"f_hz", number(f_hz(r))}, {"zeta", number(zeta(r))}};
}

// Identified roots beside their nearest model roots.
nlohmann::json compare(const std::vector<Complex>& identified, const std::vector<Complex>& model) {
  nlohmann::json a = nlohmann::json::array();
  for (const Complex& r : identified) {
    const auto [i, d] = nearest(r, model);
    nlohmann::json e = {{"identified", root_json(r)}};
    e["model"] = i >= 0 ? root_json(model[static_cast<std::size_t>(i)]) : nlohmann::json(nullptr);
    e["relative_distance"] = number(d);
    a.push_back(e);
  }
  return a;
}

}  // namespace

Validation validate(const StepOneTf& s, const ModelTf& model) {
  Validation v;
  const std::vector<Complex> id_poles = upper(numerics::polynomial_roots(s.tf.denominator));
  const std::vector<Complex> model_poles = upper(numerics::polynomial_roots(model.denominator));
  v.zero_pole["input"] = s.tf.input;
  v.zero_pole["data"] = s.file;
  v.zero_pole["poles"] = compare(id_poles, model_poles);
  nlohmann::json zeros, gains;
  std::vector<std::vector<Complex>> id_zeros;
  for (std::size_t c = 0; c < s.tf.outputs.size(); ++c) {
    // The model's numerator cut to the identified degree (the coefficients above it are structurally zero).
    Eigen::VectorXd mnum = model.numerators[c].head(s.tf.numerators[c].size());
    id_zeros.push_back(numerics::polynomial_roots(s.tf.numerators[c]));
    zeros[s.tf.outputs[c]] = compare(upper(id_zeros.back()), upper(numerics::polynomial_roots(mnum)));
    const double g_id = s.tf.denominator[0] != 0 ? s.tf.numerators[c][0] / s.tf.denominator[0] : NAN;
    const double g_m = model.denominator[0] != 0 ? mnum[0] / model.denominator[0] : NAN;
    gains[s.tf.outputs[c]] = {{"identified", number(g_id)}, {"model", number(g_m)}};
  }
  v.zero_pole["zeros"] = zeros;
  v.zero_pole["dc_gain"] = gains;

  nlohmann::json poles = nlohmann::json::array();
  for (const Complex& p : id_poles) {
    std::vector<std::string> findings;
    if (p.real() >= 0) findings.push_back("unstable");
    if (std::abs(p.imag()) <= 1e-9 * std::abs(p)) findings.push_back("real: not a vibration mode");
    else if (zeta(p) > 0.3) findings.push_back("overdamped (zeta above 0.3)");
    if (f_hz(p) < s.band_lo_hz || f_hz(p) > s.band_hi_hz) findings.push_back("outside the band the data cover");
    if (nearest(p, model_poles).second > 0.05) findings.push_back("no model counterpart within 5 %");
    int cancelled = 0;
    for (std::size_t c = 0; c < id_zeros.size(); ++c) {
      double d = std::numeric_limits<double>::infinity();
      for (const Complex& z : id_zeros[c]) d = std::min({d, std::abs(z - p), std::abs(z - std::conj(p))});
      if (d < std::abs(p.real())) {
        ++cancelled;
        findings.push_back("near-cancelled by a zero in " + s.tf.outputs[c]);
      }
    }
    if (cancelled == static_cast<int>(id_zeros.size()) && cancelled > 0)
      findings.push_back("cancelled in every channel: the data cannot determine it");
    if (!findings.empty()) ++v.suspect_poles;
    poles.push_back({{"f_hz", number(f_hz(p))}, {"zeta", number(zeta(p))}, {"findings", findings},
                     {"verdict", findings.empty() ? "valid" : "suspect"}});
  }
  v.checks = {{"data", s.file}, {"input", s.tf.input}, {"poles", poles},
              {"verdict", v.suspect_poles ? "suspect: " + std::to_string(v.suspect_poles) + " of " +
                                                std::to_string(id_poles.size()) + " poles fail a check"
                                          : "valid: every identified pole passes the checks"}};
  return v;
}

}  // namespace mbgen::methods
