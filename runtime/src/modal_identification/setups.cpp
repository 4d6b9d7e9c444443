// Several setups (roving sensors with shared references): each identified on its own, the modes paired by
// frequency and their shapes glued on the reference responses (post-separate estimation re-scaling).
#include "mbgen/data/data_error.hpp"
#include "mbgen/modal_identification/output_only_modal.hpp"
#include "shape_metrics.hpp"
#include "numerics/constants.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace mbgen {

namespace {

bool contains(const std::vector<std::string>& names, const std::string& name) {
  return std::find(names.begin(), names.end(), name) != names.end();
}

int index_of(const std::vector<std::string>& names, const std::string& name) {
  return static_cast<int>(std::find(names.begin(), names.end(), name) - names.begin());
}

std::string hz(double f) {
  std::ostringstream s;
  s << std::setprecision(6) << f << " Hz";
  return s.str();
}

double mean(const std::vector<double>& v) {
  double sum = 0;
  for (double x : v) sum += x;
  return sum / static_cast<double>(v.size());
}

double deviation(const std::vector<double>& v) {
  if (v.size() < 2) return std::numeric_limits<double>::quiet_NaN();
  const double m = mean(v);
  double sum = 0;
  for (double x : v) sum += (x - m) * (x - m);
  return std::sqrt(sum / static_cast<double>(v.size() - 1));
}

}  // namespace

std::vector<ResponseData> response_setups(const std::vector<TimeRecord>& records, const ResponseSelection& selection) {
  if (records.empty()) throw DataError("output-only modal analysis needs at least one time record");
  std::vector<std::vector<std::string>> keys;  // each setup's responses
  std::vector<std::vector<TimeRecord>> groups;
  for (const TimeRecord& r : records) {
    std::vector<std::string> names;
    for (const Signal& s : r.signals)
      if (!contains(selection.ignore, s.name)) names.push_back(s.name);
    const auto it = std::find(keys.begin(), keys.end(), names);
    if (it == keys.end()) {
      keys.push_back(names);
      groups.push_back({r});
    } else {
      groups[static_cast<std::size_t>(it - keys.begin())].push_back(r);
    }
  }
  if (groups.size() == 1) return {response_data(records, selection)};
  std::vector<std::string> references = selection.references;
  if (references.empty())
    for (const std::string& name : keys.front()) {
      bool everywhere = true;
      for (const auto& k : keys) everywhere = everywhere && contains(k, name);
      if (everywhere) references.push_back(name);
    }
  if (references.empty())
    throw DataError(groups[1].front().file, 0, 0, "its responses share none with " + groups[0].front().file +
                                                      "'s: setups are merged on responses they have in common");
  std::vector<ResponseData> setups;
  for (std::size_t g = 0; g < groups.size(); ++g) {
    for (const std::string& name : references)
      if (!contains(keys[g], name))
        throw DataError(groups[g].front().file, 0, 0, "reference " + name + " is not among its responses");
    ResponseSelection one = selection;
    one.references = references;
    // The ignored names need not be in every setup: only this setup's are passed on.
    one.ignore.clear();
    for (const std::string& name : selection.ignore)
      if (groups[g].front().find(name)) one.ignore.push_back(name);
    setups.push_back(response_data(groups[g], one));
  }
  return setups;
}

