// fit_modal: the parameters fitted to modes identified from FRFs, after Ellinger & Zaeh 2022 (docs/methods.md#modal).
// The pairing and the per-mode objectives are in modal_objectives.cpp, the configurations (`# set` values) and their
// reference modes in modal_configurations.cpp; here the refusals, the Sobol partition, the repeated local
// optimisation of each subproblem, the damping least squares, and the result.
#include "mbgen/methods/modal_fit.hpp"

#include "method_result.hpp"
#include "modal_configurations.hpp"
#include "modal_objectives.hpp"
#include "modal_solve.hpp"

#include "mbgen/modal_identification/modal_pairing.hpp"
#include "mbgen/sensitivity/sensitivity.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include "text/string_format.hpp"

namespace mbgen {

namespace {

using methods::LocalOptimum;
using methods::ModalComparison;
using methods::local_fit;
using methods::residuals_at;

constexpr int kSobolSamples = 256;
constexpr int kMaxSweeps = 30;
// The sweeps end when no parameter moves by more than this in a sweep: they only have to reach the optimum's basin
// (block coordinate descent converges linearly where subproblems share modes); the joint step after them converges.
constexpr double kSweepTolerance = 1e-3;
constexpr int kDampingIterations = 4;
// A mass/stiffness parameter whose total Sobol index is below this for every mode's objective is not estimated: the
// identified modes do not depend on it (the paper's sensitivity threshold).
constexpr double kInfluence = 0.01;     // the paper's linear solve, then relinearisations at the estimate

using methods::ModalConfiguration;
using methods::ModeRef;
using Problem = methods::ModalProblem;
using methods::compare_all;
using methods::hz_list;
using methods::in_configuration;
using methods::set_label;

// The range a parameter is sampled and restarted in: within a factor `spread` of `centre`, cut to its bounds.
std::pair<double, double> log_range(const ParameterInfo& q, double centre, double spread) {
  const double lo = std::max(centre / spread, q.lower > 0 ? q.lower : centre / spread);
  const double hi = std::min(centre * spread, q.upper);
  return {std::log(lo), std::log(std::max(hi, lo))};
}

struct Subproblem {
  int mode = 0;                 // the mode whose parameters these are
  std::vector<int> parameters;  // model indices
  std::vector<int> modes;       // objectives: the mode and, where it has too few, the next most influenced
};

// The spread of one subproblem's repetitions. The paper's test: the standard deviation of each parameter over all
// repetitions (relative_std, relative to the best). Besides, which repetitions agree with the best (every parameter
// within 1e-3), the spread among those (agreeing_relative_std), and the costs of those that stopped elsewhere: local
// optima, all worse than the best when the best is the global optimum.
nlohmann::json spread(const ModelInfo& info, const Subproblem& s, const std::vector<LocalOptimum>& reps, int best) {
  nlohmann::json j;
  const LocalOptimum& b = reps[static_cast<std::size_t>(best)];
  j["mode"] = s.mode;
  j["repetitions"] = reps.size();
  j["best_cost"] = b.cost;
  std::vector<bool> agrees;
  std::vector<double> others;
  for (const LocalOptimum& o : reps) {
    double dev = 0;
    for (int i : s.parameters) dev = std::max(dev, std::abs(o.p[i] / b.p[i] - 1));
    agrees.push_back(dev < 1e-3);
    if (!agrees.back()) others.push_back(o.cost);
  }
  j["agreeing"] = std::count(agrees.begin(), agrees.end(), true);
  j["local_optimum_costs"] = others;
  auto stats = [&](int i, bool agreeing_only) {
    double n = 0, mean = 0, var = 0;
    for (std::size_t k = 0; k < reps.size(); ++k)
      if (!agreeing_only || agrees[k]) n += 1, mean += reps[k].p[i];
    mean /= n;
    for (std::size_t k = 0; k < reps.size(); ++k)
      if (!agreeing_only || agrees[k]) var += (reps[k].p[i] - mean) * (reps[k].p[i] - mean);
    return std::pair{mean, std::sqrt(var / std::max(n - 1, 1.0)) / std::abs(b.p[i])};
  };
  nlohmann::json per = nlohmann::json::object();
  for (int i : s.parameters) {
    const auto [mean, rel] = stats(i, false);
    per[info.parameters[static_cast<std::size_t>(i)].name] = {
        {"best", b.p[i]}, {"mean", mean}, {"relative_std", rel}, {"agreeing_relative_std", stats(i, true).second}};
  }
  j["parameters"] = per;
  return j;
}

// What stays fixed during one run: the configurations and their reference modes, the prior, and the parameters to
// estimate by class.
struct ModalSetup {
  std::vector<ModalConfiguration> configurations;
  Eigen::VectorXd prior;
  std::vector<int> candidates;
  std::vector<int> set_everywhere;  // set by `# set` in every configuration: acts in none of the data
  std::vector<int> structural;      // act on M or K
  std::vector<int> damping;         // act on C
  std::vector<ModeRef> modes;       // every configuration's reference modes
  int nr = 0;                       // modes.size()
};

const IdentifiedMode& reference_of(const ModalSetup& s, int m) {
  const ModeRef& mr = s.modes[static_cast<std::size_t>(m)];
  return s.configurations[static_cast<std::size_t>(mr.configuration)].reference[static_cast<std::size_t>(mr.mode)];
}

int channels_of(const ModalSetup& s, int m) {
  return static_cast<int>(
      s.configurations[static_cast<std::size_t>(s.modes[static_cast<std::size_t>(m)].configuration)].data.channels.size());
}

// Refuses modes too few for the parameters: each mode gives a frequency, channels - 1 shape ratios and a scale for
// the mass/stiffness parameters, and one damping ratio for the damping parameters. The refusal says which
// parameters to make known (--fix works for fit, diagnose, monitor and sensitivity; docs/cli.md).
void refuse_too_few_modes(const ModelInfo& info, const ModalSetup& s) {
  int information = 0;
  for (const ModalConfiguration& cf : s.configurations)
    information += static_cast<int>(cf.reference.size()) *
                   methods::information_per_mode(static_cast<int>(cf.data.channels.size()));
  const auto advice = [&](const std::vector<int>& which, std::size_t excess) {
    std::string names;
    for (int i : which) names += (names.empty() ? "" : ", ") + info.parameters[static_cast<std::size_t>(i)].name;
    return "; make at least " + std::to_string(excess) + " of them known with --fix NAME[=VALUE] (" + names +
           "), or add data that show more modes";
  };
  const std::vector<ModalConfiguration>& configurations = s.configurations;
  const std::vector<int>& structural = s.structural;
  const int nr = s.nr;
  std::string channel_text;
  for (const ModalConfiguration& cf : configurations)
    channel_text += (channel_text.empty() ? "" : ", ") + std::to_string(cf.data.channels.size());
  if (information < static_cast<int>(structural.size())) {
    if (configurations.size() > 1)
      throw FitError("fit: error: --method modal: the FRFs of the " + std::to_string(configurations.size()) +
                     " configurations show " + std::to_string(nr) + " mode(s) (" + hz_list(configurations) +
                     ") on " + channel_text + " channel(s), which give " + std::to_string(information) +
                     " numbers (per mode: frequency, channels - 1 shape ratios, scale), fewer than the " +
                     std::to_string(structural.size()) + " mass/stiffness parameters to estimate" +
                     advice(structural, structural.size() - static_cast<std::size_t>(information)));
    const int channels = static_cast<int>(configurations.front().data.channels.size());
    throw FitError("fit: error: --method modal: the FRFs show " + std::to_string(nr) + " mode(s) (" +
                   hz_list(configurations) + ") on " + std::to_string(channels) + " channel(s), which give " +
                   std::to_string(information) + " numbers (per mode: frequency, " + std::to_string(channels - 1) +
                   " shape ratio(s), scale), fewer "
                   "than the " +
                   std::to_string(structural.size()) + " mass/stiffness parameters to estimate" +
                   advice(structural, structural.size() - static_cast<std::size_t>(information)));
  }
  if (nr < static_cast<int>(s.damping.size()))
    throw FitError("fit: error: --method modal: the FRFs show " + std::to_string(nr) + " mode(s) (" +
                   hz_list(configurations) + "), fewer than the " + std::to_string(s.damping.size()) +
                   " damping parameters to estimate (one "
                   "modal damping ratio per mode)" +
                   advice(s.damping, s.damping.size() - static_cast<std::size_t>(nr)));
}

// Setup: the data sets grouped into configurations by their `# set` values, the parameters to estimate split into
// mass/stiffness and damping (a parameter that every configuration sets acts in none of the data: kept at its prior,
// as the Sobol threshold would find), and the reference modes of each configuration by experimental modal analysis
// of its FRFs (automatic pole selection) in the quantity the model's outputs are; refused where they are too few.
ModalSetup modal_setup(const Model& model, const std::vector<DataSet>& data, const FitOptions& options) {
  const ModelInfo& info = model.info();
  ModalSetup s;
  s.configurations = methods::group_configurations(info, data);
  s.prior = methods::checked_prior(model, data, options);
  s.candidates = methods::candidate_parameters(info, options);
  if (s.candidates.empty()) throw FitError("fit: --method modal: the model has no parameter to estimate");
  std::vector<int> active;
  for (int i : s.candidates) {
    const std::string& name = info.parameters[static_cast<std::size_t>(i)].name;
    bool everywhere = true;
    for (const ModalConfiguration& c : s.configurations) everywhere = everywhere && c.set.count(name);
    (everywhere ? s.set_everywhere : active).push_back(i);
  }
  if (active.empty())
    throw FitError("fit: error: --method modal: every parameter to estimate is set by `# set` in every data set");
  methods::ParameterClasses classes = methods::classify_parameters(model, s.prior, active);
  if (!classes.other.empty()) throw FitError(classes.other.front().second);
  s.structural = classes.structural;
  s.damping = classes.damping;
  s.modes = methods::identify_reference_modes(model, s.prior, s.configurations);
  s.nr = static_cast<int>(s.modes.size());
  refuse_too_few_modes(info, s);
  return s;
}

// The model at its prior must show at least as many oscillating modes as identified in each configuration, or the
// modes cannot be paired.
void check_prior_modes(const Model& model, const ModalSetup& s) {
  const bool several = s.configurations.size() > 1;
  for (const ModalConfiguration& cf : s.configurations)
    if (!methods::compare_modes(model, in_configuration(cf, s.prior), cf.data, cf.reference).ok)
      throw FitError("fit: error: --method modal: the model at its prior" +
                     (several ? " in configuration " + set_label(cf.set) : std::string()) +
                     " has fewer oscillating modes than the " + std::to_string(cf.reference.size()) + " identified (" +
                     hz_list(cf.reference) + ")");
}

// What stays fixed during the solves.
struct ModalContext {
  const ModelInfo& info;
  const FitOptions& options;
  const ModalSetup& setup;
  const Problem& pr;
  double spread_factor = 0;  // the start range: within this factor of the centre
  int starts = 0;            // repetitions of each local optimisation
  std::vector<int> all_modes;
};

// What the steps move.
struct ModalState {
  Eigen::VectorXd p;                // the estimate so far
  std::vector<int> structural;      // the influential mass/stiffness parameters
  std::vector<int> uninfluential;   // below the Sobol threshold for every mode: kept at their priors
  nlohmann::json details;           // method_details.modal
  nlohmann::json damping;           // method_details.modal.damping
  int total_iterations = 0;
  bool joint_converged = true;
};

// The joint problem's outcome: taken (its optimum below the sweeps'), agree (half of its repetitions reach the
// best), confirms (they agree and their best is the estimate).
struct JointOutcome {
  bool taken = false, agree = true, confirms = false;
};

// The configurations and reference modes as method_details shows them.
void describe_reference_modes(const ModalSetup& s, nlohmann::json& details) {
  nlohmann::json jconf = nlohmann::json::array();
  for (const ModalConfiguration& cf : s.configurations)
    jconf.push_back({{"set", cf.set}, {"files", cf.files}, {"modes", cf.reference.size()}});
  details["configurations"] = jconf;
  nlohmann::json jref = nlohmann::json::array();
  for (int m = 0; m < s.nr; ++m) {
    const IdentifiedMode& r = reference_of(s, m);
    jref.push_back({{"configuration", s.modes[static_cast<std::size_t>(m)].configuration},
                    {"f_hz", r.f_hz},
                    {"zeta", r.zeta},
                    {"f_std_hz", std::isfinite(r.f_std_hz) ? r.f_std_hz : 0.0},
                    {"mpc", r.mpc},
                    {"support", r.support}});
  }
  details["reference_modes"] = jref;
  details["shape_criterion"] = "MAC of the residue vectors (light damping: nearly real shapes, where MACXP is MAC)";
}

// The paper's partition: Sobol total indices of each mode's objective (NFD^2 + 1 - MAC + log-scale^2, every mode of
// every configuration) over the start range; each mass/stiffness parameter to the mode whose objective it moves
// most; each mode's objectives, plus those of the modes its parameters move next most until there are as many
// numbers as parameters. Parameters below the threshold for every mode leave `state.structural`.
std::vector<Subproblem> partition_by_sobol(const ModalContext& ctx, ModalState& state) {
  const ModelInfo& info = ctx.info;
  const ModalSetup& s = ctx.setup;
  const Eigen::VectorXd& prior = s.prior;
  const int nr = s.nr;
  std::vector<int>& structural = state.structural;
  std::vector<std::pair<double, double>> range;
  for (int i : structural)
    range.push_back(log_range(info.parameters[static_cast<std::size_t>(i)], prior[i], ctx.spread_factor));
  const auto ks = static_cast<Eigen::Index>(structural.size());
  const std::vector<bool> every(s.configurations.size(), true);
  const auto objective = [&](const Eigen::VectorXd& u) {
    Eigen::VectorXd q = prior;
    for (Eigen::Index j = 0; j < ks; ++j) {
      const auto& [lo, hi] = range[static_cast<std::size_t>(j)];
      q[structural[static_cast<std::size_t>(j)]] = std::exp(lo + u[j] * (hi - lo));
    }
    Eigen::VectorXd out = Eigen::VectorXd::Constant(nr, std::numeric_limits<double>::quiet_NaN());
    const std::vector<ModalComparison> cmp = compare_all(ctx.pr, q, every);
    for (const ModalComparison& c : cmp)
      if (!c.ok) return out;
    for (int m = 0; m < nr; ++m) {
      const ModeRef& mr = s.modes[static_cast<std::size_t>(m)];
      const ModalComparison& c = cmp[static_cast<std::size_t>(mr.configuration)];
      const auto rr = static_cast<std::size_t>(mr.mode);
      const IdentifiedMode& ref = reference_of(s, m);
      const double nfd = c.f_hz[rr] / ref.f_hz - 1, scale = std::log(c.residues[rr].norm() / ref.residues.norm());
      out[m] = nfd * nfd + (1 - c.mac[rr]) + scale * scale;
    }
    return out;
  };
  SobolOptions so;
  so.samples = kSobolSamples;
  so.seed = ctx.options.seed;
  so.threads = std::max(ctx.options.threads, 1);
  const SobolIndices sobol = sobol_indices(objective, static_cast<int>(ks), nr, so);
  Eigen::MatrixXd total = sobol.total;
  for (Eigen::Index r = 0; r < total.rows(); ++r)
    for (Eigen::Index j = 0; j < total.cols(); ++j)
      if (!std::isfinite(total(r, j))) total(r, j) = 0;

  for (Eigen::Index j = 0; j < ks; ++j)
    if (!(total.col(j).maxCoeff() >= kInfluence)) state.uninfluential.push_back(structural[static_cast<std::size_t>(j)]);
  std::vector<Subproblem> subs;
  for (int r = 0; r < nr; ++r) {
    Subproblem sub;
    sub.mode = r;
    for (Eigen::Index j = 0; j < ks; ++j) {
      Eigen::Index best = 0;
      if (total.col(j).maxCoeff(&best) >= kInfluence && best == r) sub.parameters.push_back(structural[static_cast<std::size_t>(j)]);
    }
    if (sub.parameters.empty()) continue;
    std::vector<std::pair<double, int>> others;
    for (int m = 0; m < nr; ++m) {
      if (m == r) continue;
      double w = 0;
      for (Eigen::Index j = 0; j < ks; ++j)
        if (std::find(sub.parameters.begin(), sub.parameters.end(), structural[static_cast<std::size_t>(j)]) !=
            sub.parameters.end())
          w += total(m, j);
      others.push_back({-w, m});
    }
    std::sort(others.begin(), others.end());
    sub.modes.push_back(r);
    int numbers = methods::information_per_mode(channels_of(s, r));
    for (const auto& o : others) {
      if (numbers >= static_cast<int>(sub.parameters.size())) break;
      sub.modes.push_back(o.second);
      numbers += methods::information_per_mode(channels_of(s, o.second));
    }
    std::sort(sub.modes.begin(), sub.modes.end());
    subs.push_back(sub);
  }
  nlohmann::json jpart;
  jpart["samples"] = kSobolSamples;
  jpart["range_factor"] = ctx.spread_factor;
  nlohmann::json jtotal = nlohmann::json::object();
  for (Eigen::Index j = 0; j < ks; ++j) {
    std::vector<double> col(total.col(j).data(), total.col(j).data() + nr);
    jtotal[info.parameters[static_cast<std::size_t>(structural[static_cast<std::size_t>(j)])].name] = col;
  }
  jpart["total_index_per_mode"] = jtotal;
  nlohmann::json jsubs = nlohmann::json::array();
  for (const Subproblem& sub : subs) {
    std::vector<std::string> names;
    for (int i : sub.parameters) names.push_back(info.parameters[static_cast<std::size_t>(i)].name);
    std::vector<int> objective_configurations;
    for (int m : sub.modes) objective_configurations.push_back(s.modes[static_cast<std::size_t>(m)].configuration);
    jsubs.push_back({{"mode", sub.mode},
                     {"configuration", s.modes[static_cast<std::size_t>(sub.mode)].configuration},
                     {"parameters", names},
                     {"objective_modes", sub.modes},
                     {"objective_configurations", objective_configurations}});
  }
  jpart["subproblems"] = jsubs;
  std::vector<std::string> kept;
  for (int i : state.uninfluential) {
    kept.push_back(info.parameters[static_cast<std::size_t>(i)].name);
    structural.erase(std::find(structural.begin(), structural.end(), i));
  }
  jpart["not_influential"] = kept;
  jpart["influence_threshold"] = kInfluence;
  std::vector<std::string> set_names;
  for (int i : s.set_everywhere) set_names.push_back(info.parameters[static_cast<std::size_t>(i)].name);
  jpart["set_in_every_configuration"] = set_names;
  state.details["partition"] = jpart;
  return subs;
}

// The subproblems in turn, each from `starts` seeded starts (the current values, then log-uniform within the range
// factor of them), the best repetition kept; sweeps until no parameter moves (block coordinate descent: they only
// have to reach the optimum's basin, the joint steps after them converge).
void sweep_subproblems(const ModalContext& ctx, const std::vector<Subproblem>& subs, ModalState& state) {
  std::mt19937_64 rng(ctx.options.seed);
  nlohmann::json first_spread = nlohmann::json::array(), last_spread = nlohmann::json::array();
  Eigen::VectorXd& p = state.p;
  int sweeps = 0;
  double change = 0;
  for (; sweeps < kMaxSweeps;) {
    ++sweeps;
    change = 0;
    nlohmann::json spreads = nlohmann::json::array();
    for (const Subproblem& s : subs) {
      std::vector<LocalOptimum> reps;
      int best = 0;
      for (int k = 0; k < ctx.starts; ++k) {
        Eigen::VectorXd start = p;
        if (k > 0)
          for (int i : s.parameters) {
            const auto [lo, hi] = log_range(ctx.info.parameters[static_cast<std::size_t>(i)], p[i], ctx.spread_factor);
            start[i] = std::exp(std::uniform_real_distribution<double>(lo, hi)(rng));
          }
        reps.push_back(local_fit(ctx.pr, p, start, s.parameters, s.modes, ctx.options));
        state.total_iterations += reps.back().iterations;
        if (reps.back().cost < reps[static_cast<std::size_t>(best)].cost) best = k;
      }
      for (int i : s.parameters)
        change = std::max(change, std::abs(reps[static_cast<std::size_t>(best)].p[i] / p[i] - 1));
      for (int i : s.parameters) p[i] = reps[static_cast<std::size_t>(best)].p[i];
      spreads.push_back(spread(ctx.info, s, reps, best));
    }
    if (sweeps == 1) first_spread = spreads;
    last_spread = spreads;
    if (change < kSweepTolerance) break;
  }
  state.details["sweeps"] = sweeps;
  state.details["last_sweep_change"] = change;
  state.details["repetitions"] = {{"first_sweep", first_spread}, {"last_sweep", last_spread}};
}

// Damping: the modal damping ratios linear in the damping parameters at fixed M and K,
// zeta_r = zeta_res,r + sum_j q_rj c_j, solved by least squares with rows divided by zeta_ref (the NDD); q by
// differences, relinearised at the estimate (the first solve is the paper's).
void solve_damping(const ModalContext& ctx, ModalState& state) {
  if (ctx.setup.damping.empty()) return;
  nlohmann::json iterations = nlohmann::json::array();
  methods::solve_damping(ctx.pr, ctx.setup.damping, ctx.setup.prior, kDampingIterations, state.p, iterations);
  state.damping["iterations"] = iterations;
}

// The residue scale depends slightly on damping: all mass/stiffness parameters once more against all modes, from
// the estimate, then the damping again.
void joint_polish(const ModalContext& ctx, ModalState& state) {
  double polish_before = 0, polish_after = 0;
  const std::vector<int>& structural = state.structural;
  Eigen::VectorXd& p = state.p;
  if (!structural.empty()) {
    Eigen::VectorXd x(static_cast<Eigen::Index>(structural.size())), r;
    for (std::size_t j = 0; j < structural.size(); ++j) x[static_cast<Eigen::Index>(j)] = std::log(p[structural[j]]);
    if (residuals_at(ctx.pr, p, structural, ctx.all_modes, x, r)) polish_before = r.squaredNorm();
    const LocalOptimum o = local_fit(ctx.pr, p, p, structural, ctx.all_modes, ctx.options);
    state.joint_converged = o.converged;
    state.total_iterations += o.iterations;
    if (o.cost <= polish_before || polish_before == 0) p = o.p;
    polish_after = std::min(o.cost, polish_before > 0 ? polish_before : o.cost);
    solve_damping(ctx, state);
  }
  state.details["joint_polish"] = {{"cost_before", polish_before}, {"cost_after", polish_after}};
}

// The joint problem's own repetitions: every influential mass/stiffness parameter against every mode's objectives,
// from `starts` seeded starts (the priors, then log-uniform within the range factor of them), the paper's test for
// the global optimum applied to the whole problem. The sweeps' subproblems each fit their own modes only, and their
// fixed point need not be the joint optimum: on drawn spindle truths (x FRFs, dampers known) the sweeps ended at
// k_hbx 56-66 % high and k_hbz at its lower bound on 3 of 4 draws, where a joint solve from the priors placed every
// influential stiffness within 1 %. The lower joint cost wins.
JointOutcome joint_repetitions(const ModalContext& ctx, ModalState& state) {
  JointOutcome out;
  const std::vector<int>& structural = state.structural;
  if (structural.empty()) return out;
  const Eigen::VectorXd& prior = ctx.setup.prior;
  Eigen::VectorXd& p = state.p;
  Eigen::VectorXd x(static_cast<Eigen::Index>(structural.size())), r;
  for (std::size_t j = 0; j < structural.size(); ++j) x[static_cast<Eigen::Index>(j)] = std::log(p[structural[j]]);
  const double current = residuals_at(ctx.pr, p, structural, ctx.all_modes, x, r) ? r.squaredNorm()
                                                                                   : std::numeric_limits<double>::infinity();
  std::mt19937_64 joint_rng(ctx.options.seed ^ 0x9e3779b97f4a7c15ULL);  // its own stream: the sweeps' stay as they were
  std::vector<LocalOptimum> reps;
  int best = 0;
  for (int k = 0; k < ctx.starts; ++k) {
    Eigen::VectorXd start = p;
    for (int i : structural) {
      const auto [lo, hi] = log_range(ctx.info.parameters[static_cast<std::size_t>(i)], prior[i], ctx.spread_factor);
      start[i] = k == 0 ? prior[i] : std::exp(std::uniform_real_distribution<double>(lo, hi)(joint_rng));
    }
    reps.push_back(local_fit(ctx.pr, p, start, structural, ctx.all_modes, ctx.options));
    state.total_iterations += reps.back().iterations;
    if (reps.back().cost < reps[static_cast<std::size_t>(best)].cost) best = k;
  }
  const LocalOptimum& b = reps[static_cast<std::size_t>(best)];
  out.taken = b.cost < current * (1 - 1e-6);
  nlohmann::json j = spread(ctx.info, Subproblem{-1, structural, ctx.all_modes}, reps, best);
  j.erase("mode");
  j["cost_of_sweeps"] = std::isfinite(current) ? current : -1.0;
  j["taken"] = out.taken;
  out.agree = 2 * j["agreeing"].get<int>() >= static_cast<int>(reps.size());
  double deviation = 0;
  for (int i : structural) deviation = std::max(deviation, std::abs(b.p[i] / p[i] - 1));
  out.confirms = out.agree && (out.taken || deviation < 1e-3);
  state.details["joint_repetitions"] = j;
  if (out.taken) {
    p = b.p;
    state.joint_converged = b.converged;
    solve_damping(ctx, state);
  }
  return out;
}

// Agreement per mode at the estimate: frequencies, MAC, scale and damping against the reference.
void agreement_at_estimate(const ModalContext& ctx, ModalState& state) {
  const ModalSetup& s = ctx.setup;
  const std::vector<ModalComparison> fin = compare_all(ctx.pr, state.p, std::vector<bool>(s.configurations.size(), true));
  for (const ModalComparison& c : fin)
    if (!c.ok) throw FitError("fit: error: --method modal: the model's modes could not be paired at the estimate");
  nlohmann::json agreement = nlohmann::json::array();
  for (int m = 0; m < s.nr; ++m) {
    const ModeRef& mr = s.modes[static_cast<std::size_t>(m)];
    const ModalComparison& c = fin[static_cast<std::size_t>(mr.configuration)];
    const auto rr = static_cast<std::size_t>(mr.mode);
    const IdentifiedMode& ref = reference_of(s, m);
    agreement.push_back({{"configuration", mr.configuration},
                         {"reference_f_hz", ref.f_hz},
                         {"model_f_hz", c.f_hz[rr]},
                         {"nfd", c.f_hz[rr] / ref.f_hz - 1},
                         {"mac", c.mac[rr]},
                         {"scale_log_ratio", std::log(c.residues[rr].norm() / ref.residues.norm())},
                         {"reference_zeta", ref.zeta},
                         {"model_zeta", c.zeta[rr]},
                         {"ndd", (c.zeta[rr] - ref.zeta) / ref.zeta}});
  }
  state.details["agreement"] = agreement;
}

// Finish: each candidate's estimate (not estimated where uninfluential or set everywhere; at a bound, not
// identifiable) and the output-error numbers every method reports; no covariance, since the modal objectives carry
// no noise model.
FitResult finish(const Model& model, const std::vector<DataSet>& data, const ModalContext& ctx,
                 const ModalState& state) {
  const ModelInfo& info = ctx.info;
  const ModalSetup& s = ctx.setup;
  const Eigen::VectorXd& p = state.p;
  methods::MethodOutcome outcome;
  outcome.method = "modal";
  outcome.prior = s.prior;
  outcome.values = p;
  for (int i : s.candidates) {
    const ParameterInfo& q = info.parameters[static_cast<std::size_t>(i)];
    methods::ReportedParameter r;
    r.index = i;
    ParameterEstimate& e = r.verdicts;
    e.estimated = std::find(state.uninfluential.begin(), state.uninfluential.end(), i) == state.uninfluential.end() &&
                  std::find(s.set_everywhere.begin(), s.set_everywhere.end(), i) == s.set_everywhere.end();
    const double tol = 1e-9 * std::max(std::abs(p[i]), 1.0);
    if (std::abs(p[i] - q.lower) <= tol) e.at_bound = "lower";
    if (std::abs(p[i] - q.upper) <= tol) e.at_bound = "upper";
    e.identifiable = e.estimated && e.at_bound.empty();
    outcome.parameters.push_back(r);
  }
  outcome.scored = s.candidates;
  outcome.fitted = static_cast<int>(s.candidates.size() - state.uninfluential.size() - s.set_everywhere.size());
  FitResult result;
  methods::finish_result(model, data, ctx.options, outcome, result);
  result.iterations = state.total_iterations;
  return result;
}

// The verdict: the paper's test for the global optimum is that the repetitions from seeded starts agree. Where fewer
// than half of a subproblem's repetitions in the last sweep reach its best, that best is not shown to be the global
// optimum (on the spindle with drawn truths, 1 of 16 agreed at a wrong optimum: docs/methods.md, Limits). Where the
// joint repetitions confirm the estimate, theirs is the test (the sweeps' subproblems may stop apart from the joint
// optimum, or not settle, while the joint problem has one optimum repeatably).
void judge_convergence(const JointOutcome& joint, ModalState& state, FitResult& result) {
  nlohmann::json& details = state.details;
  const bool settled =
      !details.contains("last_sweep_change") || details["last_sweep_change"].get<double>() < kSweepTolerance;
  std::string disagreeing;
  if (!joint.confirms && joint.taken) {
    const nlohmann::json& j = details["joint_repetitions"];
    disagreeing = "the joint repetitions did not agree on one optimum (" + std::to_string(j["agreeing"].get<int>()) +
                  " of " + std::to_string(j["repetitions"].get<int>()) +
                  " reached the best); the estimate may be a local optimum";
  } else if (!joint.confirms && details.contains("repetitions")) {
    for (const nlohmann::json& s : details["repetitions"]["last_sweep"]) {
      const int agreeing = s["agreeing"].get<int>(), repetitions = s["repetitions"].get<int>();
      if (2 * agreeing < repetitions) {
        const std::string mode =
            detail::format("%.4g Hz", details["reference_modes"][s["mode"].get<std::size_t>()]["f_hz"].get<double>());
        disagreeing = "the repetitions did not agree on one optimum (the subproblem of the mode at " +
                      mode + ": " + std::to_string(agreeing) + " of " +
                      std::to_string(repetitions) + " reached its best); the estimate may be a local optimum";
        break;
      }
    }
  }
  details["repetitions_agree"] = disagreeing.empty();
  const bool joint_converged = state.joint_converged;
  if (joint.confirms) {
    const nlohmann::json& j = details["joint_repetitions"];
    const std::string count = std::to_string(j["agreeing"].get<int>()) + " of " + std::to_string(j["repetitions"].get<int>());
    result.converged = joint_converged;
    result.stop_reason = !joint_converged ? "the joint mass/stiffness solve did not converge"
                         : joint.taken    ? "the joint repetitions (" + count +
                                             ") agree on an optimum below the subproblem sweeps' (which stopped at a "
                                             "local optimum)"
                                          : "the joint repetitions (" + count + ") agree on the estimate";
  } else {
    result.converged = settled && joint_converged && disagreeing.empty();
    result.stop_reason = !disagreeing.empty() ? disagreeing
                         : !settled            ? "sweep limit reached"
                         : !joint_converged    ? "the joint mass/stiffness step did not converge"
                                               : "the subproblem sweeps settled and the joint step converged";
  }
}

}  // namespace

// modal_setup -> check_prior_modes -> partition_by_sobol -> sweep_subproblems -> solve_damping -> joint_polish
// -> joint_repetitions -> agreement_at_estimate -> finish -> judge_convergence
FitResult fit_modal(const Model& model, const std::vector<DataSet>& data, const FitOptions& options) {
  const ModalSetup setup = modal_setup(model, data, options);
  const Problem pr{model, setup.configurations, setup.modes};
  check_prior_modes(model, setup);
  ModalContext ctx{model.info(), options, setup, pr, std::max(options.spread, 1.0 + 1e-6), std::max(options.starts, 1),
                   std::vector<int>(static_cast<std::size_t>(setup.nr))};
  for (int r = 0; r < setup.nr; ++r) ctx.all_modes[static_cast<std::size_t>(r)] = r;

  ModalState state;
  state.p = setup.prior;
  state.structural = setup.structural;
  describe_reference_modes(setup, state.details);
  if (!setup.structural.empty()) sweep_subproblems(ctx, partition_by_sobol(ctx, state), state);
  solve_damping(ctx, state);
  joint_polish(ctx, state);
  const JointOutcome joint = joint_repetitions(ctx, state);
  if (!setup.damping.empty()) state.details["damping"] = state.damping;
  agreement_at_estimate(ctx, state);

  FitResult result = finish(model, data, ctx, state);
  judge_convergence(joint, state, result);
  result.method_details["modal"] = state.details.dump();
  return result;
}

}  // namespace mbgen
