#include "mbgen/residuals/channel_residuals.hpp"

#include <mbgen/dynamics/frf.hpp>
#include <mbgen/data/frf_noise.hpp>
#include <mbgen/data/welch.hpp>

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <tuple>

#include <mbgen/residuals/data_split.hpp>

namespace mbgen {

namespace {

Eigen::VectorXd with_set_values(const Model& model, const DataSet& d, Eigen::VectorXd values) {
  for (const auto& [name, v] : d.set()) {
    const int i = model.info().parameter_index(name);
    if (i >= 0) values[i] = v.value;
  }
  return values;
}

// A record's FRFs by Welch H1 with segments of ~1 s (at least 8 averages), the hold's half-sample delay removed
// so that they compare with the continuous-time model.
WelchOptions record_welch_options(const TimeRecord& rec) {
  WelchOptions o;
  Eigen::Index length = 256;
  while (length * 2 <= rec.samples() / 8) length *= 2;
  o.segment_length = length;
  o.compensate_hold = rec.hold == HoldMode::ZeroOrder;
  return o;
}

WelchEstimate record_frfs(const Model& model, const TimeRecord& rec) {
  std::vector<std::string> inputs, outputs;
  for (const std::string& in : model.info().inputs)
    if (rec.find(in)) inputs.push_back(in);
  for (const std::string& out : model.info().outputs)
    if (rec.find(out)) outputs.push_back(out);
  return welch_h1(rec, inputs, outputs, record_welch_options(rec));
}

// A record's noise level per line: the variance of the residual's H1, averaged over five lines (noise is smooth
// across lines; one line's estimate scatters like a chi-square of ~2 x segments degrees of freedom).
Eigen::VectorXd record_sigma(const Eigen::VectorXd& variance, const Eigen::VectorXcd& measured, double floor) {
  const Eigen::Index n = variance.size();
  const double rms = std::sqrt(measured.cwiseAbs2().mean());
  Eigen::VectorXd sigma(n);
  for (Eigen::Index k = 0; k < n; ++k) {
    const Eigen::Index lo = std::max<Eigen::Index>(0, k - 2), hi = std::min<Eigen::Index>(n - 1, k + 2);
    sigma[k] = std::max(std::sqrt(variance.segment(lo, hi - lo + 1).mean()), floor * rms);
  }
  return sigma;
}

// The degrees of freedom of record_sigma's five-line mean of a variance of `per_line` degrees of freedom whose
// neighbouring lines correlate as `rho` (a power's correlation: |c_j|^2, the same numbers as H1's errors'):
// per_line x 25 / sum over the 5 x 5 pairs of their correlation.
double five_line_dof(double per_line, const std::vector<double>& rho) {
  double pairs = 0;
  for (int i = 0; i < 5; ++i)
    for (int j = 0; j < 5; ++j) {
      const std::size_t lag = static_cast<std::size_t>(std::abs(i - j));
      pairs += lag == 0 ? 1.0 : lag <= rho.size() ? rho[lag - 1] : 0.0;
    }
  return per_line * 25.0 / pairs;
}

// Judges only the lines where the measured response stands out of the noise, by the same measure as an ordinary
// coherence of 0.8 (|H|^2 at least 4 times the noise power, sigma^2 times the segments), but with the residual's
// noise level, which leakage does not inflate: a lightly damped resonance is judged, where the measured coherence
// (0.4-0.5 at a spindle mode in 1 s records) would drop it. Where noise dominates, H1 and the noise level are both
// noise: with the Hann window's correlated neighbours a 5-line mean of z passes 4 about once per thousand windows,
// and a 1 s spindle control record, all of whose ~460 lines above 2.4 kHz are noise, showed such a finding.
// Keeps the lines where `judged(k)` holds.
template <class Judged>
void keep_lines(ChannelResidual& r, Judged judged) {
  std::vector<double> f;
  std::vector<Eigen::Index> kept;
  for (Eigen::Index k = 0; k < r.measured.size(); ++k)
    if (judged(k)) kept.push_back(k);
  const auto n = static_cast<Eigen::Index>(kept.size());
  r.lines_not_judged += r.measured.size() - n;
  Eigen::VectorXcd measured(n), model(n);
  Eigen::VectorXd sigma(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const Eigen::Index k = kept[static_cast<std::size_t>(i)];
    f.push_back(r.f_hz[static_cast<std::size_t>(k)]);
    measured[i] = r.measured[k];
    model[i] = r.model[k];
    sigma[i] = r.sigma[k];
  }
  r.f_hz = std::move(f);
  r.measured = std::move(measured);
  r.model = std::move(model);
  r.sigma = std::move(sigma);
}

// Judges only the lines where the measured response stands out of the noise, by the same measure as an ordinary
// coherence of 0.8 (|H|^2 at least 4 times the noise power, sigma^2 times the segments), but with the residual's
// noise level, which leakage does not inflate: a lightly damped resonance is judged, where the measured coherence
// (0.4-0.5 at a spindle mode in 1 s records) would drop it. Where noise dominates, H1 and the noise level are both
// noise: with the Hann window's correlated neighbours a 5-line mean of z passes 4 about once per thousand windows,
// and a 1 s spindle control record, all of whose ~460 lines above 2.4 kHz are noise, showed such a finding.
void keep_record_lines_above_noise(ChannelResidual& r, double segments) {
  keep_lines(r, [&](Eigen::Index k) { return std::norm(r.measured[k]) >= 4.0 * segments * r.sigma[k] * r.sigma[k]; });
}

// A measured FRF is judged where the data stand out of the noise: where their power averaged over nine lines is at
// least 4 times the noise's (6 dB, the measure of a coherence of 0.8). Below, the data are noise (an accelerance at
// a few Hz, a deep anti-resonance): nothing there can be a finding, and a noise wiggle is no peak to start a new
// mode at. The average matters: choosing single lines by their own |h| would keep, among noise-only lines, just
// those the noise made large, and against a model near zero they would read as findings (2 % of noise lines pass
// |h| >= 2 sigma; nine lines' mean power passes 4 sigma^2 about once in 10^9). The lines depend on the data
// alone, so that every model is judged on the same lines.
// The model's own prediction variance is added to sigma only after the lines are chosen (`extra_variance`).
void keep_frf_lines_above_noise(ChannelResidual& r, const Eigen::VectorXd& extra_variance) {
  const Eigen::Index n = r.measured.size();
  std::vector<bool> judged(static_cast<std::size_t>(n));
  for (Eigen::Index k = 0; k < n; ++k) {
    const Eigen::Index lo = std::max<Eigen::Index>(0, k - 4), hi = std::min<Eigen::Index>(n - 1, k + 4);
    double power = 0, noise = 0;
    for (Eigen::Index j = lo; j <= hi; ++j) power += std::norm(r.measured[j]), noise += r.sigma[j] * r.sigma[j];
    judged[static_cast<std::size_t>(k)] = power >= 4.0 * noise;
  }
  if (extra_variance.size() == n) r.sigma = (r.sigma.array().square() + extra_variance.array()).sqrt().matrix();
  keep_lines(r, [&](Eigen::Index k) { return judged[static_cast<std::size_t>(k)]; });
}

// The noise level of each measured FRF channel, estimated once per call: it depends on the data alone, and both the
// prediction variance's Fisher information and the judging use it.
class NoiseLevels {
 public:
  const FrfNoise& of(const DataSet& d, const FrfData& frf, const FrfChannel& c) {
    const auto key = std::make_tuple(d.file(), c.output, c.input);
    auto it = levels_.find(key);
    if (it == levels_.end()) it = levels_.emplace(key, frf_noise(frf.f_hz, c)).first;
    return it->second;
  }

