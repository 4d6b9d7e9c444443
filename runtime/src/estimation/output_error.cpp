#include "output_error.hpp"

#include <algorithm>
#include <cmath>

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
      p.f_hz = f.f_hz;
      if (f.channels.empty() || f.f_hz.size() == 0) throw FitError(where(d) + ": no FRF channels or frequencies");
      for (const FrfChannel& c : f.channels) {
        const int o = info.output_index(c.output), i = info.input_index(c.input);
        if (o < 0) throw FitError(where(d) + ": channel " + c.output + "/" + c.input + ": the model has no output " + c.output);
        if (i < 0) throw FitError(where(d) + ": channel " + c.output + "/" + c.input + ": the model has no input " + c.input);
        p.channels.push_back({o, i});
        p.names.push_back(c.output + "/" + c.input);
        p.measured.push_back(c.values);
        const Eigen::VectorXd mag = c.values.cwiseAbs();
        const double level = rms(mag) > 0 ? rms(mag) : 1.0;
        const double floor2 = std::pow(weighting.floor * level, 2);
        Eigen::VectorXd sigma(c.values.size());
        for (Eigen::Index k = 0; k < sigma.size(); ++k) {
          double var = level * level;
          if (c.coherence) {
            const double g2 = std::min(std::max((*c.coherence)[k], 1e-12), 1.0);
            var = (1 - g2) / (g2 * std::max(weighting.averages, 1)) * mag[k] * mag[k];
          }
          sigma[k] = std::sqrt(std::max(var, floor2) / 2);
        }
        p.sigma.push_back(sigma);
        measured_ss_ += (c.values.real().cwiseQuotient(sigma).squaredNorm() +
                         c.values.imag().cwiseQuotient(sigma).squaredNorm());
        p.size += 2 * c.values.size();
      }
    } else {
      const TimeRecord& t = std::get<TimeRecord>(d.content);
      if (t.samples() < 2) throw FitError(where(d) + ": a time record needs at least 2 samples");
      require_inputs(t, info.inputs);
      p.dt = t.dt();
      p.hold = t.hold;
      p.u.resize(t.samples(), static_cast<Eigen::Index>(info.inputs.size()));
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

void OutputErrorProblem::evaluate(const Eigen::VectorXd& values, const std::vector<int>& free_params,
                                  ResidualKind kind, Eigen::VectorXd& r, Eigen::MatrixXd* J) const {
  const Eigen::Index k = static_cast<Eigen::Index>(free_params.size());
  r.resize(count_);
  if (J) J->setZero(count_, k);
  ModelMatrices m;
  ModelDerivatives md;
  for (const Prepared& s : sets_) {
    Eigen::VectorXd p = values;
    for (const auto& [idx, v] : s.overrides) p[idx] = v;
    model_.evaluate(p, m);
    std::vector<int> inactive;
    for (const auto& [idx, v] : s.overrides) inactive.push_back(idx);  // acts through the set value, not the shared one
    if (J) model_.derivatives(p, md);
    Eigen::Index row = s.offset;
    if (s.frf) {
      const FrfResponse h = frf_response(m, J ? &md : nullptr, free_params, inactive, s.f_hz, s.channels);
      const Eigen::Index nf = s.f_hz.size();
      for (std::size_t c = 0; c < s.channels.size(); ++c) {
        if (kind == ResidualKind::LogRatio) {
          // log(Hm / Hd): real part log-magnitude ratio, imaginary part phase difference in (-pi, pi].
          for (Eigen::Index f = 0; f < nf; ++f) {
            const std::complex<double> hm = h.values[c][f], hd = s.measured[c][f];
            const std::complex<double> lr = (hm == 0.0 || hd == 0.0) ? 0.0 : std::log(hm / hd);
            r[row + f] = lr.real();
            r[row + nf + f] = lr.imag();
            if (J && hm != 0.0 && hd != 0.0)
              for (Eigen::Index j = 0; j < k; ++j) {
                const std::complex<double> g = h.jacobian[c](f, j) / hm;
                (*J)(row + f, j) = g.real();
                (*J)(row + nf + f, j) = g.imag();
              }
          }
        } else {
          const Eigen::VectorXcd e = h.values[c] - s.measured[c];
          r.segment(row, nf) = e.real().cwiseQuotient(s.sigma[c]);
          r.segment(row + nf, nf) = e.imag().cwiseQuotient(s.sigma[c]);
          if (J) {
            J->block(row, 0, nf, k) = s.sigma[c].cwiseInverse().asDiagonal() * h.jacobian[c].real();
            J->block(row + nf, 0, nf, k) = s.sigma[c].cwiseInverse().asDiagonal() * h.jacobian[c].imag();
          }
        }
        row += 2 * nf;
      }
    } else {
      std::vector<DenseDerivative> dd;
      if (J) {
        dd = dense_derivatives(m, md, free_params);
        for (std::size_t j = 0; j < free_params.size(); ++j)
          if (std::find(inactive.begin(), inactive.end(), free_params[j]) != inactive.end()) dd[j].any = false;
      }
      const TimeResponse y = time_response(m, J ? &dd : nullptr, s.u, s.dt, s.hold, s.outputs);
      const Eigen::Index N = s.u.rows();
      for (std::size_t o = 0; o < s.outputs.size(); ++o) {
        r.segment(row, N) = s.weight[o] * (y.values[o] - s.measured_y[o]);
        if (J) J->block(row, 0, N, k) = s.weight[o] * y.sensitivity[o];
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
    std::vector<Eigen::VectorXcd> channels;
    if (s.frf) {
      channels = frf_response(m, nullptr, {}, {}, s.f_hz, s.channels).values;
    } else {
      for (const auto& y : time_response(m, nullptr, s.u, s.dt, s.hold, s.outputs).values)
        channels.push_back(y.cast<std::complex<double>>());
    }
    out.channels.push_back(std::move(channels));
    out.channel_names.push_back(s.names);
  }
  return out;
}

}  // namespace mbgen::estimation
