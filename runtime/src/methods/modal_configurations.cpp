#include "modal_configurations.hpp"

#include "mbgen/estimation/fit.hpp"
#include "mbgen/dynamics/model_modes.hpp"
#include "mbgen/modal_identification/modal_pairing.hpp"

#include <stdexcept>

#include "text/string_format.hpp"

namespace mbgen::methods {

std::vector<ModalConfiguration> group_configurations(const ModelInfo& info, const std::vector<DataSet>& data) {
  std::vector<ModalConfiguration> out;
  for (const DataSet& d : data) {
    if (!d.is_frf())
      throw FitError(d.file() +
                     ": error: --method modal needs FRFs (it identifies modes from them), but this is a "
                     "time record");
    std::map<std::string, double> set;
    for (const auto& [name, v] : d.set()) set[name] = v.value;
    std::size_t c = 0;
    while (c < out.size() && out[c].set != set) ++c;
    if (c == out.size()) {
      out.emplace_back();
      out.back().set = set;
      for (const auto& [name, v] : set) out.back().overrides.emplace_back(info.parameter_index(name), v);
    }
    out[c].files.push_back(d.file());
    out[c].frfs.push_back(std::get<FrfData>(d.content));
  }
  return out;
}

std::vector<ModeRef> identify_reference_modes(const Model& model, const Eigen::VectorXd& prior,
                                              std::vector<ModalConfiguration>& configurations) {
  std::vector<ModeRef> modes;
  for (std::size_t c = 0; c < configurations.size(); ++c) {
    ModalConfiguration& cf = configurations[c];
    const std::string where = configurations.size() > 1 ? " (configuration " + set_label(cf.set) + ")" : "";
    // Bad input: DataError, DynamicsError (runtime_error), and invalid_argument, which the modal analysis throws for
    // data it cannot serve (too few lines for the order, channels the model does not have). Any other logic_error
    // is a bug and goes on to the command's internal-error status.
    const auto failed = [&](const std::string& what) {
      return FitError(std::string("fit: error: --method modal") + where + ": " + what);
    };
    try {
      cf.data = modal_data(cf.frfs, FrequencyBand{}, FrfQuantity::Unknown);
      cf.data.quantity = model_modes(model, in_configuration(cf, prior), cf.data).quantity;
    } catch (const std::runtime_error& e) {
      throw failed(e.what());
    } catch (const std::invalid_argument& e) {
      throw failed(e.what());
    }
    const auto analysis_failed = [&](const std::string& what) {
      return FitError(std::string("fit: error: --method modal: the modal analysis of the FRFs") + where +
                      " failed: " + what);
    };
    try {
      cf.reference = identify_modes(cf.data, ModalOptions{}).modes;
    } catch (const std::runtime_error& e) {
      throw analysis_failed(e.what());
    } catch (const std::invalid_argument& e) {
      throw analysis_failed(e.what());
    }
    for (int m = 0; m < static_cast<int>(cf.reference.size()); ++m) modes.push_back({static_cast<int>(c), m});
  }
  return modes;
}

Eigen::VectorXd in_configuration(const ModalConfiguration& c, Eigen::VectorXd p) {
  for (const auto& [i, v] : c.overrides) p[i] = v;
  return p;
}

std::vector<ModalComparison> compare_all(const ModalProblem& pr, const Eigen::VectorXd& p,
                                         const std::vector<bool>& needed) {
  std::vector<ModalComparison> out(pr.configurations.size());
  for (std::size_t c = 0; c < pr.configurations.size(); ++c) {
    if (!needed[c]) continue;
    const ModalConfiguration& cf = pr.configurations[c];
    out[c] = compare_modes(pr.model, in_configuration(cf, p), cf.data, cf.reference);
    if (!out[c].ok) break;
  }
  return out;
}

bool objectives_at(const ModalProblem& pr, const Eigen::VectorXd& p, const std::vector<int>& modes, Eigen::VectorXd& r) {
  std::vector<bool> needed(pr.configurations.size(), false);
  for (int m : modes) needed[static_cast<std::size_t>(pr.modes[static_cast<std::size_t>(m)].configuration)] = true;
  const std::vector<ModalComparison> cmp = compare_all(pr, p, needed);
  std::vector<double> all;
  for (int m : modes) {
    const ModeRef& mr = pr.modes[static_cast<std::size_t>(m)];
    const ModalComparison& c = cmp[static_cast<std::size_t>(mr.configuration)];
    if (!c.ok) return false;
    Eigen::VectorXd part;
    structural_residuals(c, pr.configurations[static_cast<std::size_t>(mr.configuration)].reference, {mr.mode}, part);
    all.insert(all.end(), part.data(), part.data() + part.size());
  }
  r = Eigen::Map<const Eigen::VectorXd>(all.data(), static_cast<Eigen::Index>(all.size()));
  return r.allFinite();
}

std::string set_label(const std::map<std::string, double>& set) {
  std::string s;
  for (const auto& [name, v] : set) {
    s += detail::format("%s%s=%.10g", s.empty() ? "" : ", ", name.c_str(), v);
  }
  return s.empty() ? "no `# set` values" : s;
}

std::string hz_list(const std::vector<IdentifiedMode>& modes) {
  std::string s;
  for (const IdentifiedMode& m : modes) {
    s += detail::format("%s%.4g Hz", s.empty() ? "" : ", ", m.f_hz);
  }
  return s.empty() ? "none" : s;
}

std::string hz_list(const std::vector<ModalConfiguration>& configurations) {
  if (configurations.size() == 1) return hz_list(configurations.front().reference);
  std::string s;
  for (const ModalConfiguration& c : configurations)
    s += (s.empty() ? "" : "; ") + set_label(c.set) + ": " + hz_list(c.reference);
  return s;
}

}  // namespace mbgen::methods
