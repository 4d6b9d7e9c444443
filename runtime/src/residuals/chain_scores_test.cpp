#include <catch2/catch.hpp>

#include <cmath>
#include <random>

#include <mbgen/residuals/chain_scores.hpp>

using namespace mbgen;

namespace {

// A channel whose model is a resonance and whose data are `factor` times it plus complex noise of std sigma.
ChannelResidual channel(const std::string& name, double factor, double sigma, std::mt19937_64& rng,
                        double resonance_hz = 100) {
  ChannelResidual c;
  c.channel = name;
  c.data_set = "d.csv";
  const int n = 400;
  c.measured.resize(n);
  c.model.resize(n);
  c.sigma = Eigen::VectorXd::Constant(n, sigma);
  std::normal_distribution<double> noise(0, sigma / std::sqrt(2.0));
  for (int k = 0; k < n; ++k) {
    const double f = 10 + k;
    c.f_hz.push_back(f);
    const std::complex<double> s(0, 2 * M_PI * f);
    const double w0 = 2 * M_PI * resonance_hz;
    c.model[k] = 1.0 / (s * s + 0.05 * w0 * s + w0 * w0) * w0 * w0;
    c.measured[k] = factor * c.model[k] + std::complex<double>(noise(rng), noise(rng));
  }
  return c;
}

bool all(const std::string&) { return true; }

}  // namespace

TEST_CASE("gain_score recovers a channel's factor and sees no error where there is none") {
  std::mt19937_64 rng(7);
  const std::vector<ChannelResidual> calibrated{channel("y/F", 0.8, 0.01, rng)};
  const GainScore off = gain_score(calibrated, all);
  CHECK(off.lines == 400);
  CHECK(std::abs(off.factor - 0.8) < 4 * off.factor_std);
  CHECK(off.factor_std < 0.01);
  CHECK(off.statistic > 1000);

  const std::vector<ChannelResidual> reversed{channel("y/F", -1.0, 0.01, rng)};
  CHECK(gain_score(reversed, all).factor == Approx(-1.0).margin(0.01));

  // Without an error the statistic is chi-square with one degree of freedom: over 200 draws its mean is near 1.
  double sum = 0;
  for (int draw = 0; draw < 200; ++draw) sum += gain_score({channel("y/F", 1.0, 0.01, rng)}, all).statistic;
  CHECK(sum / 200 == Approx(1.0).margin(0.3));
}

TEST_CASE("gain_score takes only the selected channels") {
  std::mt19937_64 rng(8);
  const std::vector<ChannelResidual> channels{channel("a/F", 1.0, 0.01, rng), channel("b/F", 1.25, 0.01, rng)};
  const GainScore a = gain_score(channels, [](const std::string& c) { return c == "a/F"; });
  const GainScore b = gain_score(channels, [](const std::string& c) { return c == "b/F"; });
  CHECK(std::abs(a.factor - 1.0) < 4 * a.factor_std);
  CHECK(std::abs(b.factor - 1.25) < 4 * b.factor_std);
  CHECK(gain_score(channels, [](const std::string&) { return false; }).lines == 0);
}

TEST_CASE("driving_point_passivity: a passive driving point takes in power, a reversed one gives it out") {
  std::mt19937_64 rng(11);
  const ChannelResidual c = channel("d1/F1", 1.0, 0.01, rng);  // a receptance: Im H <= 0
  const PassivityCheck right = driving_point_passivity(c.measured, c.sigma, 0);
  CHECK(right.lines > 50);
  CHECK(right.against_share < 0.02);
  const PassivityCheck reversed = driving_point_passivity(-c.measured, c.sigma, 0);
  CHECK(reversed.against_share > 0.98);
  // The same data as a mobility (times i w) and an accelerance (times -w^2).
  Eigen::VectorXcd mobility(c.measured.size()), accelerance(c.measured.size());
  Eigen::VectorXd sigma_v(c.measured.size()), sigma_a(c.measured.size());
  for (Eigen::Index k = 0; k < c.measured.size(); ++k) {
    const double w = 2 * M_PI * c.f_hz[static_cast<std::size_t>(k)];
    mobility[k] = std::complex<double>(0, w) * c.measured[k];
    accelerance[k] = -w * w * c.measured[k];
    sigma_v[k] = w * c.sigma[k];
    sigma_a[k] = w * w * c.sigma[k];
  }
  CHECK(driving_point_passivity(mobility, sigma_v, 1).against_share < 0.02);
  CHECK(driving_point_passivity(accelerance, sigma_a, 2).against_share < 0.02);
  CHECK(driving_point_passivity(-accelerance, sigma_a, 2).against_share > 0.98);
  // Noise alone decides nothing: no line stands out.
  CHECK(driving_point_passivity(Eigen::VectorXcd::Zero(10), Eigen::VectorXd::Constant(10, 1.0), 0).lines == 0);
}

TEST_CASE("swap_gain is large when two outputs' data are exchanged, negative when they are right") {
  std::mt19937_64 rng(9);
  ChannelResidual a = channel("a/F", 1.0, 0.01, rng, 100), b = channel("b/F", 1.0, 0.01, rng, 180);
  CHECK(swap_gain({a, b}, "a", "b") < -100);
  std::swap(a.measured, b.measured);
  CHECK(swap_gain({a, b}, "a", "b") > 100);
  CHECK(swap_gain({a, b}, "b", "a") > 100);
  CHECK(swap_gain({a, b}, "a", "c") == 0);
}

TEST_CASE("form_gain finds data given as another form of the quantity, and nothing where the form is right") {
  std::mt19937_64 rng(11);
  // The data of y are a mobility, i w times the receptance the model has (written out here, 1 % noise of the peak).
  ChannelResidual mobility = channel("y/F", 1.0, 0.01, rng);
  ChannelResidual as_model = channel("z/F", 1.0, 0.01, rng);
  for (Eigen::Index k = 0; k < mobility.measured.size(); ++k) {
    const std::complex<double> iw(0, 2 * M_PI * mobility.f_hz[static_cast<std::size_t>(k)]);
    mobility.measured[k] = iw * mobility.model[k] + (mobility.measured[k] - mobility.model[k]) * std::abs(iw);
    mobility.sigma[k] *= std::abs(iw);
  }
  const std::vector<ChannelResidual> channels{mobility, as_model};
  const double log_n = std::log(2.0 * 2 * 400);
  CHECK(form_gain(channels, "y", 1) > 1000 * log_n);  // a velocity: far better
  for (int d : {-2, -1, 2}) CHECK(form_gain(channels, "y", d) < form_gain(channels, "y", 1));  // the right form wins
  // z's data are what the model says: no other form fits better by the price of a parameter.
  for (int d : {-2, -1, 1, 2}) CHECK(form_gain(channels, "z", d) < log_n);
  CHECK(form_gain(channels, "nosuch", 1) == 0);
  // The magnitude's trend shows the form even where the model's resonance lies elsewhere (6 % off, where chi^2
  // compares misplaced peaks): one decade per decade for a mobility against a receptance, none for z.
  std::mt19937_64 other(12);
  std::vector<ChannelResidual> misplaced = channels;
  misplaced[0].model = channel("y/F", 1.0, 0.01, other, 106).model;
  CHECK(magnitude_slope(misplaced, "y") == Approx(1.0).margin(0.15));
  CHECK(std::abs(magnitude_slope(channels, "z")) < 0.05);
  CHECK(std::isnan(magnitude_slope(channels, "nosuch")));
}