MergedSetups identify_setups(std::vector<ResponseData> setups, const OutputOnlyOptions& options) {
  MergedSetups out;
  out.setups = std::move(setups);
  for (const ResponseData& s : out.setups) {
    try {
      out.per_setup.push_back(identify_output_only(s, options));
    } catch (const std::invalid_argument& e) {  // this setup's records cannot serve the method: say which
      throw DataError(s.files.front(), 0, 0, e.what());
    }
  }
  ResponseData& data = out.data;
  for (const ResponseData& s : out.setups) {
    data.files.insert(data.files.end(), s.files.begin(), s.files.end());
    for (const std::string& c : s.channels)
      if (!contains(data.channels, c)) data.channels.push_back(c);
    for (const std::string& n : s.notes)
      if (!contains(data.notes, n)) data.notes.push_back(n);
  }
  const ResponseData& first = out.setups.front();
  for (int r : first.references)
    data.references.push_back(index_of(data.channels, first.channels[static_cast<std::size_t>(r)]));
  data.dt = first.dt;
  std::string references;
  for (int r : data.references)
    references += (references.empty() ? "" : ", ") + data.channels[static_cast<std::size_t>(r)];
  data.notes.push_back(std::to_string(out.setups.size()) + " setups merged on the references " + references);

  OutputOnlyIdentification& result = out.result;
  result.method = options.method;
  const double tolerance = options.selection.criteria.frequency;
  const Eigen::Index channels = static_cast<Eigen::Index>(data.channels.size());
  std::vector<std::vector<bool>> used(out.per_setup.size());
  for (std::size_t s = 0; s < out.per_setup.size(); ++s) used[s].assign(out.per_setup[s].modes.size(), false);
  for (std::size_t m = 0; m < out.per_setup[0].modes.size(); ++m) {
    const OperationalMode& anchor = out.per_setup[0].modes[m];
    std::vector<const OperationalMode*> found{&anchor};
    std::string missing;
    for (std::size_t s = 1; s < out.per_setup.size(); ++s) {
      int best = -1;
      for (std::size_t k = 0; k < out.per_setup[s].modes.size(); ++k) {
        const double df = std::abs(out.per_setup[s].modes[k].f_hz - anchor.f_hz);
        if (df <= tolerance * anchor.f_hz &&
            (best < 0 || df < std::abs(out.per_setup[s].modes[static_cast<std::size_t>(best)].f_hz - anchor.f_hz)))
          best = static_cast<int>(k);
      }
      if (best < 0) {
        missing = out.setups[s].files.front();
        break;
      }
      used[s][static_cast<std::size_t>(best)] = true;
      found.push_back(&out.per_setup[s].modes[static_cast<std::size_t>(best)]);
    }
    if (!missing.empty()) {
      SelectedPole p;
      p.f_hz = anchor.f_hz;
      p.zeta = anchor.zeta;
      p.lambda = anchor.lambda;
      p.support = anchor.support;
      result.rejected.push_back({p, "no mode within " + std::to_string(static_cast<int>(100 * tolerance)) +
                                        " % in the setup of " + missing});
      continue;
    }
    OperationalMode merged;
    std::vector<double> f, zeta;
    Eigen::VectorXcd shape = Eigen::VectorXcd::Zero(channels);
    std::vector<bool> filled(static_cast<std::size_t>(channels), false);
    for (std::size_t s = 0; s < found.size(); ++s) {
      const ResponseData& setup = out.setups[s];
      const OperationalMode& mode = *found[s];
      f.push_back(mode.f_hz);
      zeta.push_back(mode.zeta);
      // Scale to the shape assembled so far on the references (all filled by the first setup).
      std::complex<double> alpha = 1;
      if (s > 0) {
        std::complex<double> num = 0;
        double den = 0;
        for (int r : setup.references) {
          const std::complex<double> mine = mode.shape[r];
          num += std::conj(mine) * shape[index_of(data.channels, setup.channels[static_cast<std::size_t>(r)])];
          den += std::norm(mine);
        }
        alpha = den > 0 ? num / den : 0.0;
      }
      for (std::size_t c = 0; c < setup.channels.size(); ++c) {
        const int g = index_of(data.channels, setup.channels[c]);
        if (filled[static_cast<std::size_t>(g)]) continue;
        shape[g] = alpha * mode.shape[static_cast<Eigen::Index>(c)];
        filled[static_cast<std::size_t>(g)] = true;
      }
    }
    merged.f_hz = mean(f);
    merged.zeta = mean(zeta);
    merged.f_scatter_hz = deviation(f);
    merged.zeta_scatter = deviation(zeta);
    const double w = numerics::kTwoPi * merged.f_hz;
    merged.lambda = {-merged.zeta * w, w * std::sqrt(std::max(0.0, 1 - merged.zeta * merged.zeta))};
    merged.support = anchor.support;
    merged.contribution = anchor.contribution;
    merged.shape = normalize_shape(shape);
    merged.mpc = modal_phase_collinearity(merged.shape);
    merged.mpd_deg = mean_phase_deviation_deg(merged.shape);
    result.modes.push_back(std::move(merged));
  }
  for (std::size_t s = 1; s < out.per_setup.size(); ++s)
    for (std::size_t k = 0; k < out.per_setup[s].modes.size(); ++k)
      if (!used[s][k]) {
        const OperationalMode& mode = out.per_setup[s].modes[k];
        SelectedPole p;
        p.f_hz = mode.f_hz;
        p.zeta = mode.zeta;
        p.lambda = mode.lambda;
        p.support = mode.support;
        result.rejected.push_back({p, "found in the setup of " + out.setups[s].files.front() + " but not within " +
                                          std::to_string(static_cast<int>(100 * tolerance)) + " % of " +
                                          hz(mode.f_hz) + " in the first setup's"});
      }
  const Eigen::Index n = static_cast<Eigen::Index>(result.modes.size());
  result.auto_mac.resize(n, n);
  for (Eigen::Index i = 0; i < n; ++i)
    for (Eigen::Index j = 0; j < n; ++j)
      result.auto_mac(i, j) = modal_detail::shape_mac(result.modes[static_cast<std::size_t>(i)].shape,
                                                      result.modes[static_cast<std::size_t>(j)].shape);
  return out;
}

}  // namespace mbgen
