// The inspection emitter behind `mbgen inspect MODEL.mdl --format markdown|latex|json`: parameters,
// coordinates, inputs, outputs, the symbolic M, C, K (G when there is spin), B and the output maps, the
// transfer-function coefficients, exact pole-zero cancellations and the modes at the current values.
// JSON follows schema mbgen-inspect/1 (docs/interfaces.md) exactly. Output is deterministic.
#pragma once

#include <string>

#include "symbolic/symbolic_model.hpp"

namespace mbgen::emit {

enum class InspectFormat { Markdown, Latex, Json };

// "markdown", "latex" or "json"; throws std::invalid_argument otherwise.
InspectFormat parse_inspect_format(const std::string& name);

std::string emit_inspect(const symbolic::SymbolicModel& sm, InspectFormat format);

std::string emit_inspect_markdown(const symbolic::SymbolicModel& sm);
std::string emit_inspect_latex(const symbolic::SymbolicModel& sm);
std::string emit_inspect_json(const symbolic::SymbolicModel& sm);

}  // namespace mbgen::emit
