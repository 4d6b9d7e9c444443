// The `mbgen-modal/1` document (docs/interfaces.md) and its documented extra members (docs/modal.md).
#include "mbgen/modal_identification/modal_report.hpp"

#include <nlohmann/json.hpp>

#include <cmath>

#include "json_values.hpp"

namespace mbgen {

namespace {

using nlohmann::json;
using modal_json_values::complex_number;
using modal_json_values::matrix;
using modal_json_values::number;

json per_channel(const ModalData& data, const Eigen::VectorXd& values) {
  json out = json::object();
  for (std::size_t c = 0; c < data.channels.size(); ++c)
    out[data.channels[c].name] = number(values[static_cast<Eigen::Index>(c)]);
  return out;
}

}  // namespace

std::string modal_result_json(const ModalReportInput& in) {
  const ModalData& data = in.data;
  const ModalIdentification& r = in.result;
  json j;
  j["schema"] = "mbgen-modal/1";
  j["data"] = data.files;
  j["method"] = r.method;
  json modes = json::array();
  for (std::size_t m = 0; m < r.modes.size(); ++m) {
    const IdentifiedMode& mode = r.modes[m];
    json shape = json::object();
    for (std::size_t c = 0; c < data.channels.size(); ++c)
      shape[data.channels[c].name] = complex_number(mode.residues[static_cast<Eigen::Index>(c)]);
    json entry = {{"f_hz", number(mode.f_hz)},
                  {"zeta", number(mode.zeta)},
                  {"mpc", number(mode.mpc)},
                  {"mpd_deg", number(mode.mpd_deg)},
                  {"shape", shape},
                  {"refined", mode.refined},
                  {"f_std_hz", number(mode.f_std_hz)},
                  {"zeta_std", number(mode.zeta_std)},
                  {"lscf", {{"f_hz", number(mode.lscf_f_hz)}, {"zeta", number(mode.lscf_zeta)}}},
                  {"pole", complex_number(mode.lambda)},
                  {"stable_orders", mode.support},
                  {"selected_by", mode.user_selected ? "user" : "automatic"}};
    if (in.model) {
      const int k = in.model->pairing.model_mode[m];
      entry["model_mode"] = k;
      entry["mac"] = number(in.model->pairing.best_mac[m]);
      entry["model_mode_shared"] = static_cast<bool>(in.model->pairing.shared[m]);
      if (k >= 0) {
        entry["model_f_hz"] = number(in.model->modes.f_hz[static_cast<std::size_t>(k)]);
        entry["model_zeta"] = number(in.model->modes.zeta[static_cast<std::size_t>(k)]);
      }
    }
    modes.push_back(entry);
  }
  j["modes"] = modes;
  std::vector<std::string> channels;
  for (const ModalData::Channel& c : data.channels) channels.push_back(c.name);
  j["channels"] = channels;
  j["band_hz"] = json::array({number(data.f_hz[0]), number(data.f_hz[data.f_hz.size() - 1])});
  j["lines"] = data.f_hz.size();
  j["quantity"] = frf_quantity_name(data.quantity);
  j["references"] = r.diagram.references;
  j["max_order"] = r.diagram.orders.empty() ? 0 : r.diagram.orders.back();
  const StabilizationCriteria& c = in.options.selection.criteria;
  j["stability_criteria"] = {{"frequency", number(c.frequency)},
                             {"damping", number(c.damping)},
                             {"shape", number(c.shape)},
                             {"max_zeta", number(c.max_zeta)}};
  j["selection"] = in.options.select_hz.empty() ? "automatic" : "user";
  json held = json::array();  // user-selected poles the refinement could not move to a minimum
  for (const std::string& note : r.refinement.notes)
    if (!note.empty()) held.push_back(note);
  json rejected = json::array();
  for (const RejectedPole& p : r.rejected)
    rejected.push_back({{"f_hz", number(p.pole.f_hz)},
                        {"zeta", number(p.pole.zeta)},
                        {"stable_orders", p.pole.support},
                        {"reason", p.reason}});
  j["rejected_poles"] = rejected;
  j["refinement"] = {{"enabled", in.options.refine},
                     {"iterations", r.refinement.iterations},
                     {"initial_cost", number(r.refinement.initial_cost)},
                     {"cost", number(r.refinement.cost)},
                     {"held", held}};
  j["residual_terms"] = {{"lower", per_channel(data, r.fit.lower)}, {"upper", per_channel(data, r.fit.upper)}};
  j["channel_error"] = per_channel(data, r.fit.channel_error);
  j["auto_mac"] = matrix(r.auto_mac);
  if (in.model) {
    j["model"] = in.model->model_file;
    json model_modes = json::array();
    for (std::size_t k = 0; k < in.model->modes.f_hz.size(); ++k)
      model_modes.push_back({{"f_hz", number(in.model->modes.f_hz[k])}, {"zeta", number(in.model->modes.zeta[k])}});
    j["model_modes"] = model_modes;
    j["model_mac"] = matrix(in.model->pairing.mac);
  }
  // Invalid UTF-8 in a file name becomes U+FFFD (docs/cli.md), not an exception.
  return j.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
}

}  // namespace mbgen
