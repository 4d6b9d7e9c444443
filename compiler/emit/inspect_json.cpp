// schema mbgen-inspect/1: exactly the keys of docs/interfaces.md, in its order.
#include <nlohmann/json.hpp>

#include "emit/infix_printer.hpp"
#include "emit/inspect.hpp"
#include "emit/inspect_common.hpp"

namespace mbgen::emit {

namespace {

using Json = nlohmann::ordered_json;

Json matrix_json(const GiNaC::matrix& m) {
  Json rows = Json::array();
  for (unsigned r = 0; r < m.rows(); ++r) {
    Json row = Json::array();
    for (unsigned c = 0; c < m.cols(); ++c) row.push_back(infix_text(m(r, c)));
    rows.push_back(row);
  }
  return rows;
}

Json coefficients_json(const std::vector<GiNaC::ex>& c) {
  Json out = Json::array();
  for (const auto& e : c) out.push_back(infix_text(e));
  return out;
}

}  // namespace

std::string emit_inspect_json(const symbolic::SymbolicModel& sm) {
  const detail::InspectNames names = detail::inspect_names(sm);
  Json j;
  j["schema"] = "mbgen-inspect/1";
  Json params = Json::array();
  for (const auto& p : sm.parameters) {
    Json e;
    e["name"] = p.name;
    e["value"] = detail::value_as_double(p.value);
    e["role"] = detail::role_name(p);
    e["unit"] = detail::unit_of(p);
    params.push_back(e);
  }
  j["parameters"] = params;
  j["coordinates"] = names.coordinates;
  j["inputs"] = names.inputs;
  j["outputs"] = names.outputs;
  j["M"] = matrix_json(sm.M);
  j["C"] = matrix_json(sm.C_total);
  j["K"] = matrix_json(sm.K);
  Json tfs = Json::array();
  for (const auto& tf : sm.transfer_functions) {
    Json e;
    e["output"] = names.outputs.at(static_cast<std::size_t>(tf.output));
    e["input"] = names.inputs.at(static_cast<std::size_t>(tf.input));
    e["symbolic"] = tf.symbolic;
    e["numerator"] = coefficients_json(tf.numerator);
    e["denominator"] = coefficients_json(tf.denominator);
    if (!tf.exact) e["exact"] = false;  // a block too large for exact coefficients: both lists are empty
    tfs.push_back(e);
  }
  j["transfer_functions"] = tfs;
  Json modes = Json::array();
  for (const Mode& m : detail::modes_at_current_values(sm)) {
    Json e;
    e["f_hz"] = m.f_hz;
    e["zeta"] = m.zeta;
    modes.push_back(e);
  }
  j["modes"] = modes;
  // Invalid UTF-8 (a file name in another encoding) cannot be JSON text: such bytes become U+FFFD.
  return j.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
}

}  // namespace mbgen::emit
