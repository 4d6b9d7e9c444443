// For the output-only tests: a response record made by the independent truth generator (scripts/truthgen --kind
// oma: numpy, its own assembly and simulation) and the truth's modes at the sensors from its .truth.json, and the
// comparison of identified modes with them. Test-only header (Catch2).
#pragma once

#include "mbgen/data/data_set.hpp"
#include "mbgen/modal_identification/output_only_modal.hpp"
#include "mbgen_test/files.hpp"
#include "mbgen_test/paths.hpp"
#include "shape_metrics.hpp"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <variant>
#include <vector>

namespace mbgen::test {

struct TruthMode {
  double f_hz = 0, zeta = 0, visibility = 0;
  Eigen::VectorXcd shape;
};

struct OmaTruth {
  ResponseData data;
  std::vector<TruthMode> modes;
};

struct OmaRecord {
  TimeRecord record;
  std::vector<TruthMode> modes;
};

// truthgen --kind oma on EXAMPLE's nominal case, truth draw `draw`, noise seed `seed`, at the default 40 dB, written
// under BUILD/DIR (one directory per test program: ctest runs them in parallel).
inline OmaRecord oma_record(const std::string& dir, const std::string& example, int draw, int seed) {
  const std::filesystem::path folder = std::filesystem::path(mbgen_binary_dir()) / dir;
  std::filesystem::create_directories(folder);
  const std::string stem =
      (folder / (example + "_draw" + std::to_string(draw) + "_seed" + std::to_string(seed))).string();
  const std::string command = "/usr/bin/python3 " + source_path("scripts/truthgen/truthgen.py") + " --example " +
                              example + " --case nominal --kind oma --draw " + std::to_string(draw) + " --seed " +
                              std::to_string(seed) + " -o " + stem + ".csv";
  REQUIRE(std::system(command.c_str()) == 0);
  DataSet file = read_data_file(stem + ".csv");
  REQUIRE(!file.is_frf());
  OmaRecord r{std::get<TimeRecord>(std::move(file.content)), {}};
  std::ifstream in(stem + ".truth.json");
  const nlohmann::json document = nlohmann::json::parse(in);
  for (const nlohmann::json& m : document.at("truth_modes")) {
    TruthMode mode{m.at("f_hz").get<double>(), m.at("zeta").get<double>(), m.at("visibility").get<double>(), {}};
    const auto& shape = m.at("shape");
    mode.shape.resize(static_cast<Eigen::Index>(shape.size()));
    for (std::size_t c = 0; c < shape.size(); ++c)
      mode.shape[static_cast<Eigen::Index>(c)] = {shape[c][0].get<double>(), shape[c][1].get<double>()};
    r.modes.push_back(mode);
  }
  return r;
}

inline OmaTruth oma_truth(const std::string& dir, const std::string& example, int draw, int seed) {
  OmaRecord r = oma_record(dir, example, draw, seed);
  return {response_data({std::move(r.record)}), std::move(r.modes)};
}

// The targets of issue 34 for every truth mode the responses show (visibility >= 0.01: its peak in the output
// spectrum within 40 dB of the strongest mode's): an identified mode within 1 % in frequency, its damping ratio
// within 25 %, MAC > 0.95 with the truth's shape at the sensors; and no identified mode that is no truth mode.
struct Targets {
  bool frequency = true, damping = true, shape = true, no_spurious = true;
};

inline void check_against_truth(const std::vector<OperationalMode>& found, const std::vector<TruthMode>& truth,
                                const Targets& targets = {}) {
  constexpr double kVisible = 0.01;
  for (const OperationalMode& m : found)
    UNSCOPED_INFO("identified " << m.f_hz << " Hz, zeta " << m.zeta << ", support " << m.support << ", MPC "
                                << m.mpc << ", contribution " << m.contribution);
  for (const TruthMode& t : truth) {
    if (t.visibility < kVisible) continue;
    const OperationalMode* best = nullptr;
    for (const OperationalMode& m : found)
      if (!best || std::abs(m.f_hz - t.f_hz) < std::abs(best->f_hz - t.f_hz)) best = &m;
    INFO("truth " << t.f_hz << " Hz, zeta " << t.zeta << ", visibility " << t.visibility);
    REQUIRE(best != nullptr);
    const double mac = modal_detail::shape_mac(best->shape, t.shape);
    INFO("identified " << best->f_hz << " Hz (" << 100 * (best->f_hz / t.f_hz - 1) << " %), zeta " << best->zeta
                       << " (" << 100 * (best->zeta / t.zeta - 1) << " %), MAC " << mac);
    if (targets.frequency) CHECK(std::abs(best->f_hz / t.f_hz - 1) < 0.01);
    if (targets.damping) CHECK(std::abs(best->zeta / t.zeta - 1) < 0.25);
    if (targets.shape) CHECK(mac > 0.95);
  }
  for (const OperationalMode& m : found) {
    if (!targets.no_spurious) break;
    bool near = false;
    for (const TruthMode& t : truth) near = near || std::abs(m.f_hz / t.f_hz - 1) < 0.01;
    INFO("identified " << m.f_hz << " Hz, zeta " << m.zeta << ": no truth mode within 1 %");
    CHECK(near);
  }
}

}  // namespace mbgen::test
