// The whole output-only analysis: SSI-cov's diagram through the FRF path's stabilization and selection, or FDD's
// peaks, and the mode table.
#include "mbgen/modal_identification/output_only_modal.hpp"
#include "shape_metrics.hpp"
#include "numerics/constants.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <limits>
#include <stdexcept>

namespace mbgen {

namespace {

using numerics::kTwoPi;

double scatter(const std::vector<double>& v) {
  if (v.size() < 2) return std::numeric_limits<double>::quiet_NaN();
  double mean = 0, sum = 0;
  for (double x : v) mean += x / static_cast<double>(v.size());
  for (double x : v) sum += (x - mean) * (x - mean);
  return std::sqrt(sum / static_cast<double>(v.size() - 1));
}

double median_contribution(const std::vector<double>& contribution, const SelectedPole& p) {
  std::vector<double> c;
  for (int i : p.members) c.push_back(contribution[static_cast<std::size_t>(i)]);
  std::sort(c.begin(), c.end());
  return c.size() % 2 ? c[c.size() / 2] : 0.5 * (c[c.size() / 2 - 1] + c[c.size() / 2]);
}

void fill_indicators(OperationalMode& m) {
  m.shape = normalize_shape(m.shape);
  m.mpc = modal_phase_collinearity(m.shape);
  m.mpd_deg = mean_phase_deviation_deg(m.shape);
}

std::vector<OperationalMode> ssi_modes(const StabilizationDiagram& d, const std::vector<double>& contribution,
                                       const std::vector<SelectedPole>& poles) {
  std::vector<OperationalMode> modes;
  for (const SelectedPole& p : poles) {
    OperationalMode m;
    m.f_hz = p.f_hz;
    m.zeta = p.zeta;
    m.lambda = p.lambda;
    m.support = p.support;
    // The shape of the member nearest the cluster's median pole: a shape of the diagram, not an average of
    // shapes whose phases are arbitrary.
    std::vector<double> f, zeta;
    const DiagramPole* nearest = nullptr;
    for (int i : p.members) {
      const DiagramPole& q = d.poles[static_cast<std::size_t>(i)];
      f.push_back(q.f_hz);
      zeta.push_back(q.zeta);
      if (!nearest || std::abs(q.lambda - p.lambda) < std::abs(nearest->lambda - p.lambda)) nearest = &q;
    }
    m.shape = nearest->shape;
    m.contribution = median_contribution(contribution, p);
    m.f_scatter_hz = scatter(f);
    m.zeta_scatter = scatter(zeta);
    fill_indicators(m);
    modes.push_back(std::move(m));
  }
  return modes;
}

std::vector<OperationalMode> fdd_modes(const FddResult& r) {
  std::vector<OperationalMode> modes;
  for (const FddPeak& p : r.peaks) {
    OperationalMode m;
    m.f_hz = std::isfinite(p.efdd_f_hz) ? p.efdd_f_hz : p.f_hz;
    m.zeta = p.zeta;
    const double w = kTwoPi * m.f_hz;
    m.lambda = std::isfinite(m.zeta)
                   ? std::complex<double>(-m.zeta * w, w * std::sqrt(std::max(0.0, 1 - m.zeta * m.zeta)))
                   : std::complex<double>(std::numeric_limits<double>::quiet_NaN(), w);
    m.shape = p.shape;
    m.support = p.bell_lines;
    m.f_scatter_hz = m.zeta_scatter = m.contribution = std::numeric_limits<double>::quiet_NaN();
    fill_indicators(m);
    modes.push_back(std::move(m));
  }
  return modes;
}

void fill_auto_mac(OutputOnlyIdentification& out) {
  const Eigen::Index n = static_cast<Eigen::Index>(out.modes.size());
  out.auto_mac.resize(n, n);
  for (Eigen::Index i = 0; i < n; ++i)
    for (Eigen::Index j = 0; j < n; ++j)
      out.auto_mac(i, j) = modal_detail::shape_mac(out.modes[static_cast<std::size_t>(i)].shape,
                                                   out.modes[static_cast<std::size_t>(j)].shape);
}

}  // namespace

const char* output_only_method_name(OutputOnlyMethod m) { return m == OutputOnlyMethod::SsiCov ? "ssi-cov" : "fdd"; }

Eigen::VectorXcd normalize_shape(const Eigen::VectorXcd& shape) {
  const double norm = shape.norm();
  if (!(norm > 0)) return shape;
  Eigen::Index big = 0;
  for (Eigen::Index k = 1; k < shape.size(); ++k)
    if (std::abs(shape[k]) > std::abs(shape[big])) big = k;
  return shape * (std::abs(shape[big]) / shape[big] / norm);
}

OutputOnlyIdentification identify_output_only(const ResponseData& data, const OutputOnlyOptions& options) {
  OutputOnlyIdentification out;
  out.method = options.method;
  if (options.method == OutputOnlyMethod::SsiCov) {
    // One channel gives scalar shapes: the stabilization's shape test, and with it the selection, says nothing.
    if (data.channels.size() < 2)
      throw std::invalid_argument("SSI-cov needs at least 2 response channels (this has 1; FDD works with one)");
    out.ssi = ssi_cov(data, options.ssi);
    label_stability(out.ssi.diagram, options.selection.criteria);
    std::vector<SelectedPole> kept;
    for (SelectedPole& p : select_physical_poles(out.ssi.diagram, options.selection)) {
      const double c = median_contribution(out.ssi.contribution, p);
      if (c >= options.min_contribution) {
        kept.push_back(std::move(p));
        continue;
      }
      std::ostringstream why;
      why << std::setprecision(3) << "it explains too little of the responses: contribution " << c << " < "
          << options.min_contribution;
      out.rejected.push_back({std::move(p), why.str()});
    }
    out.modes = ssi_modes(out.ssi.diagram, out.ssi.contribution, kept);
  } else {
    out.fdd = fdd(data, options.fdd);
    out.modes = fdd_modes(out.fdd);
  }
  fill_auto_mac(out);
  return out;
}

OutputOnlyIdentification identify_output_only_frfs(const ModalData& frfs, const OutputOnlyOptions& options) {
  if (options.method != OutputOnlyMethod::Fdd)
    throw std::invalid_argument("FRFs are analysed output-only by FDD only (--method fdd)");
  OutputOnlyIdentification out;
  out.method = options.method;
  out.fdd = fdd_of_frfs(frfs, options.fdd);
  out.modes = fdd_modes(out.fdd);
  fill_auto_mac(out);
  return out;
}

ResponseData frf_responses(const ModalData& frfs) {
  ResponseData data;
  data.files = frfs.files;
  const bool transposed = frfs.outputs.size() < frfs.inputs.size();  // as fdd_of_frfs
  data.channels = transposed ? frfs.inputs : frfs.outputs;
  for (std::size_t c = 0; c < data.channels.size(); ++c) data.references.push_back(static_cast<int>(c));
  data.dt = frf_equivalent_dt(frfs);
  std::string forces;
  for (const std::string& i : transposed ? frfs.outputs : frfs.inputs) forces += (forces.empty() ? "" : ", ") + i;
  data.notes.push_back("FRFs read as the spectra of the responses to unmeasured unit white forces at " + forces +
                       (transposed ? " (by reciprocity: fewer outputs than inputs)" : "") +
                       ": G = H H^H, no lag window");
  return data;
}

}  // namespace mbgen
