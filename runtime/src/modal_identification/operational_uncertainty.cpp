// The identified operational modes' standard deviations by batch means over data blocks
// (mbgen/modal_identification/operational_comparison.hpp). SSI-cov gives no uncertainty of its own, and the scatter
// of a cluster over the orders is not one: every order sees the same correlations, so they share their estimation
// error. Blocks of the record are independent data.
#include "mbgen/modal_identification/operational_comparison.hpp"
#include "shape_metrics.hpp"

#include <cmath>
#include <complex>
#include <limits>
#include <stdexcept>

namespace mbgen {

namespace {

constexpr double kBlockMac = 0.9;  // a block's mode is the whole record's when their shapes agree this well

// The block's records: the b-th of `blocks` equal pieces of each record.
ResponseData block_of(const ResponseData& data, int b, int blocks) {
  ResponseData out = data;
  for (std::size_t k = 0; k < data.records.size(); ++k) {
    const Eigen::MatrixXd& rec = data.records[k];
    const Eigen::Index n = rec.rows() / blocks;
    Eigen::MatrixXd piece = rec.middleRows(n * b, n);
    piece.rowwise() -= piece.colwise().mean();
    out.records[k] = std::move(piece);
  }
  return out;
}

// The shape's part that no complex factor on `reference` explains: shape * a - reference, a by least squares.
Eigen::VectorXcd scaled_difference(const Eigen::VectorXcd& shape, const Eigen::VectorXcd& reference) {
  const double ss = shape.squaredNorm();
  const std::complex<double> a = ss > 0 ? shape.dot(reference) / ss : 0.0;  // shape^H reference / |shape|^2
  return shape * a - reference;
}

}  // namespace

BlockUncertainty block_uncertainty(const ResponseData& data, const OutputOnlyIdentification& id,
                                   const OutputOnlyOptions& options, int blocks) {
  BlockUncertainty out;
  out.blocks = blocks;
  for (const Eigen::MatrixXd& r : data.records) out.block_s += static_cast<double>(r.rows() / blocks) * data.dt;
  const std::size_t nm = id.modes.size();
  std::vector<std::vector<double>> f(nm), zeta(nm), shape_sq(nm);
  for (int b = 0; b < blocks; ++b) {
    OutputOnlyOptions o = options;
    o.ssi.progress = nullptr;
    const OutputOnlyIdentification part = identify_output_only(block_of(data, b, blocks), o);
    for (std::size_t m = 0; m < nm; ++m) {
      const OperationalMode& whole = id.modes[m];
      const OperationalMode* best = nullptr;
      for (const OperationalMode& q : part.modes)
        if (std::abs(q.f_hz - whole.f_hz) <= options.selection.criteria.frequency * whole.f_hz &&
            modal_detail::shape_mac(q.shape, whole.shape) > kBlockMac &&
            (!best || std::abs(q.f_hz - whole.f_hz) < std::abs(best->f_hz - whole.f_hz)))
          best = &q;
      if (!best) continue;
      f[m].push_back(best->f_hz);
      zeta[m].push_back(best->zeta);
      shape_sq[m].push_back(scaled_difference(best->shape, whole.shape).squaredNorm());
    }
  }
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const auto channels = static_cast<double>(data.channels.size());
  for (std::size_t m = 0; m < nm; ++m) {
    ModeUncertainty u;
    const auto n = static_cast<double>(f[m].size());
    u.blocks_found = static_cast<int>(f[m].size());
    if (u.blocks_found < 3) {
      u.f_std_hz = u.zeta_std = u.shape_std = nan;
      out.modes.push_back(u);
      continue;
    }
    double fm = 0, zm = 0, s2 = 0;
    for (std::size_t k = 0; k < f[m].size(); ++k) {
      fm += f[m][k] / n;
      zm += zeta[m][k] / n;
      s2 += shape_sq[m][k];
    }
    double fv = 0, zv = 0;
    for (std::size_t k = 0; k < f[m].size(); ++k) {
      fv += (f[m][k] - fm) * (f[m][k] - fm) / (n - 1);
      zv += (zeta[m][k] - zm) * (zeta[m][k] - zm) / (n - 1);
    }
    // The blocks' shapes are compared with the whole record's, which is about their mean: as for a sample
    // variance, the sum of squares over n blocks holds n - 1 of their variance, per component left by the scaling.
    const double shape_var = s2 / (n - 1) / std::max(1.0, 2 * channels - 2);
    u.f_std_hz = std::sqrt(fv / n);
    u.zeta_std = std::sqrt(zv / n);
    u.shape_std = std::sqrt(shape_var / n);
    out.modes.push_back(u);
  }
  return out;
}

}  // namespace mbgen
