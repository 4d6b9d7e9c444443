#include "output_error.hpp"

#include "excited_block.hpp"

#include "mbgen/dynamics/frf.hpp"
#include "mbgen/data/frf_sigma.hpp"
#include "mbgen/dynamics/simulate.hpp"

#include <algorithm>
#include <cmath>
#include <complex>

namespace mbgen::estimation {

namespace {

double rms(const Eigen::VectorXd& v) { return v.size() ? std::sqrt(v.squaredNorm() / double(v.size())) : 0.0; }

std::string where(const DataSet& d) { return d.file().empty() ? std::string("data set") : d.file(); }

}  // namespace

OutputErrorProblem::OutputErrorProblem(const Model& model, const std::vector<DataSet>& data,
                                       const FrfWeighting& weighting)
    : model_(model) {
  const ModelInfo& info = model.info();
  if (data.empty()) throw FitError("fit: no data sets given");
  for (const DataSet& d : data) {
    Prepared p;
    for (const auto& [name, value] : d.set()) {
      const int idx = info.parameter_index(name);
      if (idx < 0) throw FitError(where(d) + ": `# set " + name + "`: the model has no parameter " + name);
      p.overrides.emplace_back(idx, value.value);
    }
    p.offset = count_;
    if (d.is_frf()) {
      const FrfData& f = std::get<FrfData>(d.content);
      p.frf = true;
      p.f_hz.assign(f.f_hz.data(), f.f_hz.data() + f.f_hz.size());
      if (f.channels.empty() || f.f_hz.size() == 0) throw FitError(where(d) + ": no FRF channels or frequencies");
      for (const FrfChannel& c : f.channels) {
        const int o = info.output_index(c.output), i = info.input_index(c.input);
        if (o < 0) throw FitError(where(d) + ": channel " + c.output + "/" + c.input + ": the model has no output " + c.output);
        if (i < 0) throw FitError(where(d) + ": channel " + c.output + "/" + c.input + ": the model has no input " + c.input);
        auto slot = [](std::vector<int>& used, int index) {
          const auto it = std::find(used.begin(), used.end(), index);
          if (it != used.end()) return static_cast<int>(it - used.begin());
          used.push_back(index);
          return static_cast<int>(used.size()) - 1;
        };
        p.channel_output.push_back(slot(p.frf_outputs, o));
        p.channel_input.push_back(slot(p.inputs, i));
        p.names.push_back(c.output + "/" + c.input);
        p.measured.push_back(c.values);
        const Eigen::VectorXd mag = c.values.cwiseAbs();
        const Eigen::VectorXd sigma = (frf_variance(c, weighting) / 2).cwiseSqrt();  // per real component
        p.sigma.push_back(sigma);
        Eigen::VectorXcd inverse(c.values.size());
        Eigen::VectorXd log_weight(c.values.size());
        for (Eigen::Index k = 0; k < sigma.size(); ++k) {
          const std::complex<double> hd = c.values[k];
          inverse[k] = hd != 0.0 ? 1.0 / hd : 0.0;
          log_weight[k] = mag[k] / (std::sqrt(2.0) * sigma[k]);
        }
        p.inverse_measured.push_back(inverse);
        p.log_weight.push_back(log_weight);
        measured_ss_ += (c.values.real().cwiseQuotient(sigma).squaredNorm() +
                         c.values.imag().cwiseQuotient(sigma).squaredNorm());
        p.size += 2 * c.values.size();
      }
    } else {
      const TimeRecord& t = std::get<TimeRecord>(d.content);
      // A method may fit a part of the record (a split for validation): say how many samples it had.
      if (t.samples() < 2)
        throw FitError(where(d) + ": error: a time record needs at least 2 samples for a fit; the part of it fitted here "
                       "has " + std::to_string(t.samples()));
      require_inputs(t, info.inputs);
      p.dt = t.dt();
      p.hold = t.hold;
      p.u.resize(t.samples(), static_cast<Eigen::Index>(info.inputs.size()));
      for (std::size_t i = 0; i < info.inputs.size(); ++i) p.inputs.push_back(static_cast<int>(i));
      for (std::size_t i = 0; i < info.inputs.size(); ++i) p.u.col(static_cast<Eigen::Index>(i)) = t.at(info.inputs[i]).values;
      for (std::size_t o = 0; o < info.outputs.size(); ++o) {
        const Signal* s = t.find(info.outputs[o]);
        if (!s) continue;
        p.outputs.push_back(static_cast<int>(o));
        p.names.push_back(info.outputs[o]);
        p.measured_y.push_back(s->values);
        const double level = rms(s->values);
        p.weight.push_back(level > 0 ? 1 / level : 1.0);
        measured_ss_ += (s->values * p.weight.back()).squaredNorm();
        p.size += t.samples();
      }
      if (p.outputs.empty()) throw FitError(where(d) + ": the record has none of the model's outputs (" + [&] {
        std::string s;
        for (const auto& n : info.outputs) s += (s.empty() ? "" : ", ") + n;
        return s;
      }() + ")");
    }
    count_ += p.size;
    sets_.push_back(std::move(p));
  }
}

bool OutputErrorProblem::has_frf() const {
  for (const auto& s : sets_) if (s.frf) return true;
  return false;
}
bool OutputErrorProblem::has_time() const {
  for (const auto& s : sets_) if (!s.frf) return true;
  return false;
}

namespace {

InputHold input_hold(HoldMode hold) { return hold == HoldMode::None ? InputHold::FirstOrder : InputHold::ZeroOrder; }

// log z = log|z| + j arg z. std::log of a complex number (glibc's clog) guards log|z| near |z| = 1 by sorting
// partial sums (__x2y2m1, a qsort per call): a fifth of a frame3 fit's time went there. Near a fit the ratio
// H_model / H_measured is that close to 1, and the absolute error of log(|z|^2) / 2 there, a few 1e-16, is far
// below any residual's noise.
std::complex<double> log_of(std::complex<double> z) {
  const double norm2 = z.real() * z.real() + z.imag() * z.imag();
  const double log_abs = norm2 > 0 && std::isfinite(norm2) ? 0.5 * std::log(norm2) : std::log(std::abs(z));
  return {log_abs, std::atan2(z.imag(), z.real())};
}

}  // namespace

void OutputErrorProblem::evaluate(const Eigen::VectorXd& values, const std::vector<int>& free_params,
                                  ResidualKind kind, Eigen::VectorXd& r, Eigen::MatrixXd* J,
                                  const Eigen::VectorXd* column_scale) const {
  const Eigen::Index k = static_cast<Eigen::Index>(free_params.size());
  r.resize(count_);
  if (J) J->resize(count_, k);  // every entry is written below
  const auto scale = [&](Eigen::Index j) { return column_scale ? (*column_scale)[j] : 1.0; };
  ModelMatrices m;
  ModelDerivatives md;
  std::vector<int> column;
  for (const Prepared& s : sets_) {
    Eigen::VectorXd p = values;
    for (const auto& [idx, v] : s.overrides) p[idx] = v;
    model_.evaluate(p, m);
    // Jacobian column of each model parameter; a data set's `# set` parameters act through the set value,
    // not the shared one, so they get none.
    column.assign(static_cast<std::size_t>(values.size()), -1);
    for (std::size_t j = 0; j < free_params.size(); ++j) column[static_cast<std::size_t>(free_params[j])] = static_cast<int>(j);
    for (const auto& [idx, v] : s.overrides) column[static_cast<std::size_t>(idx)] = -1;
    if (J) model_.derivatives(p, md);
    const std::vector<int>& outputs = s.frf ? s.frf_outputs : s.outputs;
    const ReducedModel red = reduce_to_excited_block(m, J ? &md : nullptr, s.inputs, outputs, column);
    Eigen::Index row = s.offset;
    if (s.frf) {
      const std::size_t channels = s.channel_output.size();
      const Eigen::Index no = static_cast<Eigen::Index>(s.frf_outputs.size());
      // The per-line data of each channel, as plain pointers: the stores into r and J below could alias
      // the vectors' own pointers, which the compiler would otherwise reload for every line.
      std::vector<const std::complex<double>*> measured(channels), inverse_measured(channels);
      std::vector<const double*> sigma(channels), log_weight(channels);
      std::vector<Eigen::Index> entry(channels);
      for (std::size_t c = 0; c < channels; ++c) {
        measured[c] = s.measured[c].data();
        inverse_measured[c] = s.inverse_measured[c].data();
        sigma[c] = s.sigma[c].data();
        log_weight[c] = s.log_weight[c].data();
        entry[c] = s.channel_output[c] + s.channel_input[c] * no;
      }
      Eigen::VectorXd scales(k);
      for (Eigen::Index j = 0; j < k; ++j) scales[j] = scale(j);
      // Residuals of every channel at frequency index f (rows row + 2 (f channels + c), real then imaginary part),
      // and their Jacobian rows when dH is given: one line's rows are adjacent in every column of J.
      auto residuals_at = [&](std::size_t fk, const Eigen::MatrixXcd& H, const Eigen::MatrixXcd* dH) {
        const Eigen::Index f = static_cast<Eigen::Index>(fk);
        Eigen::Index at = row + 2 * f * static_cast<Eigen::Index>(channels);
        for (std::size_t c = 0; c < channels; ++c, at += 2) {
          const std::complex<double> hm = H(s.channel_output[c], s.channel_input[c]);
          std::complex<double> value, gain;  // residual, and the factor taking dH to the residual's derivative
          if (kind == ResidualKind::LogRatio) {
            // log(Hm / Hd): real part log-magnitude ratio, imaginary part phase difference in (-pi, pi].
            // Weighted by |Hd| / sigma (sigma of the complex value): to first order log(Hm/Hd) = (Hm - Hd)/Hd,
            // so near the fit this is the weighted residual, while noise-dominated points (anti-resonances,
            // |Hd| ~ sigma) get little weight; far from the fit a missed peak still costs only a log ratio.
            const std::complex<double> inverse_hd = inverse_measured[c][f];
            const double w = log_weight[c][f];
            const double hm2 = hm.real() * hm.real() + hm.imag() * hm.imag();
            const bool defined = hm2 != 0 && inverse_hd != 0.0;
            value = defined ? w * log_of(hm * inverse_hd) : 0.0;
            gain = defined ? std::complex<double>(w * hm.real() / hm2, -w * hm.imag() / hm2) : 0.0;  // w / Hm
          } else {
            const double w = 1 / sigma[c][f];
            value = (hm - measured[c][f]) * w;
            gain = w;
          }
          r[at] = value.real();
          r[at + 1] = value.imag();
          if (!dH || k == 0) continue;  // no columns: J has no storage to point into
          double* J_row = J->data() + at;
          const Eigen::Index stride = J->rows();
          for (Eigen::Index j = 0; j < k; ++j, J_row += stride) {
            const std::complex<double> g = gain * (*dH)(entry[c], j) * scales[j];
            J_row[0] = g.real();
            J_row[1] = g.imag();
          }
        }
      };
      // A Levenberg-Marquardt step evaluates the residuals at its trial point and, once accepted, their Jacobian
      // there: the Jacobian takes the factors that evaluation left on this thread (frf.hpp, FrfFactorCache).
      thread_local std::vector<FrfFactorCache> factors;
      const std::size_t set_index = static_cast<std::size_t>(&s - sets_.data());
      if (factors.size() <= set_index) factors.resize(set_index + 1);
      if (J)
        frf_jacobian(
            red.m, red.d, static_cast<int>(k), s.f_hz,
            [&](std::size_t f, const Eigen::MatrixXcd& H, const Eigen::MatrixXcd& dH) { residuals_at(f, H, &dH); },
            &factors[set_index]);
      else
        frf(red.m, s.f_hz, [&](std::size_t f, const Eigen::MatrixXcd& H) { residuals_at(f, H, nullptr); },
            &factors[set_index]);
    } else {
      const Eigen::Index N = s.u.rows();
      const InputHold hold = input_hold(s.hold);
      SimulationSensitivity y;
      if (J)
        y = simulate_with_sensitivity(red.m, red.d, static_cast<int>(k), s.u, s.dt, hold);
      else
        y.outputs = simulate(red.m, s.u, s.dt, hold);
      if (!y.outputs.allFinite()) throw FitError("time simulation diverged (unstable model at these parameter values)");
      for (std::size_t o = 0; o < s.outputs.size(); ++o) {
        const auto oi = static_cast<Eigen::Index>(o);
        r.segment(row, N) = s.weight[o] * (y.outputs.col(oi) - s.measured_y[o]);
        if (J)
          for (Eigen::Index j = 0; j < k; ++j)
            J->block(row, j, N, 1) = (s.weight[o] * scale(j)) * y.doutputs[static_cast<std::size_t>(j)].col(oi);
        row += N;
      }
    }
  }
}

Prediction OutputErrorProblem::predict(const Eigen::VectorXd& values) const {
  Prediction out;
  ModelMatrices m;
  for (const Prepared& s : sets_) {
    Eigen::VectorXd p = values;
    for (const auto& [idx, v] : s.overrides) p[idx] = v;
    model_.evaluate(p, m);
    const ReducedModel red = reduce_to_excited_block(m, nullptr, s.inputs, s.frf ? s.frf_outputs : s.outputs, {});
    std::vector<Eigen::VectorXcd> channels;
    if (s.frf) {
      const FrfResult h = frf(red.m, s.f_hz);
      for (std::size_t c = 0; c < s.channel_output.size(); ++c) {
        Eigen::VectorXcd v(static_cast<Eigen::Index>(s.f_hz.size()));
        for (std::size_t f = 0; f < s.f_hz.size(); ++f)
          v[static_cast<Eigen::Index>(f)] = h.H[f](s.channel_output[c], s.channel_input[c]);
        channels.push_back(std::move(v));
      }
    } else {
      const Eigen::MatrixXd y = simulate(red.m, s.u, s.dt, input_hold(s.hold));
      for (Eigen::Index o = 0; o < y.cols(); ++o) channels.push_back(y.col(o).cast<std::complex<double>>());
    }
    out.channels.push_back(std::move(channels));
    out.channel_names.push_back(s.names);
  }
  return out;
}

}  // namespace mbgen::estimation
