#include "diagnosis/engine/chain_selection.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>

#include <mbgen/residuals/chain_scores.hpp>

#include "diagnosis/engine/candidate_judging.hpp"
#include "diagnosis/engine/text_format.hpp"

namespace mbgen::diagnosis {

namespace {

// Chain candidates fitted per round: the best by their statistic.
constexpr std::size_t kChainFits = 3;
// How close the slope of log |data / model| against log f must come to a whole number k for data of another form
// ((i w)^k off the model) to be taken as evidence: nearer to k than to any other whole number, 0 (the form declared)
// included. The candidate is then fitted and judged like any other; the slope only decides that it is. (A quarter of
// a decade per decade missed a drawn mdof2 whose d2 was a mobility: slope 0.75, the fit bent to an acceleration.)
constexpr double kFormSlopeTolerance = 0.5;

// Time derivatives of displacement an output kind reads ("displacement" 0, "velocity" 1, "acceleration" 2).
int derivative_order(const std::string& kind) { return kind == "velocity" ? 1 : kind == "acceleration" ? 2 : 0; }

}  // namespace

std::vector<Extension> chain_candidates_worth_fitting(std::vector<Extension> extensions, const ModelState& current,
                                                      const std::vector<ChannelResidual>& prior_channels,
                                                      const std::vector<ReversedDrivingPoint>& reversed_points,
                                                      const std::function<void(const std::string&)>& say) {
  const double price = std::log(std::max(2.0, static_cast<double>(current.fit.residual_count)));
  // Evidence in tiers, by how little it leans on a fit: 0 the data alone (a driving point's phase), 1 the data's
  // magnitude trend against the priors (another form), 2 the current fit, 3 only the priors' chi-square.
  struct Worth {
    int tier;
    double statistic;
    std::size_t index;
  };
  std::vector<Worth> worth;
  for (std::size_t k = 0; k < extensions.size(); ++k) {
    const Extension& e = extensions[k];
    const std::string kind = e.target.substr(0, e.target.find(':'));
    const std::string what = e.target.substr(e.target.find(':') + 1);
    double statistic = 0;
    int tier = 2;
    std::string seen;
    if (kind == "form") {
      const auto declared = std::find_if(current.model.outputs.begin(), current.model.outputs.end(),
                                         [&](const ir::Output& o) { return o.name == what; });
      if (declared == current.model.outputs.end()) continue;
      const int derivatives = derivative_order(e.variant) - derivative_order(ir::to_string(declared->kind));
      // At the fit, else at the priors in the last tier: a fit bends the structure to follow an output of another
      // form (mdof2 with d2 a mobility: fitted, only an acceleration "fitted better"), but at priors a few per cent
      // off the truth every output's model is off by more than the noise, and multiplying it by (i w)^k "fitted
      // better" on all three outputs of a drawn spindle; ranked with the fit's evidence they crowded out the
      // calibration error its data had.
      const double at_fit = form_gain(current.channels, what, derivatives),
                   at_priors = form_gain(prior_channels, what, derivatives);
      // And the magnitude's trend: data of another form stand (i w)^k off the model over the band, whatever the
      // resonances do (mdof2, modes damped at 0.05 % on 0.25 Hz lines: at the fit and at the priors alike the
      // peaks lay elsewhere, and chi^2 saw no form). A slope nearest to k != 0 is evidence that needs no fit: its
      // own tier, ahead of the fit's. A fit gone wrong raises every output's chi-square gains alike (a drawn
      // spindle whose xs_front was a mobility, fitted to nrmse 0.99: the slope read 1.00 there and -0.01 to 0.12
      // on the others, while three candidates of the others ranked above it by the fit's chi-square and took the
      // three places). In those 8 draws the mobility's slope read 0.96-1.03, the declared forms' -0.11 to 0.12.
      const double slope = magnitude_slope(prior_channels, what);
      const bool trend = derivatives != 0 && std::abs(slope - derivatives) < kFormSlopeTolerance;
      tier = trend ? 1 : at_fit > price ? 2 : 3;
      statistic = trend ? std::max({at_fit, at_priors, price + 1}) : tier == 2 ? at_fit : at_priors;
      seen = "as its " + e.variant +
             format(", the data fit better by %.1f in chi-square (at the priors %.1f; ", at_fit, at_priors) +
             format("their magnitude's slope against the priors' %.2f decades per decade)", slope);
    } else if (kind == "swap") {
      const std::size_t comma = what.find(',');
      const std::string a = what.substr(0, comma), b = what.substr(comma + 1);
      const double at_fit = swap_gain(current.channels, a, b), at_priors = swap_gain(prior_channels, a, b);
      statistic = std::max(at_fit, at_priors);
      seen = format("exchanged, the data fit better by %.1f in chi-square (at the priors %.1f)", at_fit, at_priors);
    } else {
      const auto selected = [&](const std::string& channel) {
        const std::size_t slash = channel.find('/');
        return kind == "gain" ? channel.substr(0, slash) == what : channel.substr(slash + 1) == what;
      };
      // At the fit, and for the sign at the priors: a fit bends the structure to follow a reversed channel (on a
      // spindle whose xh_front reads -1 times the truth, the fit put a mode 20 % off and read a factor of +0.76
      // there), the priors do not. A negative factor at the priors is taken (the polarity variant, with the priors'
      // statistic); otherwise the fit's statistic ranks: priors a few per cent off the truth raise the priors'
      // statistic on every channel alike (a drawn spindle: factors of 0.43-0.46 on all, where xs_rear alone read
      // 1.12 times the truth), and ranking by it fitted the wrong outputs.
      const GainScore at_fit = gain_score(current.channels, selected);
      const GainScore at_priors = gain_score(prior_channels, selected);
      const GainScore& s = at_priors.factor < 0 && at_priors.statistic > price ? at_priors : at_fit;
      const auto factor = [&](const GainScore& g) { return kind == "gain" ? g.factor : 1 / g.factor; };
      seen = format("the data read %.4g times the model (score statistic %.1f; at the priors %.4g, ", factor(at_fit),
                    at_fit.statistic, factor(at_priors)) +
             format("%.1f)", at_priors.statistic);
      // A driving point that gives out power says, without any model, that its force or its sensor has the wrong
      // sign: both polarities are fitted, first, whatever the factors read. A structure fitted to reversed data
      // (every mode of a shear tower shaken at its roof, with the force's sign reversed) reads positive factors
      // at the fit and meaningless ones at priors whose modes lie elsewhere.
      const bool reversed =
          std::any_of(reversed_points.begin(), reversed_points.end(),
                      [&](const ReversedDrivingPoint& p) { return (kind == "gain" ? p.output : p.input) == what; });
      const bool negative = e.variant == "polarity" || e.variant == "reversed";
      if (reversed && negative) {
        tier = 0;
        statistic = std::numeric_limits<double>::infinity();
        seen = "a driving point on it gives out power (the data's phase; no model needed); " + seen;
      } else {
        if (negative != (s.factor < 0)) continue;
        statistic = s.statistic;
      }
    }
    if (!(statistic > price)) continue;
    say("measurement chain: " + label(e) + ": " + seen);
    worth.push_back({tier, statistic, k});
  }
  // The candidates of the kChainFits strongest pieces of evidence are fitted (each with the variants that passed),
  // in enumeration order: by tier, then by statistic.
  std::stable_sort(worth.begin(), worth.end(), [](const Worth& a, const Worth& b) {
    return a.tier != b.tier ? a.tier < b.tier : a.statistic > b.statistic;
  });
  std::set<std::string> ids;
  for (const Worth& w : worth)
    if (ids.size() < kChainFits) ids.insert(extensions[w.index].id);
  worth.erase(
      std::remove_if(worth.begin(), worth.end(), [&](const Worth& w) { return !ids.count(extensions[w.index].id); }),
      worth.end());
  std::sort(worth.begin(), worth.end(), [](const Worth& a, const Worth& b) { return a.index < b.index; });
  std::vector<Extension> out;
  for (const Worth& w : worth) out.push_back(std::move(extensions[w.index]));
  return out;
}

}  // namespace mbgen::diagnosis
