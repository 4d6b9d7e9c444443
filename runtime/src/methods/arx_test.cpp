// The order criteria of step one's ARX model from records (arx.hpp), on a record made here by a path independent of
// the code under test: a two-mode discrete-time system driven by a random +-1 input with coloured noise,
// A(q) y = B(q) u + C(q) e, simulated by its difference equation.
#include "arx.hpp"
#include "polynomial.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <complex>
#include <random>

using namespace mbgen::methods;

namespace {

struct Record {
  Eigen::VectorXd u, y;
  std::vector<std::complex<double>> lambda;  // continuous-time poles, Im > 0
};

constexpr double kDt = 0.01;

Record armax_record(unsigned seed, double noise) {
  // Modes at 4 and 11 Hz, 5 % and 3 % damping.
  Record r;
  for (auto [f, zeta] : {std::pair{4.0, 0.05}, std::pair{11.0, 0.03}}) {
    const double w = 2 * M_PI * f;
    r.lambda.push_back({-zeta * w, w * std::sqrt(1 - zeta * zeta)});
  }
  std::vector<std::complex<double>> z;
  for (auto l : r.lambda) {
    z.push_back(std::exp(l * kDt));
    z.push_back(std::conj(std::exp(l * kDt)));
  }
  const Eigen::VectorXcd Az = poly_from_roots(z);  // ascending in z: a_4 .. a_0 = 1 at the top
  double a[5];
  for (int l = 0; l <= 4; ++l) a[l] = Az[4 - l].real();  // a[0] = 1
  const double b[5] = {0, 0.02, -0.01, 0.015, 0.0};       // B(q) = b1 q^-1 + b2 q^-2 + b3 q^-3
  const double c[5] = {1, -0.6, 0.45, -0.2, 0.1};         // C(q): roots well inside the unit circle
  std::mt19937 rng(seed);
  std::normal_distribution<double> gauss(0, 1);
  std::bernoulli_distribution coin(0.5);
  const Eigen::Index N = 8000;
  r.u.resize(N);
  r.y.resize(N);
  Eigen::VectorXd e(N);
  for (Eigen::Index k = 0; k < N; ++k) {
    r.u[k] = coin(rng) ? 1 : -1;
    e[k] = noise * gauss(rng);
    double v = 0;
    for (int l = 1; l <= 4; ++l) {
      if (k - l < 0) break;
      v += -a[l] * r.y[k - l] + b[l] * r.u[k - l] + c[l] * e[k - l];
    }
    r.y[k] = v + e[k];
  }
  return r;
}

double criterion_value(const ArxOrder& row, const std::string& criterion) {
  return criterion == "bic" ? row.bic : criterion == "fpe" ? row.fpe : row.aic;
}

}  // namespace

TEST_CASE("the order criteria behave as documented", "[two-step][arx][criteria]") {
  const Record r = armax_record(4, 0.05);
  int order[3];
  const char* names[3] = {"bic", "fpe", "aic"};
  for (int c = 0; c < 3; ++c) {
    ArxOptions o;
    o.max_order = 30;
    o.criterion = names[c];
    const ArxIdentification id = identify_arx(r.u, {r.y}, {"y"}, "u", kDt, false, 4, {3}, o);
    order[c] = id.selected_order;
    // The table: AIC = N ln(RSS/N) + 2p, BIC = N ln(RSS/N) + p ln N, FPE = RSS/N (N+p)/(N-p), N the equations.
    const double N = double(r.u.size() - 30);
    for (const ArxOrder& row : id.orders) {
      const double p = double(row.parameters);
      CHECK(row.aic == Approx(N * std::log(row.rss / N) + 2 * p));
      CHECK(row.bic == Approx(N * std::log(row.rss / N) + p * std::log(N)));
      CHECK(row.fpe == Approx(row.rss / N * (N + p) / (N - p)));
    }
    // The selected order minimises the criterion.
    for (const ArxOrder& row : id.orders)
      CHECK(criterion_value(row, names[c]) >= criterion_value(id.orders[static_cast<std::size_t>(id.selected_order - 4)], names[c]));
  }
  // BIC's penalty p ln N exceeds FPE's (N ln((N+p)/(N-p)) = 2p + O(p^3/N^2)), which exceeds AIC's 2p, and each grows
  // faster with p: on one table the orders they choose can only fall in that order.
  CHECK(order[0] <= order[1]);
  CHECK(order[1] <= order[2]);
  INFO("orders: BIC " << order[0] << ", FPE " << order[1] << ", AIC " << order[2]);
  CHECK(order[0] < order[2]);  // coloured noise: AIC keeps adding lags to whiten it, BIC stops sooner
}
