// The model writer: ir::ModelIr -> readable .mdl text in the syntax of docs/language.md.
//
// parse_string(write_model(m)) gives a model equivalent to m (same names, values, roles, bounds, geometry and
// signals, declared in the same order), and writing that again gives the same text. Used by `mbgen diagnose` to
// show extended models. Source locations and the file name are not written; implicit points (an attachment
// without `at`) stay implicit.
#pragma once

#include <string>

#include "ir/model_ir.hpp"

namespace mbgen::frontend {

// The whole model: `model`, parameters, grounds, bodies, elements, spins, inputs, outputs, in IR order.
std::string write_model(const ir::ModelIr& model);

// Single statements, each ending with a newline (blocks span several lines). The operators of
// `mbgen diagnose` use them to write the declarations they add to a model's original text.
std::string write_parameter(const ir::Parameter& p);
std::string write_ground(const ir::Ground& g);
std::string write_body(const ir::Body& b);
std::string write_element(const ir::Element& e);
std::string write_spin(const ir::Spin& s);
std::string write_input(const ir::Input& in);
std::string write_output(const ir::Output& out);
std::string write_filter(const ir::Filter& f);

// Pieces, without a newline: `(X, Y, Z)`, a direction (`x` or `(A, B, C)`), an attachment (`NAME [at (X, Y, Z)]`).
std::string write_vec3(const ir::Vec3& v);
std::string write_direction(const ir::Direction& d);
std::string write_attachment(const ir::Attachment& a);

}  // namespace mbgen::frontend
