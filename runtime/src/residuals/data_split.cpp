#include "mbgen/residuals/data_split.hpp"

#include <mbgen/data/frf_sigma.hpp>

#include <cmath>

namespace mbgen {

namespace {

FrfData every_other_line(const FrfData& in, int parity) {
  FrfData out;
  out.file = in.file;
  out.set = in.set;
  const Eigen::Index n = (in.f_hz.size() + (parity == 0 ? 1 : 0)) / 2;
  out.f_hz.resize(n);
  for (Eigen::Index i = 0; i < n; ++i) out.f_hz[i] = in.f_hz[2 * i + parity];
  for (const FrfChannel& c : in.channels) {
    FrfChannel k;
    k.output = c.output;
    k.input = c.input;
    k.values.resize(n);
    if (c.coherence) k.coherence = Eigen::VectorXd(n);
    for (Eigen::Index i = 0; i < n; ++i) {
      k.values[i] = c.values[2 * i + parity];
      if (c.coherence) (*k.coherence)[i] = (*c.coherence)[2 * i + parity];
    }
    out.channels.push_back(std::move(k));
  }
  return out;
}

TimeRecord first_samples(const TimeRecord& in, Eigen::Index n) {
  TimeRecord out = in;
  out.t = in.t.head(n);
  for (Signal& s : out.signals) s.values = s.values.head(n).eval();
  return out;
}

}  // namespace

SplitData split_for_validation(const std::vector<DataSet>& data, double fit_fraction) {
  SplitData split;
  for (const DataSet& d : data) {
    if (const FrfData* frf = std::get_if<FrfData>(&d.content)) {
      split.fit.emplace_back(every_other_line(*frf, 0));
      split.validation.emplace_back(every_other_line(*frf, 1));
      split.scored_from.push_back(0);
    } else {
      const TimeRecord& rec = std::get<TimeRecord>(d.content);
      const Eigen::Index n_fit = static_cast<Eigen::Index>(std::floor(fit_fraction * static_cast<double>(rec.samples())));
      split.fit.emplace_back(first_samples(rec, n_fit));
      split.validation.emplace_back(rec);
      split.scored_from.push_back(n_fit);
    }
  }
  return split;
}

double validation_nrmse(const Model& model, const SplitData& split, const Eigen::VectorXd& values,
                        const FrfWeighting& weighting) {
  const Prediction pred = predict(model, split.validation, values);
  double err = 0, ref = 0;
  for (std::size_t s = 0; s < split.validation.size(); ++s) {
    const DataSet& d = split.validation[s];
    const std::vector<std::string>& names = pred.channel_names[s];
    for (std::size_t c = 0; c < names.size(); ++c) {
      const Eigen::VectorXcd& model_values = pred.channels[s][c];
      if (const FrfData* frf = std::get_if<FrfData>(&d.content)) {
        const FrfChannel& ch = frf->channels[c];
        const Eigen::VectorXd var = frf_variance(ch, weighting);
        err += (model_values - ch.values).cwiseAbs2().cwiseQuotient(var).sum();
        ref += ch.values.cwiseAbs2().cwiseQuotient(var).sum();
      } else {
        const TimeRecord& rec = std::get<TimeRecord>(d.content);
        const Eigen::VectorXd& measured = rec.at(names[c]).values;
        const Eigen::Index from = split.scored_from[s], n = measured.size() - from;
        const Eigen::VectorXd e = model_values.real().segment(from, n) - measured.segment(from, n);
        const double ms = measured.squaredNorm() / static_cast<double>(measured.size());  // weight 1/RMS^2
        err += e.squaredNorm() / ms;
        ref += measured.segment(from, n).squaredNorm() / ms;
      }
    }
  }
  return ref > 0 ? std::sqrt(err / ref) : 0.0;
}

}  // namespace mbgen
