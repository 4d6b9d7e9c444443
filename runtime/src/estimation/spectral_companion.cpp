#include "mbgen/estimation/spectral_companion.hpp"

#include "mbgen/data/welch.hpp"
#include "mbgen/dynamics/frf.hpp"

#include <algorithm>
#include <cmath>

namespace mbgen::estimation {

namespace {

constexpr Eigen::Index min_segment = 64, max_segment = 4096, min_segments = 8;

// Keeps the bins with 0 < f <= f_max, in every channel.
FrfData band(const FrfData& in, double f_max) {
  std::vector<Eigen::Index> keep;
  for (Eigen::Index k = 0; k < in.f_hz.size(); ++k)
    if (in.f_hz[k] > 0 && in.f_hz[k] <= f_max) keep.push_back(k);
  const auto n = static_cast<Eigen::Index>(keep.size());
  FrfData out;
  out.file = in.file;
  out.set = in.set;
  out.f_hz.resize(n);
  for (Eigen::Index j = 0; j < n; ++j) out.f_hz[j] = in.f_hz[keep[static_cast<std::size_t>(j)]];
  for (const FrfChannel& c : in.channels) {
    FrfChannel k{c.output, c.input, Eigen::VectorXcd(n), std::nullopt};
    if (c.coherence) k.coherence = Eigen::VectorXd(n);
    for (Eigen::Index j = 0; j < n; ++j) {
      const Eigen::Index src = keep[static_cast<std::size_t>(j)];
      k.values[j] = c.values[src];
      if (c.coherence) (*k.coherence)[j] = (*c.coherence)[src];
    }
    out.channels.push_back(std::move(k));
  }
  return out;
}

}  // namespace

std::optional<SpectralCompanion> spectral_companion(const ModelInfo& info, const std::vector<DataSet>& data) {
  SpectralCompanion out;
  bool any_record = false;
  int averages = 0;
  for (const DataSet& d : data) {
    if (d.is_frf()) {
      out.data.push_back(d);
      continue;
    }
    any_record = true;
    const TimeRecord& record = std::get<TimeRecord>(d.content);
    Eigen::Index segment = max_segment;
    while (segment >= min_segment && segment * min_segments > record.samples()) segment /= 2;
    if (segment < min_segment) return std::nullopt;
    std::vector<std::string> outputs;
    for (const std::string& o : info.outputs)
      if (record.find(o)) outputs.push_back(o);
    // A record may hold an input at zero (the simulation needs every input): H1 uses the excited ones only,
    // whose auto-spectral matrix is regular.
    std::vector<std::string> inputs;
    for (const std::string& i : info.inputs) {
      const Signal* s = record.find(i);
      if (s && s->values.size() > 1 && (s->values.array() - s->values.mean()).abs().maxCoeff() > 0) inputs.push_back(i);
    }
    if (inputs.empty() || outputs.empty()) return std::nullopt;
    WelchOptions options;
    options.segment_length = segment;
    options.compensate_hold = record.hold == HoldMode::ZeroOrder;
    WelchEstimate h1 = welch_h1(record, inputs, outputs, options);
    const double nyquist = 0.5 / h1.dt;
    FrfData estimate = band(h1.frf, 0.5 * nyquist);
    if (estimate.f_hz.size() == 0) return std::nullopt;
    estimate.file = record.file;
    estimate.set = record.set;
    out.data.emplace_back(std::move(estimate));
    averages = averages == 0 ? static_cast<int>(h1.segments) : std::min(averages, static_cast<int>(h1.segments));
  }
  if (!any_record) return std::nullopt;
  out.averages = std::max(averages, 1);
  return out;
}

std::optional<SpectralCompanion> debiased_spectral_companion(const Model& model, const Eigen::VectorXd& p,
                                                             const std::vector<DataSet>& data) {
  const ModelInfo& info = model.info();
  std::optional<SpectralCompanion> measured = spectral_companion(info, data);
  if (!measured) return measured;
  // The records with their outputs replaced by the model's response at p (the inputs, and so H1's segments, stay).
  std::vector<DataSet> simulated = data;
  for (DataSet& d : simulated) {
    TimeRecord* record = std::get_if<TimeRecord>(&d.content);
    if (!record) continue;
    const Prediction prediction = predict(model, {d}, p);
    for (std::size_t c = 0; c < prediction.channel_names.front().size(); ++c)
      for (Signal& s : record->signals)
        if (s.name == prediction.channel_names.front()[c]) s.values = prediction.channels.front()[c].real();
  }
  const std::optional<SpectralCompanion> of_model = spectral_companion(info, simulated);
  if (!of_model || of_model->data.size() != measured->data.size()) return measured;
  for (std::size_t i = 0; i < data.size(); ++i) {
    if (data[i].is_frf()) continue;
    FrfData& h1 = std::get<FrfData>(measured->data[i].content);
    const FrfData& h1_model = std::get<FrfData>(of_model->data[i].content);
    const std::vector<double> f(h1.f_hz.data(), h1.f_hz.data() + h1.f_hz.size());
    const FrfResult exact = frf(model, p, f);
    for (FrfChannel& c : h1.channels) {
      const FrfChannel* m = h1_model.find(c.output, c.input);
      const int o = info.output_index(c.output), in = info.input_index(c.input);
      if (!m || o < 0 || in < 0) continue;
      for (Eigen::Index k = 0; k < c.values.size(); ++k) {
        const std::complex<double> biased = m->values[k];
        const std::complex<double> ratio = exact.H[static_cast<std::size_t>(k)](o, in) / biased;
        if (std::abs(biased) > 0 && std::isfinite(ratio.real()) && std::isfinite(ratio.imag())) c.values[k] *= ratio;
      }
    }
  }
  return measured;
}

}  // namespace mbgen::estimation
