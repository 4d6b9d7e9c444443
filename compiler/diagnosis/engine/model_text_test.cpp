// The diagnosis's edits of model text: estimates written in place, held parameters declared known, each through
// TextPatch so the rest of the text stays as the user wrote it.
#include "diagnosis/engine/model_text.hpp"

#include <catch2/catch.hpp>

#include <algorithm>

#include "frontend/parser.hpp"

namespace mbgen::diagnosis {
namespace {

const char* const kModel = R"(model small
param m = 2 "kg" known
param k = 1e3 "N/m" estimate in [0, inf]  # the mount
param k_new = 5e4 "N/m" estimate in [0, inf]
param c_new = 3 "N*s/m" estimate
ground g
body b { mass m; dof x }
spring s { from g; to b; along x; stiffness k + k_new; damping c_new }
input F force on b along x
output d displacement of b along x
)";

}  // namespace

TEST_CASE("the added parameters' estimates are written in place, and nothing else", "[diagnosis][text]") {
  const std::string out =
      with_estimates(kModel, "small.mdl", {{"k", 1234.5}, {"k_new", 61234.567}, {"c_new", 2.5}}, {"k_new", "c_new"});
  CHECK(out.find("param k_new = 61234.6 \"N/m\" estimate in [0, inf]\n") != std::string::npos);
  CHECK(out.find("param c_new = 2.5 \"N*s/m\" estimate\n") != std::string::npos);
  CHECK(out.find("param k = 1e3 \"N/m\" estimate in [0, inf]  # the mount\n") != std::string::npos);  // not added
  const ir::ModelIr parsed = frontend::parse_string(out, "small.mdl");
  REQUIRE(parsed.parameters.size() == 4);
}

TEST_CASE("a held parameter becomes known in the model and its text, saying why", "[diagnosis][text]") {
  ModelState s;
  s.text = kModel;
  s.model = frontend::parse_string(kModel, "small.mdl");
  s.held = {"c_new"};
  declare_held_known(s);
  CHECK(s.held.empty());
  const auto c = std::find_if(s.model.parameters.begin(), s.model.parameters.end(),
                              [](const ir::Parameter& p) { return p.name == "c_new"; });
  REQUIRE(c != s.model.parameters.end());
  CHECK(c->role == ir::Role::Known);
  const ir::ModelIr reparsed = frontend::parse_string(s.text, "small.mdl");
  for (const ir::Parameter& p : reparsed.parameters)
    CHECK((p.role == ir::Role::Known) == (p.name == "m" || p.name == "c_new"));
  CHECK(s.text.find("the data do not determine it") != std::string::npos);
}

TEST_CASE("the added parameters are those of the selected extensions", "[diagnosis]") {
  DiagnosisResult r;
  CandidateOutcome taken, other;
  taken.id = "compliant_ground:g";
  taken.new_parameters = {{"k_g", ""}, {"m_g", ""}};
  other.id = "added_mass:b";
  other.new_parameters = {{"m_added", ""}};
  r.candidates = {other, taken};
  r.selected = {"compliant_ground:g"};
  CHECK(added_parameters(r) == std::set<std::string>{"k_g", "m_g"});
}

}  // namespace mbgen::diagnosis