 private:
  std::map<std::tuple<std::string, std::string, std::string>, FrfNoise> levels_;
};

// The parameters' covariance from the noise alone: the inverse Fisher information of the fitted lines,
// sum over lines of 2 Re(j^H j) / sigma^2 (real and imaginary parts each carry half of the complex noise
// variance sigma^2). at() gives the model's prediction variance E|dH|^2 = j Cov j^H at the lines of one data set's
// channel that the fit did not see.
class PredictionVariance {
 public:
  PredictionVariance(const Model& model, const std::vector<DataSet>& data, const Eigen::VectorXd& values,
                     const FittedOn& fitted, NoiseLevels& noise_levels)
      : model_(model) {
    if (!fitted.data || !fitted.estimated || fitted.estimated->empty()) return;
    for (const std::string& name : *fitted.estimated) {
      const int i = model.info().parameter_index(name);
      if (i >= 0) columns_.push_back(i);
    }
    const auto p = static_cast<Eigen::Index>(columns_.size());
    if (p == 0) return;
    Eigen::MatrixXd fisher = Eigen::MatrixXd::Zero(p, p);
    for (const DataSet& fd : *fitted.data) {
      const FrfData* fit_frf = std::get_if<FrfData>(&fd.content);
      if (!fit_frf || fit_frf->f_hz.size() == 0) continue;
      const DataSet* full = nullptr;
      for (const DataSet& d : data)
        if (d.file() == fd.file() && d.is_frf()) full = &d;
      if (!full) continue;
      const FrfData& all = std::get<FrfData>(full->content);
      const std::vector<double> f(fit_frf->f_hz.data(), fit_frf->f_hz.data() + fit_frf->f_hz.size());
      const FrfJacobianResult jac = frf_jacobian(model, with_set_values(model, fd, values), f);
      const Eigen::Index outputs = jac.H.empty() ? 0 : jac.H.front().rows();
      for (const FrfChannel& c : fit_frf->channels) {
        const int o = model.info().output_index(c.output), i = model.info().input_index(c.input);
        const FrfChannel* whole = all.find(c.output, c.input);
        if (o < 0 || i < 0 || !whole) continue;
        const FrfNoise& noise = noise_levels.of(*full, all, *whole);
        const Eigen::Index row = o + i * outputs;
        Eigen::Index line = 0;
        for (std::size_t k = 0; k < f.size(); ++k) {
          while (line < all.f_hz.size() && all.f_hz[line] < f[k]) ++line;
          if (line == all.f_hz.size() || all.f_hz[line] != f[k]) continue;
          const double s2 = noise.sigma[line] * noise.sigma[line];
          if (!(s2 > 0)) continue;
          Eigen::RowVectorXcd j(p);
          for (Eigen::Index q = 0; q < p; ++q) j[q] = jac.dH[k](row, columns_[static_cast<std::size_t>(q)]);
          fisher.noalias() += 2.0 * (j.adjoint() * j).real() / s2;
        }
      }
      fitted_lines_[fd.file()] = f;
    }
    // A pseudo-inverse: directions the fitted lines do not determine stay out (the fit reports them unidentifiable).
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(fisher);
    const Eigen::VectorXd ev = eig.eigenvalues();
    const double top = ev.size() ? ev.maxCoeff() : 0;
    if (!(top > 0)) return;
    Eigen::VectorXd inv = Eigen::VectorXd::Zero(p);
    for (Eigen::Index q = 0; q < p; ++q)
      if (ev[q] > top * 1e-14) inv[q] = 1 / ev[q];
    covariance_ = eig.eigenvectors() * inv.asDiagonal() * eig.eigenvectors().transpose();
  }

