// The `mbgen-modal/1` document of an output-only analysis: the FRF path's mode table (f_hz, zeta, mpc, mpd_deg,
// shape, pole) with the method, what the shapes are scaled to, and each method's own members (docs/modal.md).
#include "mbgen/modal_identification/output_only_report.hpp"

#include <nlohmann/json.hpp>

#include <cmath>

#include "json_values.hpp"

namespace mbgen {

namespace {

using nlohmann::json;
using modal_json_values::complex_number;
using modal_json_values::matrix;
using modal_json_values::number;

json pair_side(int model_mode, double f_hz, double zeta, double mac, double f_identified) {
  return {{"model_mode", model_mode},
          {"f_hz", number(f_hz)},
          {"zeta", number(zeta)},
          {"mac", number(mac)},
          {"f_error", number((f_hz - f_identified) / f_identified)}};
}

// The `model_update` object: the uncertainties used, the estimates with their standard deviations, the pairs
// before and after.
json update_json(const OperationalUpdate& u) {
  json per_mode = json::array();
  for (const ModeUncertainty& m : u.uncertainty.modes)
    per_mode.push_back({{"f_std_hz", number(m.f_std_hz)},
                        {"zeta_std", number(m.zeta_std)},
                        {"shape_std", number(m.shape_std)},
                        {"blocks_found", m.blocks_found}});
  json parameters = json::object();
  for (const UpdatedParameter& p : u.parameters)
    parameters[p.name] = {{"kind", p.kind}, {"prior", number(p.prior)}, {"estimate", number(p.estimate)},
                          {"std", number(p.std)}};
  json pairs = json::array();
  for (const UpdatedPair& p : u.pairs)
    pairs.push_back({{"mode", p.mode},
                     {"f_hz", number(p.f_hz)},
                     {"f_std_hz", number(p.f_std_hz)},
                     {"zeta", number(p.zeta)},
                     {"zeta_std", number(p.zeta_std)},
                     {"shape_std", number(p.shape_std)},
                     {"before",
                      pair_side(p.model_mode_before, p.model_f_before, p.model_zeta_before, p.mac_before, p.f_hz)},
                     {"after",
                      pair_side(p.model_mode_after, p.model_f_after, p.model_zeta_after, p.mac_after, p.f_hz)}});
  return {{"model", u.model_file},
          {"uncertainty",
           {{"method", "data-blocks"}, {"blocks", u.uncertainty.blocks}, {"block_s", number(u.uncertainty.block_s)},
            {"modes", per_mode}}},
          {"parameters", parameters},
          {"pairs", pairs},
          {"unpaired_modes", u.unpaired},
          {"chi2_before", number(u.chi2_before)},
          {"chi2_after", number(u.chi2_after)},
          {"residuals", u.residuals},
          {"iterations", u.iterations},
          {"converged", u.converged},
          {"notes", u.notes}};
}

}  // namespace

std::string output_only_json(const OutputOnlyReportInput& in) {
  const ResponseData& data = in.data;
  const OutputOnlyIdentification& r = in.result;
  const OutputOnlyIdentification& run = method_run(in);  // settings: the first setup's when merged
  const bool ssi = r.method == OutputOnlyMethod::SsiCov;
  json j;
  j["schema"] = "mbgen-modal/1";
  j["data"] = data.files;
  j["method"] = output_only_method_name(r.method);
  j["output_only"] = true;
  j["shape_scaling"] = "unit-norm";
  json modes = json::array();
  for (std::size_t m = 0; m < r.modes.size(); ++m) {
    const OperationalMode& mode = r.modes[m];
    json shape = json::object();
    for (std::size_t c = 0; c < data.channels.size(); ++c)
      shape[data.channels[c]] = complex_number(mode.shape[static_cast<Eigen::Index>(c)]);
    json entry = {{"f_hz", number(mode.f_hz)},     {"zeta", number(mode.zeta)},   {"mpc", number(mode.mpc)},
                  {"mpd_deg", number(mode.mpd_deg)}, {"shape", shape},            {"pole", complex_number(mode.lambda)},
                  {"selected_by", "automatic"}};
    if (ssi) {
      entry["stable_orders"] = mode.support;
      entry["f_scatter_hz"] = number(mode.f_scatter_hz);
      entry["zeta_scatter"] = number(mode.zeta_scatter);
      entry["contribution"] = number(mode.contribution);
    } else if (!in.setups) {
      const FddPeak& p = r.fdd.peaks[m];
      entry["peak_f_hz"] = number(p.f_hz);
      entry["peak_db"] = number(p.sv_db);
      entry["bell_lines"] = p.bell_lines;
      entry["efdd_note"] = p.note;
    }
    modes.push_back(entry);
  }
  j["modes"] = modes;
  j["channels"] = data.channels;
  std::vector<std::string> references;
  for (int c : data.references) references.push_back(data.channels[static_cast<std::size_t>(c)]);
  j["references"] = static_cast<int>(references.size());
  j["reference_channels"] = references;
  j["sample_rate_hz"] = number(1 / data.dt);
  json samples = json::array();
  for (const Eigen::MatrixXd& y : data.records) samples.push_back(y.rows());
  if (in.setups) {
    json setups = json::array();
    for (std::size_t s = 0; s < in.setups->setups.size(); ++s) {
      const ResponseData& setup = in.setups->setups[s];
      json f = json::array();
      for (const OperationalMode& mode : in.setups->per_setup[s].modes) f.push_back(number(mode.f_hz));
      setups.push_back({{"files", setup.files}, {"channels", setup.channels}, {"modes_f_hz", f}});
      for (const Eigen::MatrixXd& y : setup.records) samples.push_back(y.rows());
    }
    j["setups"] = setups;
  }
  j["samples"] = samples;
  j["notes"] = data.notes;
  j["auto_mac"] = matrix(r.auto_mac);
  if (ssi) {
    const StabilizationCriteria& c = in.options.selection.criteria;
    j["max_order"] = run.ssi.diagram.orders.empty() ? 0 : run.ssi.diagram.orders.back();
    j["block_rows"] = run.ssi.block_rows;
    j["stability_criteria"] = {{"frequency", number(c.frequency)},
                               {"damping", number(c.damping)},
                               {"shape", number(c.shape)},
                               {"max_zeta", number(c.max_zeta)}};
    j["selection"] = "automatic";
    j["min_orders_fraction"] = number(in.options.selection.min_orders_fraction);
    j["min_contribution"] = number(in.options.min_contribution);
    json rejected = json::array();
    for (const RejectedPole& p : r.rejected)
      rejected.push_back({{"f_hz", number(p.pole.f_hz)},
                          {"zeta", number(p.pole.zeta)},
                          {"stable_orders", p.pole.support},
                          {"reason", p.reason}});
    j["rejected_poles"] = rejected;
  } else {
    j["window_s"] = number(run.fdd.window_s);
    if (!run.fdd.frf_inputs.empty()) j["white_force_inputs"] = run.fdd.frf_inputs;
    j["lines"] = run.fdd.f_hz.size();
    j["df_hz"] = number(run.fdd.f_hz.size() > 1 ? run.fdd.f_hz[1] : 0.0);
    j["prominence_db"] = number(in.options.fdd.prominence_db);
    j["bell"] = {{"mac", number(in.options.fdd.bell_mac)}, {"db", number(in.options.fdd.bell_db)}};
  }
  if (in.update) j["model_update"] = update_json(*in.update);
  return j.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
}

}  // namespace mbgen
