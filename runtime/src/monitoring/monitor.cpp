// The monitoring loop: fit each data set, learn the baseline, run the CUSUMs, report changes once
// (runtime/include/mbgen/monitoring/monitor.hpp, docs/monitor.md).
#include "mbgen/monitoring/monitor.hpp"

#include "mbgen/monitoring/change_detection.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "text/string_format.hpp"

namespace mbgen {

namespace {

// Numbers in the change messages: four significant digits.
std::string g4(double x) { return detail::format("%.4g", x); }

const ParameterEstimate* find_estimate(const FitResult& r, const std::string& name) {
  for (const ParameterEstimate& p : r.parameters)
    if (p.name == name) return &p;
  return nullptr;
}

// An estimate the test can use: fitted, identifiable (not at a bound, not kept at its prior), with a finite std.
const ParameterEstimate* usable(const FitResult& r, const std::string& name) {
  const ParameterEstimate* p = find_estimate(r, name);
  return p && p->estimated && p->identifiable && std::isfinite(p->std) && std::isfinite(p->value) ? p : nullptr;
}

}  // namespace

MonitorResult monitor(const Model& model, const std::vector<DataSet>& data,
                      const std::vector<std::optional<std::string>>& times, const MonitorOptions& options) {
  const int n_sets = static_cast<int>(data.size());
  const int n_base = options.baseline;
  if (n_base < 2) throw FitError("the baseline needs at least 2 data sets (their spread is the scatter)");
  if (n_sets < n_base + 1)
    throw FitError("monitoring needs more data sets than the baseline's " + std::to_string(n_base) + ", got " +
                   std::to_string(n_sets));
  if (!(options.reference_shift > 0) || !(options.run_length > 1) || !(options.structural_ratio > 1))
    throw FitError("monitor: the reference shift must be positive, the run length and structural ratio above 1");
  const ModelInfo info = model.info();

  MonitorResult result;
  result.baseline = n_base;
  result.k = options.reference_shift / 2;
  result.run_length = options.run_length;
  result.structural_ratio = options.structural_ratio;

  // The cold priors: the model's values with the options' overrides. Every warm fit also starts there, so that a
  // change too large for the warm start's neighbourhood is still found.
  std::map<std::string, double> cold = options.fit.values;

  std::vector<TwoSidedCusum> cusums;
  std::vector<SelfStartingReference> references;  // per monitored parameter: its level and scatter
  bool in_structural = false;
  int regime_first = n_base;  // the first set tested against the current references

  for (int i = 0; i < n_sets; ++i) {
    const DataSet& set = data[static_cast<std::size_t>(i)];
    if (options.progress) options.progress({i, n_sets, set.file(), "fitting"});
    FitOptions fo = options.fit;
    if (i > 0) {
      const FitResult& previous = result.series.back().fit;
      for (const ParameterEstimate& p : previous.parameters) {
        if (!p.estimated) continue;
        fo.values[p.name] = p.value;
        const int index = info.parameter_index(p.name);
        const auto c = cold.find(p.name);
        fo.also_start_at[p.name] = c != cold.end() ? c->second : info.parameters[static_cast<std::size_t>(index)].value;
      }
      fo.starts = std::min(options.warm_starts, options.fit.starts);
    }
    if (options.add_starts) options.add_starts(set, fo);
    MonitorPoint point;
    point.file = set.file();
    point.time = i < static_cast<int>(times.size()) ? times[static_cast<std::size_t>(i)] : std::nullopt;
    point.fit = fit(model, {set}, fo);
    point.misfit = options.misfit ? options.misfit(set, point.fit) : point.fit.residual_variance;
    point.baseline = i < n_base;
    result.series.push_back(std::move(point));
    MonitorPoint& here = result.series.back();

    if (i < n_base) {
      if (i == n_base - 1) {
        // Learn the baseline: the parameters usable in every baseline set are monitored.
        for (const ParameterEstimate& p : here.fit.parameters) {
          std::vector<double> values, stds;
          for (const MonitorPoint& b : result.series)
            if (const ParameterEstimate* e = usable(b.fit, p.name)) {
              values.push_back(e->value);
              stds.push_back(e->std);
            }
          if (static_cast<int>(values.size()) != n_base) continue;
          const BaselineScatter s = baseline_scatter(values, stds);
          result.parameters.push_back({p.name, p.unit, s.mean, s.sigma, s.sample_std, s.fit_std});
          references.emplace_back(values, s.fit_std);
        }
        if (result.parameters.empty())
          throw FitError("no parameter was estimated and identifiable in every baseline data set: nothing to monitor");
        // The stated false-alarm rate split in halves between the CUSUMs and the single-set limit (rare events'
        // rates add): a large step is then found at its first set even where the shifts' t tails, with the scatter
        // known from few sets, keep its first value from crossing h alone.
        const int streams = static_cast<int>(result.parameters.size());
        result.h = scheme_threshold(result.k, 2 * options.run_length, streams);
        result.single_set_limit = mbgen::single_set_limit(2 * options.run_length, streams);
        for (std::size_t j = 0; j < result.parameters.size(); ++j) {
          cusums.emplace_back(result.k, result.h, result.single_set_limit);
          cusums.back().reset(i);
        }
        result.baseline_misfit = 0;
        for (const MonitorPoint& b : result.series) result.baseline_misfit = std::max(result.baseline_misfit, b.misfit);
      }
      if (options.progress) options.progress({i, n_sets, set.file(), "baseline"});
      continue;
    }

    // The sequential test.
    std::vector<int> alarms(result.parameters.size(), 0);
    bool any_alarm = false;
    for (std::size_t j = 0; j < result.parameters.size(); ++j) {
      const std::string& name = result.parameters[j].name;
      here.reference[name] = references[j].mean();
      const ParameterEstimate* e = usable(here.fit, name);
      if (!e) {  // no information on it in this set: the CUSUM waits
        here.shift[name] = std::numeric_limits<double>::quiet_NaN();
      } else {
        const double z = references[j].z(e->value, e->std);
        here.shift[name] = z;
        alarms[j] = cusums[j].update(z, i);
        any_alarm = any_alarm || alarms[j] != 0;
      }
      here.cusum_up[name] = cusums[j].upper();
      here.cusum_down[name] = cusums[j].lower();
    }
    const double ratio = result.baseline_misfit > 0 ? here.misfit / result.baseline_misfit
                                                    : std::numeric_limits<double>::infinity();
    const bool new_structural = !in_structural && ratio > options.structural_ratio;
    if (new_structural) in_structural = true;
    else if (in_structural && ratio < 1 + (options.structural_ratio - 1) / 2) in_structural = false;

    if (any_alarm || new_structural) {
      MonitorChange change;
      change.index = i;
      change.onset = i;
      change.time = here.time;
      change.structural = new_structural;
      change.misfit_ratio = ratio;
      // The onset: the change point of a shift of unknown size in the parameters that alarmed, over the sets tested
      // since the last reset (change_detection.hpp; the CUSUM's own estimate came out two sets early on a step).
      std::vector<std::vector<double>> z;
      for (std::size_t j = 0; j < alarms.size(); ++j) {
        if (alarms[j] == 0) continue;
        z.emplace_back();
        for (int s = regime_first; s <= i; ++s)
          z.back().push_back(result.series[static_cast<std::size_t>(s)].shift.at(result.parameters[j].name));
      }
      if (!z.empty()) change.onset = regime_first + change_point(z);
      // A new regime: every parameter's reference is learned afresh, starting from this set alone. The sets between
      // the estimated onset and now would estimate it better, but an onset estimated a set too early would mix the
      // old level in, and the next set would alarm again for the same change.
      std::string moved;
      for (std::size_t j = 0; j < result.parameters.size(); ++j) {
        const std::string& name = result.parameters[j].name;
        const double before = references[j].mean();
        if (const ParameterEstimate* e = usable(here.fit, name)) references[j].restart(e->value);
        cusums[j].reset(i);
        if (alarms[j] == 0) continue;
        change.parameters.push_back(name);
        change.direction[name] = alarms[j];
        const double after = references[j].mean();
        moved += (moved.empty() ? "" : ", ") + name + (alarms[j] > 0 ? " rose" : " fell") + " from " + g4(before) +
                 " to " + g4(after);
        if (before != 0) moved += " (" + std::string(after > before ? "+" : "") + g4(100 * (after - before) / before) + " %)";
      }
      const std::string where = "data set " + std::to_string(i) + " (" + here.file + ")";
      // A structural change is said first: the parameters then moved only as far as the fit could bend them towards
      // what the model lacks (a loose mount showed as four bearing parameters moving), which is not the cause.
      if (new_structural) {
        change.text = "The model no longer fits " + where + ": its misfit is " + g4(ratio) +
                      " times the baseline's, beyond what any of its parameters explains (a structural change).";
        if (!moved.empty())
          change.text += " Absorbing what it can, the fit moved its parameters: " + moved + ", since data set " +
                         std::to_string(change.onset) + ".";
      } else if (!moved.empty()) {
        change.text = moved + ", since data set " + std::to_string(change.onset) + "; detected at " + where + ".";
      }
      result.changes.push_back(std::move(change));
      regime_first = i + 1;
    } else {
      // No change: this set joins the reference (after being tested against it), which so keeps learning, the
      // baseline's as well as a re-learned one (a self-starting CUSUM, Hawkins 1987). A reference fixed at the
      // mean of three sets is off by sigma/sqrt(3) = 0.58 sigma, and the CUSUM sums that error set after set: on
      // a scatter-only mdof2 series three parameters stood 1.3 sigma above it in every later set and a statistic
      // reached 4.8 of h = 7.7 within five sets.
      for (std::size_t j = 0; j < result.parameters.size(); ++j)
        if (const ParameterEstimate* e = usable(here.fit, result.parameters[j].name)) references[j].join(e->value);
    }
    if (options.progress) {
      std::string line = "nrmse " + g4(here.fit.nrmse) + ", misfit " + g4(ratio) + "x baseline";
      if (any_alarm || new_structural) line += ": CHANGE: " + result.changes.back().text;
      options.progress({i, n_sets, set.file(), line});
    }
  }
  return result;
}

}  // namespace mbgen