  // The prediction variance at the lines of data set `d`'s FRFs for channel (o, i); zero at the fitted lines.
  // Empty when there is no covariance.
  Eigen::VectorXd at(const DataSet& d, const Eigen::VectorXd& values, const std::vector<double>& f, int o,
                     int i) {
    if (covariance_.size() == 0) return {};
    auto lines = fitted_lines_.find(d.file());
    if (jacobian_file_ != d.file()) {
      jacobian_ = frf_jacobian(model_, with_set_values(model_, d, values), f);
      jacobian_file_ = d.file();
    }
    const Eigen::Index outputs = jacobian_.H.empty() ? 0 : jacobian_.H.front().rows();
    const Eigen::Index row = o + i * outputs;
    const auto p = static_cast<Eigen::Index>(columns_.size());
    Eigen::VectorXd var = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(f.size()));
    for (std::size_t k = 0; k < f.size(); ++k) {
      if (lines != fitted_lines_.end() && std::binary_search(lines->second.begin(), lines->second.end(), f[k]))
        continue;  // the fit saw this line: its residual is, if anything, smaller than the noise
      Eigen::RowVectorXcd j(p);
      for (Eigen::Index q = 0; q < p; ++q) j[q] = jacobian_.dH[k](row, columns_[static_cast<std::size_t>(q)]);
      var[static_cast<Eigen::Index>(k)] = std::max(0.0, (j * covariance_ * j.adjoint())(0, 0).real());
    }
    return var;
  }

 private:
  const Model& model_;
  std::vector<int> columns_;
  Eigen::MatrixXd covariance_;
  std::map<std::string, std::vector<double>> fitted_lines_;
  std::string jacobian_file_;
  FrfJacobianResult jacobian_;
};

}  // namespace

