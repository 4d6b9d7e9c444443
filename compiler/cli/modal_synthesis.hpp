// `mbgen modal --synthesis OUT`: the FRFs synthesized from the identified modes, for another tool or another run.
#pragma once

#include <mbgen/modal_identification/modal_identification.hpp>

#include <map>
#include <string>
#include <vector>

#include "cli/data_writing.hpp"
#include "ir/model_ir.hpp"

namespace mbgen::cli {

// The synthesis on the analysed lines (the band's, f > 0), one channel per measured one and named so: the modes with
// the residual terms, ModalIdentification::fit.synthesized, which channel_error and the report's "synthesized against
// measured" overlays compare with the data. As CSV, or as UFF 58 whose points are the measured channels' (their
// names, the mapping files beside UFF data files: own_mappings), else the model's sensor points (`model`, placed with `sets`), else
// the default ones (frf_uff58.hpp), with the ordinate type of the analysed quantity.
DataTexts synthesis_texts(const ModalData& data, const ModalIdentification& result, DataFormat format,
                          const std::vector<std::string>& data_paths, const ir::ModelIr* model,
                          const std::map<std::string, std::string>& sets);

}  // namespace mbgen::cli
