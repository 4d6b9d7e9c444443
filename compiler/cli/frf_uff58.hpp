// Measured or synthesized FRFs written as UFF 58 with the mapping file that names their points (`mbgen convert`,
// `mbgen modal --synthesis`, mbgen.write_data): what docs/data.md ("Writing measured FRFs") describes.
#pragma once

#include <mbgen/data/frf_data.hpp>
#include <mbgen/data/uff.hpp>

#include <map>
#include <string>
#include <vector>

#include "cli/uff_modes.hpp"

namespace mbgen::cli {

// Where a channel's name finds its UFF point (node and direction), in this order, the model's rules first when
// model_first:
// - the data's own: a name that is a point ("node12:+Z", a UFF file read without a mapping), or a point that one of
//   `mappings` (the mapping files read with the data) names so;
// - the model's: an output among `model_outputs` (its sensor points, sensor_geometry), an input among `model_inputs`
//   (node 1001 + its index, +X, as `mbgen export --what frf --format uff`);
// - else the default: outputs nodes 1, 2, ... and inputs 1001, 1002, ..., all +X, in order of first appearance,
//   skipping points already taken.
struct UffPointRules {
  std::vector<UffMapping> mappings;
  const SensorGeometry* model_outputs = nullptr;
  std::vector<std::string> model_inputs;
  bool model_first = false;
  // Record 9's specific data type per output (8 displacement, 11 velocity, 12 acceleration), else the data's
  // (FrfData::uff_ordinate_type; 0 when unknown).
  std::map<std::string, int> output_types;
};

// The specific data type of an FRF quantity: 8, 11, 12; 0 for Unknown.
int uff_specific_data_type(FrfQuantity q);

// `data` as ASCII UFF 58: per channel an FRF record (function type 4, complex double, denominator force) and, when it
// has one, its coherence (function type 6, real) right after it; `title` is ID line 1 and the channel's name ID line
// 2. The frequencies are written evenly spaced (record 7) only when that reproduces every line exactly, else with
// each point. The mapping file holds the data's `set` values and a line for each name that is not its point's
// default name ("node1:+X"). DataError (naming data.file) when two names would share a point, or a name cannot
// stand in a mapping file (not an identifier).
UffText frf_uff58_text(const FrfData& data, const UffPointRules& rules, const std::string& title);

}  // namespace mbgen::cli