std::vector<ChannelResidual> channel_residuals(const Model& model, const std::vector<DataSet>& data,
                                               const Eigen::VectorXd& values, const FrfWeighting& weighting,
                                               const FittedOn& fitted) {
  std::vector<ChannelResidual> out;
  const ModelInfo& info = model.info();
  NoiseLevels noise_levels;
  PredictionVariance prediction(model, data, values, fitted, noise_levels);
  for (const DataSet& d : data) {
    FrfData frf;
    std::optional<FrfData> model_frf;  // for a record: the model's FRFs as the same estimator sees them
    WelchEstimate residual_est;        // for a record: the H1 of measured minus simulated outputs
    std::vector<double> line_correlation;  // for a record: of H1's neighbouring lines' noise
    double sigma_dof = 0;                  // for a record: of its five-line noise level
    if (const FrfData* measured = std::get_if<FrfData>(&d.content)) {
      frf = *measured;
    } else {
      const TimeRecord& record = std::get<TimeRecord>(d.content);
      const WelchEstimate est = record_frfs(model, record);
      frf = est.frf;
      // The model is judged through the same estimator: its response simulated from the record's inputs, then
      // the same Welch H1. A lightly damped peak comes out lower and wider in any H1 of finite resolution (at
      // 4 Hz lines, a 236 Hz spindle mode by 2.4 dB); compared with the model's exact FRF, that bias read as a
      // damping mismatch the correct model could not remove.
      TimeRecord simulated = record, residual = record;
      const Prediction prediction = predict(model, {d}, values);
      for (std::size_t c = 0; c < prediction.channel_names.front().size(); ++c)
        for (std::size_t s = 0; s < simulated.signals.size(); ++s)
          if (simulated.signals[s].name == prediction.channel_names.front()[c]) {
            simulated.signals[s].values = prediction.channels.front()[c].real();
            residual.signals[s].values = record.signals[s].values - simulated.signals[s].values;
          }
      model_frf = record_frfs(model, simulated).frf;
      // The noise level is the residual's own: the output power of the time-domain residual (measured minus
      // simulated) that the inputs do not explain. Its H1 is H1(measured) - H1(model) exactly (H1 is linear in the
      // outputs), and that power is the noise plus the leakage of the model's error only. The measured output's
      // unexplained power also holds the leakage of the whole response: with a 1 s record's 8 Hz lines the
      // coherence at a lightly damped spindle mode drops to 0.5, a noise level far too high there, which hid the
      // gyroscopic split of those modes.
      residual_est = record_frfs(model, residual);
      // H1's neighbouring lines share the segments' windowed spectra: their noise correlates (Hann: 0.44), and the
      // noise level is an estimate; the finding threshold counts both (residual_analysis.hpp). Without them a right
      // model's records were called `unexplained` in 5 of 40 drawn mdof2 controls, against the 5 % the threshold
      // states.
      const WelchOptions welch = record_welch_options(record);
      const auto present = [&](const std::string& in) { return record.find(in) != nullptr; };
      const auto inputs = static_cast<Eigen::Index>(std::count_if(info.inputs.begin(), info.inputs.end(), present));
      line_correlation = welch_line_correlation(welch, 4);
      sigma_dof = five_line_dof(welch_variance_dof(welch, residual_est.segments, inputs), line_correlation);
      // Above 90 % of Nyquist the anti-aliasing roll-off of any real record dominates; judge below it.
      const double f_max = 0.45 / est.dt;
      Eigen::Index keep = 0;
      while (keep < frf.f_hz.size() && frf.f_hz[keep] <= f_max) ++keep;
      Eigen::Index first = 0;
      while (first < keep && frf.f_hz[first] <= 0.0) ++first;  // no DC line
      for (FrfData* x : {&frf, &*model_frf}) {
        x->f_hz = x->f_hz.segment(first, keep - first).eval();
        for (FrfChannel& c : x->channels) {
          c.values = c.values.segment(first, keep - first).eval();
          if (c.coherence) *c.coherence = c.coherence->segment(first, keep - first).eval();
        }
      }
      for (Eigen::VectorXd& v : residual_est.variance) v = v.segment(first, keep - first).eval();
    }
    const std::vector<double> f(frf.f_hz.data(), frf.f_hz.data() + frf.f_hz.size());
    FrfResult h;
    if (!model_frf) h = mbgen::frf(model, with_set_values(model, d, values), f);
    for (std::size_t channel = 0; channel < frf.channels.size(); ++channel) {
      const FrfChannel& c = frf.channels[channel];
      const int o = info.output_index(c.output), i = info.input_index(c.input);
      if (o < 0 || i < 0) continue;
      ChannelResidual r;
      r.channel = c.output + "/" + c.input;
      r.data_set = d.file();
      r.f_hz = f;
      r.measured = c.values;
      r.model.resize(c.values.size());
      if (model_frf) {
        const FrfChannel* m = model_frf->find(c.output, c.input);
        if (!m || m->values.size() != c.values.size()) continue;  // the same record, so never: but never misalign
        r.model = m->values;
      } else {
        for (std::size_t k = 0; k < f.size(); ++k) r.model[static_cast<Eigen::Index>(k)] = h.H[k](o, i);
      }
      if (model_frf) {
        r.sigma = record_sigma(residual_est.variance[channel], c.values, weighting.floor);
        r.noise = "the H1 variance of the record's residual (measured minus simulated) over five lines";
        keep_record_lines_above_noise(r, static_cast<double>(residual_est.segments));
        r.line_correlation = line_correlation;
        r.sigma_dof = sigma_dof;
      } else {
        // The noise level from the data alone, the same for every model judged against them.
        const FrfNoise& noise = noise_levels.of(d, frf, c);
        r.sigma = noise.sigma;
        r.noise = noise.description();
        r.sigma_dof = noise.level_dof;
        keep_frf_lines_above_noise(r, prediction.at(d, values, f, o, i));
      }
      out.push_back(std::move(r));
    }
  }
  return out;
}

}  // namespace mbgen
