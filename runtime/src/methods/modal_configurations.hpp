// The modal method's configurations (docs/methods.md#modal): Ellinger & Zaeh identify over several machine
// positions; in mbgen a configuration is the data sets that share their `# set` values, which hold in the model
// evaluated for them. Per configuration the reference modes identified from its FRFs; the objectives of any modes
// of any configurations at a parameter vector. Internal header.
#pragma once

#include "modal_objectives.hpp"

#include "mbgen/data/data_set.hpp"
#include "mbgen/model.hpp"

#include <Eigen/Core>

#include <map>
#include <string>
#include <vector>

namespace mbgen::methods {

struct ModalConfiguration {
  std::map<std::string, double> set;              // name -> value
  std::vector<std::pair<int, double>> overrides;  // model index -> value
  std::vector<std::string> files;
  std::vector<FrfData> frfs;
  ModalData data;                                 // the FRFs on one frequency axis
  std::vector<IdentifiedMode> reference;
};

// A reference mode across the configurations: configuration `configuration`'s mode `mode`.
struct ModeRef {
  int configuration = 0, mode = 0;
};

struct ModalProblem {
  const Model& model;
  const std::vector<ModalConfiguration>& configurations;
  const std::vector<ModeRef>& modes;  // all reference modes, configuration by configuration
};

// The data sets grouped by their `# set` values, in order of first appearance. Throws FitError for a time record.
std::vector<ModalConfiguration> group_configurations(const ModelInfo& info, const std::vector<DataSet>& data);

// Each configuration's reference modes (identify_modes, in the quantity of the model's outputs at `prior` in that
// configuration); returns all of them, configuration by configuration. Throws FitError naming the configuration.
std::vector<ModeRef> identify_reference_modes(const Model& model, const Eigen::VectorXd& prior,
                                              std::vector<ModalConfiguration>& configurations);

// p with the configuration's `# set` values.
Eigen::VectorXd in_configuration(const ModalConfiguration& c, Eigen::VectorXd p);

// The model's modes at p paired with each configuration's reference modes (only where `needed`).
std::vector<ModalComparison> compare_all(const ModalProblem& pr, const Eigen::VectorXd& p,
                                         const std::vector<bool>& needed);

// The objectives (structural_residuals) of the modes `modes` (indices into pr.modes) at p, stacked; false when a
// configuration's modes cannot be paired.
bool objectives_at(const ModalProblem& pr, const Eigen::VectorXd& p, const std::vector<int>& modes, Eigen::VectorXd& r);

// "k12=240000" for a configuration's `# set` values ("no `# set` values" without).
std::string set_label(const std::map<std::string, double>& set);
// The modes' frequencies, "90.83 Hz, 153.8 Hz"; with several configurations per configuration, "k12=...: ...; ...".
std::string hz_list(const std::vector<IdentifiedMode>& modes);
std::string hz_list(const std::vector<ModalConfiguration>& configurations);

}  // namespace mbgen::methods
