// Edits of texts the examples do not exercise: statements sharing a line, a file without a final newline,
// implicit points that must stay where they were.
#include "diagnosis/text_patch.hpp"

#include <algorithm>

#include "diagnosis/test_support.hpp"

using namespace mbgen;
using namespace mbgen::diagnosis;
using Catch::Matchers::Contains;
using Catch::Matchers::Equals;

namespace {

// No final newline; several statements per line.
const char* const kCompact = R"(model compact
param m = 2 "kg" estimate in [0, inf]; param c = 0 fixed
param k = 1e3 estimate; param k2 = 5 fixed
ground g; ground g2
body b { mass m; dof x }; body b2 { mass m; dof x }
spring s1 { from g; to b; along x; stiffness k; damping c }
spring s2 { from g2; to b2; along x; stiffness k }
spring s3 { from b at (1, 0, 0); to b2; along x; stiffness k; damping k2 }
input F force on b at (0.5, 0, 0) along x
output d displacement of b2 along x)";

}  // namespace

TEST_CASE("statements sharing a line are replaced in place", "[diagnosis][text]") {
  const ir::ModelIr m = frontend::parse_string(kCompact, "compact.mdl");
  const std::vector<Extension> xs = enumerate_extensions(m, kCompact, {});
  CHECK_THAT(test::structural_ids_of(xs), Equals(std::vector<std::string>{
                                   "compliant_ground:g", "compliant_ground:g2", "free_parameter:c",
                                   "free_parameter:k2", "untie_parameter:k", "untie_parameter:k",
                                   "untie_parameter:k", "added_mass:b", "added_mass:b2",
                                   "connection:g-b2", "connection:g2-b"}));
  for (const Extension& x : xs) test::check_candidate(x);

  // The first ground of `ground g; ground g2` became a body; the second is untouched.
  const Extension& g = test::find(xs, "compliant_ground:g");
  CHECK_THAT(g.mdl_text, Contains("\nbody g {\n  mass m_g\n  dof x\n}\n; ground g2\n"));
  CHECK_THAT(g.mdl_text, Contains("# ground `g` now moves"));
  // The first variant unties s1: its reference is renamed in place on the shared line, k stays declared.
  const Extension& k = test::find(xs, "untie_parameter:k");
  CHECK(k.variant == "s1");
  CHECK_THAT(k.mdl_text, Contains("\nparam k = 1e3 estimate; param k2 = 5 fixed\n"));
  CHECK_THAT(k.mdl_text, Contains("stiffness k_s1; damping c }"));
  CHECK_THAT(k.mdl_text, Contains("spring s2 { from g2; to b2; along x; stiffness k }"));
  CHECK(k.new_parameters.size() == 1);
  // The mass at F (x = 0.5) moves b's centre of mass: where the text meant the old one, it now says so.
  const Extension& b = test::find(xs, "added_mass:b");
  CHECK_THAT(b.mdl_text, Contains("spring s1 { from g; to b at (0, 0, 0); along x;"));
  CHECK_THAT(b.mdl_text, Contains("  at (ma_b*0.5/(m + ma_b), 0, 0)\n"));
  // A role changed on a shared line: the note goes to the end section.
  const Extension& c = test::find(xs, "free_parameter:c");
  CHECK_THAT(c.mdl_text, Contains("param c = 0 estimate\nparam k = 1e3"));
  CHECK_THAT(c.mdl_text, Contains("---\n# was fixed\n"));
}

TEST_CASE("a statement removed from a shared line leaves the rest of the line", "[diagnosis][text]") {
  TextPatch patch("param a = 1; param b = 2\nparam c = b\n", "t.mdl");
  patch.replace_statement({1, 7}, "a is no longer used", "");
  const std::string out = patch.result("test");
  CHECK_THAT(out, Contains("\n; param b = 2\n") || Catch::Matchers::StartsWith("; param b = 2\n"));
  CHECK_THAT(out, !Contains("param a = 1;"));
  CHECK_THAT(out, Contains("# a is no longer used"));
}

TEST_CASE("a text patch checks what it edits", "[diagnosis][text]") {
  TextPatch patch("param a = 1\nparam b = a*2\n", "t.mdl");
  CHECK_THROWS_AS(patch.rename({2, 11}, "b", "c"), std::logic_error);  // `a` is there, not `b`
  CHECK_THROWS_AS(patch.rename({7, 1}, "a", "c"), std::logic_error);   // no such line
  patch.rename({2, 11}, "a", "a_new");
  patch.replace_statement({1, 7}, "a is renamed", "param a_new = 1\n");
  CHECK(patch.result("rename a") ==
        "# mbgen diagnose: a is renamed\n# param a = 1\nparam a_new = 1\nparam b = a_new*2\n\n"
        "# --- mbgen diagnose: rename a ---\n");
  TextPatch overlap("param a = 1\n", "t.mdl");
  overlap.rename({1, 7}, "a", "x");
  overlap.rename({1, 7}, "a", "y");
  CHECK_THROWS_AS(overlap.result("t"), std::logic_error);
}

TEST_CASE("a statement rewritten in place keeps the lines and what shares its line", "[diagnosis][text]") {
  const ir::ModelIr m = frontend::parse_string(kCompact, "compact.mdl");
  TextPatch patch(kCompact, "compact.mdl");
  // `param c = 0 fixed` shares its line with `param m ...`: only its tokens change, the `;` and the line stay.
  patch.rewrite_statement(m.parameters[1].loc, "param c = 0 estimate in [0, 10]");
  const std::string text = patch.text();
  CHECK_THAT(text, Contains("\nparam m = 2 \"kg\" estimate in [0, inf]; param c = 0 estimate in [0, 10]\n"));
  CHECK(std::count(text.begin(), text.end(), '\n') == 10);  // the original's 9 lines and the final newline
  CHECK(text.find("mbgen diagnose") == std::string::npos);    // no end section
  const ir::ModelIr edited = frontend::parse_string(text, "compact.mdl");
  CHECK(edited.parameters[1].role == ir::Role::Estimate);
  CHECK(edited.outputs[0].loc.line == m.outputs[0].loc.line);
}

TEST_CASE("a parameter's number is replaced in place, its unit, role, bounds and comment kept", "[diagnosis][text]") {
  const char* const text = "param m = 2 \"kg\" estimate in [0, inf]  # a mass\nparam k = -1e3 estimate; param g = 2*m\n";
  const ir::ModelIr m = frontend::parse_string(text, "t.mdl");
  TextPatch patch(text, "t.mdl");
  patch.replace_number(m.parameters[0].loc, "2.5");
  patch.replace_number(m.parameters[1].loc, "-1250");
  CHECK_THAT(patch.text(), Equals("param m = 2.5 \"kg\" estimate in [0, inf]  # a mass\n"
                                  "param k = -1250 estimate; param g = 2*m\n"));
  // An expression is not a number: the patch refuses rather than cut it.
  CHECK_THROWS_WITH(patch.replace_number(m.parameters[2].loc, "3"), Contains("is not `param NAME = NUMBER`"));
}
