// The whole experimental modal analysis: poles over the orders, their stabilization, the physical poles, their
// refinement, the residues, and the mode table.
#include "mbgen/modal_identification/modal_identification.hpp"
#include "shape_metrics.hpp"
#include "numerics/constants.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>

namespace mbgen {

namespace {
constexpr double kSignificance = 3;  // a physical pole's zeta lies this many standard deviations above 0
}  // namespace

ModalIdentification identify_modes(const ModalData& data, const ModalOptions& options) {
  ModalIdentification out;
  out.diagram = lscf(data, options.lscf);
  out.method = out.diagram.references > 1 ? "plscf-lsfd" : "lscf-lsfd";
  label_stability(out.diagram, options.selection.criteria);
  const bool automatic = options.select_hz.empty();
  std::vector<SelectedPole> poles = automatic ? select_physical_poles(out.diagram, options.selection)
                                              : select_poles_near(out.diagram, options.select_hz, options.selection);
  std::vector<std::complex<double>> lambdas;
  for (const SelectedPole& p : poles) lambdas.push_back(p.lambda);
  if (options.refine) {
    RefineOptions refine = options.refinement;
    refine.max_zeta = options.selection.criteria.max_zeta;
    out.refinement = refine_poles(data, lambdas, options.lsfd, refine);
    // An automatically selected pole is dropped, and the others refined again without it, when the refinement
    // cannot hold it (the misfit has no minimum near it: no resonance of the data), or when its damping is not
    // significantly above 0 (zeta < 3 std: a pole fitted to noise). Poles the user selected stay.
    for (;;) {
      std::vector<SelectedPole> kept;
      for (std::size_t r = 0; automatic && r < poles.size(); ++r) {
        std::string reason = out.refinement.notes[r];
        const double zeta = -out.refinement.poles[r].real() / std::abs(out.refinement.poles[r]);
        if (reason.empty() && std::isfinite(out.refinement.zeta_std[r]) &&
            zeta < kSignificance * out.refinement.zeta_std[r]) {
          std::ostringstream why;
          why << std::setprecision(3) << "its damping is not determined by the data: zeta " << 100 * zeta << " +- "
              << 100 * out.refinement.zeta_std[r] << " %";
          reason = why.str();
        }
        if (reason.empty())
          kept.push_back(poles[r]);
        else
          out.rejected.push_back({poles[r], reason});
      }
      if (!automatic || kept.size() == poles.size()) break;
      poles = kept;
      lambdas.clear();
      for (const SelectedPole& p : poles) lambdas.push_back(p.lambda);
      out.refinement = refine_poles(data, lambdas, options.lsfd, refine);
    }
  } else {
    out.refinement.poles = lambdas;
    out.refinement.refined.assign(lambdas.size(), false);
    out.refinement.notes.assign(lambdas.size(), "");
    out.refinement.f_std_hz.assign(lambdas.size(), std::numeric_limits<double>::quiet_NaN());
    out.refinement.zeta_std = out.refinement.f_std_hz;
  }
  lambdas = out.refinement.poles;
  out.fit = lsfd(data, lambdas, options.lsfd);
  const Eigen::Index n = static_cast<Eigen::Index>(poles.size());
  for (Eigen::Index r = 0; r < n; ++r) {
    const SelectedPole& p = poles[static_cast<std::size_t>(r)];
    const std::complex<double> lambda = lambdas[static_cast<std::size_t>(r)];
    IdentifiedMode mode;
    mode.lambda = lambda;
    mode.f_hz = std::abs(lambda) / numerics::kTwoPi;
    mode.zeta = -lambda.real() / std::abs(lambda);
    mode.f_std_hz = out.refinement.f_std_hz[static_cast<std::size_t>(r)];
    mode.zeta_std = out.refinement.zeta_std[static_cast<std::size_t>(r)];
    mode.refined = out.refinement.refined[static_cast<std::size_t>(r)];
    mode.lscf_f_hz = p.f_hz;
    mode.lscf_zeta = p.zeta;
    mode.residues = out.fit.residues.row(r).transpose();
    mode.mpc = modal_phase_collinearity(mode.residues);
    mode.mpd_deg = mean_phase_deviation_deg(mode.residues);
    mode.support = p.support;
    mode.user_selected = p.user_selected;
    out.modes.push_back(std::move(mode));
  }
  out.auto_mac.resize(n, n);
  for (Eigen::Index i = 0; i < n; ++i)
    for (Eigen::Index j = 0; j < n; ++j)
      out.auto_mac(i, j) = modal_detail::shape_mac(out.modes[static_cast<std::size_t>(i)].residues,
                                                   out.modes[static_cast<std::size_t>(j)].residues);
  return out;
}

}  // namespace mbgen
