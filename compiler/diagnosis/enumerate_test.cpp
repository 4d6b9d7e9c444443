// The candidates each example gets, and the checks every candidate passes (its text parses to its model, the
// model derives with a non-singular mass matrix).
#include "diagnosis/test_support.hpp"
#include "diagnosis/model_values.hpp"

using namespace mbgen;
using namespace mbgen::diagnosis;
using Catch::Matchers::Equals;

TEST_CASE("mdof2: the candidates come from its structure", "[diagnosis]") {
  const test::Example ex = test::load("mdof2");
  const std::vector<Extension> plain = enumerate_extensions(ex.model, ex.text, {});
  CHECK_THAT(test::structural_ids_of(plain), Equals(std::vector<std::string>{
                                      "compliant_ground:wall", "free_parameter:c12", "added_mass:mass1",
                                      "added_mass:mass2"}));
  ExtensionContext peaks;
  peaks.peak_hz = {190};
  const std::vector<Extension> with_peak = enumerate_extensions(ex.model, ex.text, peaks);
  CHECK_THAT(test::structural_ids_of(with_peak), Equals(std::vector<std::string>{
                                          "compliant_ground:wall", "free_parameter:c12", "added_mass:mass1",
                                          "added_mass:mass2", "resonator:mass1", "resonator:mass2"}));
  for (const Extension& x : with_peak) test::check_candidate(x);
}

TEST_CASE("mdof2: a candidate whose new mode starts at a peak also starts at the next peaks", "[diagnosis]") {
  const test::Example ex = test::load("mdof2");
  ExtensionContext ctx;
  ctx.peak_hz = {136, 72, 328, 500};
  const std::vector<Extension> xs = enumerate_extensions(ex.model, ex.text, ctx);
  ExtensionContext at_328 = ctx;
  at_328.peak_hz = {328, 136, 72, 500};
  const std::vector<Extension> ys = enumerate_extensions(ex.model, ex.text, at_328);
  REQUIRE(xs.size() == ys.size());
  for (std::size_t i = 0; i < xs.size(); ++i) {
    const Extension& x = xs[i];
    INFO(x.id);
    if (x.id == "compliant_ground:wall" || x.id.rfind("resonator:", 0) == 0) {
      // The second and third peaks (kAlternativePeaks), not the fourth; each start names every new parameter.
      REQUIRE(x.alternative_starts.size() == kAlternativePeaks);
      std::map<std::string, double> as_at_328;
      const ModelValues values(ys[i].model, {});
      for (const NewParameter& p : ys[i].new_parameters) as_at_328[p.name] = values.of_parameter(p.name);
      CHECK(x.alternative_starts[1] == as_at_328);
      CHECK(x.alternative_starts[0] != as_at_328);
    } else {
      CHECK(x.alternative_starts.empty());  // their starts do not depend on the peaks
    }
  }
  ExtensionContext one_peak;
  one_peak.peak_hz = {136};
  for (const Extension& x : enumerate_extensions(ex.model, ex.text, one_peak)) CHECK(x.alternative_starts.empty());
}

TEST_CASE("spindle: the candidates come from its structure", "[diagnosis]") {
  const test::Example ex = test::load("spindle");
  // compliant_ground: two variants, the simple moving base and the base on four feet.
  const std::vector<std::string> common_head = {"compliant_ground:base", "compliant_ground:base"};
  std::vector<std::string> common_tail;
  // untie_parameter: one variant per mount (which one differs), all under the parameter's id.
  for (const char* p : {"k_hbx", "k_hby", "k_hbz", "c_hbx", "c_hby", "c_hbz"})
    for (int mount = 0; mount < 4; ++mount) common_tail.push_back(std::string("untie_parameter:") + p);
  for (const char* id : {
      "moment_stiffness:bearing_fx", "moment_stiffness:bearing_fy", "moment_stiffness:bearing_fz",
      "moment_stiffness:bearing_rx", "moment_stiffness:bearing_ry", "moment_stiffness:mount1",
      "moment_stiffness:mount2",   "moment_stiffness:mount3",   "moment_stiffness:mount4",
      "added_mass:spindle",        "added_mass:housing"})
    common_tail.push_back(id);

  SECTION("n_sp is zero and the same in every data set: no gyroscopic candidate") {
    std::vector<std::string> expected = common_head;
    expected.insert(expected.end(), common_tail.begin(), common_tail.end());
    expected.push_back("connection:base-spindle");
    const std::vector<Extension> xs = enumerate_extensions(ex.model, ex.text, {});
    CHECK_THAT(test::structural_ids_of(xs), Equals(expected));
    for (const Extension& x : xs) test::check_candidate(x);
  }
  SECTION("n_sp varies between data sets, and there is a peak to explain") {
    ExtensionContext ctx;
    ctx.varying_parameters = {"n_sp"};
    ctx.peak_hz = {190, 420};
    std::vector<std::string> expected = common_head;
    expected.push_back("gyroscopic:spindle");
    expected.insert(expected.end(), common_tail.begin(), common_tail.end());
    for (const char* id : {"resonator:spindle", "resonator:housing", "connection:base-spindle"}) expected.push_back(id);
    const std::vector<Extension> xs = enumerate_extensions(ex.model, ex.text, ctx);
    CHECK_THAT(test::structural_ids_of(xs), Equals(expected));
    for (const Extension& x : xs) test::check_candidate(x);
  }
  SECTION("an unexplained peak in one output's channels brings that output's sensor candidate") {
    ExtensionContext ctx;
    ctx.peak_hz = {1000};
    ctx.output_peak_hz["xs_front"] = {1000};
    std::vector<std::string> expected = common_head;
    expected.insert(expected.end(), common_tail.begin(), common_tail.end());
    // The mounting resonance (there is a peak); the signal chain's forms only where the model misses the output
    // alone, which a peak by itself does not say (the priors may put a structural mode elsewhere).
    for (const char* id :
         {"resonator:spindle", "resonator:housing", "sensor_dynamics:xs_front", "connection:base-spindle"})
      expected.push_back(id);
    std::vector<Extension> xs = enumerate_extensions(ex.model, ex.text, ctx);
    CHECK_THAT(test::structural_ids_of(xs), Equals(expected));
    const auto variants_of = [](const std::vector<Extension>& extensions) {
      std::vector<std::string> variants;
      for (const Extension& x : extensions)
        if (x.id == "sensor_dynamics:xs_front") variants.push_back(x.variant);
      return variants;
    };
    CHECK_THAT(variants_of(xs), Equals(std::vector<std::string>{"mounting resonance"}));
    for (const Extension& x : xs) test::check_candidate(x);
    ctx.outputs_with_findings = {"xs_front"};
    xs = enumerate_extensions(ex.model, ex.text, ctx);
    CHECK_THAT(variants_of(xs),
               Equals(std::vector<std::string>{"mounting resonance", "low-pass", "high-pass", "delay"}));
    for (const Extension& x : xs) test::check_candidate(x);
  }
  SECTION("a finding without a peak on one output's channels brings its signal chain's forms, not the mounting") {
    ExtensionContext ctx;
    ctx.outputs_with_findings = {"xs_rear"};
    ctx.output_delay_s["xs_rear"] = 2e-4;
    ctx.band_lo_hz = 50;
    ctx.band_hi_hz = 1200;
    std::vector<std::string> variants;
    const std::vector<Extension> xs = enumerate_extensions(ex.model, ex.text, ctx);
    for (const Extension& x : xs) {
      if (x.id != "sensor_dynamics:xs_rear") continue;
      variants.push_back(x.variant);
      REQUIRE(x.model.filters.size() == 1);
      CHECK(x.model.filters[0].output == "xs_rear");
      test::check_candidate(x);
    }
    CHECK_THAT(variants, Equals(std::vector<std::string>{"low-pass", "high-pass", "delay"}));
  }
  SECTION("a non-zero spin speed alone brings the gyroscopic candidate") {
    ExtensionContext ctx;
    ctx.values["n_sp"] = 300;
    const std::vector<std::string> ids = test::ids_of(enumerate_extensions(ex.model, ex.text, ctx));
    CHECK(std::count(ids.begin(), ids.end(), "gyroscopic:spindle") == 1);
  }
}

TEST_CASE("a model built in code is written out and extended the same way", "[diagnosis]") {
  const test::Example ex = test::load("mdof2");
  ir::ModelIr built = ex.model;
  built.file.clear();
  const std::vector<Extension> xs = enumerate_extensions(built, "", {});
  REQUIRE(test::structural_ids_of(xs).size() == 4);
  for (const Extension& x : xs) test::check_candidate(x);
}

TEST_CASE("the measurement chain: a factor per output and on the input, and swapped outputs", "[diagnosis]") {
  const test::Example ex = test::load("mdof2");
  std::vector<Extension> chain;
  for (Extension& x : enumerate_extensions(ex.model, ex.text, {}))
    if (x.operator_name == "measurement_chain") chain.push_back(std::move(x));
  CHECK_THAT(test::ids_of(chain),
             Equals(std::vector<std::string>{"measurement_chain:gain:d1", "measurement_chain:gain:d1",
                                             "measurement_chain:gain:d1", "measurement_chain:gain:d2",
                                             "measurement_chain:gain:d2", "measurement_chain:gain:d2",
                                             "measurement_chain:form:d1", "measurement_chain:form:d1",
                                             "measurement_chain:form:d2", "measurement_chain:form:d2",
                                             "measurement_chain:swap:d1,d2", "measurement_chain:input:F1",
                                             "measurement_chain:input:F1", "measurement_chain:input:F1"}));
  for (const Extension& x : chain) {
    INFO(x.id << " " << x.variant);
    test::check_candidate(x);
    if (x.target.rfind("form:", 0) == 0) {
      // The output measures another form of its quantity: its statement's kind changes, nothing else.
      CHECK(x.new_parameters.empty());
      const ir::Output& o = x.model.outputs[x.target == "form:d1" ? 0 : 1];
      CHECK(ir::to_string(o.kind) == x.variant);
      CHECK(o.kind != ir::OutputKind::Displacement);
      CHECK(x.model.filters.empty());
      continue;
    }
    if (x.target == "swap:d1,d2") {
      // The two output statements exchange their names: d1 now measures mass2.
      CHECK(x.new_parameters.empty());
      CHECK(x.model.outputs[0].name == "d2");
      CHECK(x.model.outputs[1].name == "d1");
      continue;
    }
    if (x.variant == "reversed") {
      // The sign alone: no new parameter; an output's reading negated by a gain of -1, the input's direction turned.
      CHECK(x.new_parameters.empty());
      if (x.target == "input:F1") {
        CHECK(x.model.filters.empty());
        CHECK(x.mdl_text.find("F1 reversed") != std::string::npos);
      } else {
        REQUIRE(x.model.filters.size() == 1u);
        CHECK(x.model.filters[0].kind == ir::FilterKind::Gain);
        REQUIRE(x.model.filters[0].factor);
        CHECK(ModelValues(x.model, {}).of(*x.model.filters[0].factor) == -1.0);
      }
      continue;
    }
    REQUIRE(x.new_parameters.size() == 1);
    const ir::Parameter* g = x.model.find_parameter(x.new_parameters[0].name);
    REQUIRE(g);
    const double start = ModelValues(x.model, {}).of_parameter(g->name);
    CHECK(start == (x.variant == "polarity" ? -1.0 : 1.0));
    // A gain filter per output it scales: one for an output, every output for the input.
    CHECK(x.model.filters.size() == (x.target == "input:F1" ? 2u : 1u));
    for (const ir::Filter& f : x.model.filters) CHECK(f.kind == ir::FilterKind::Gain);
  }
}

TEST_CASE("the measurement chain with several inputs: each input's factor through its own gain", "[diagnosis]") {
  // mdof2 with a second force on mass2 whose record already has a gain: the candidate multiplies it.
  const test::Example one = test::load("mdof2");
  const std::string text = one.text + "param gF2 = 2 \"\"\ninput F2 force on mass2 along x gain gF2\n";
  const ir::ModelIr model = frontend::parse_string(text, "two_inputs.mdl");
  std::vector<Extension> inputs;
  for (Extension& x : enumerate_extensions(model, text, {}))
    if (x.target.rfind("input:", 0) == 0) inputs.push_back(std::move(x));
  CHECK_THAT(test::ids_of(inputs),
             Equals(std::vector<std::string>{"measurement_chain:input:F1", "measurement_chain:input:F1",
                                             "measurement_chain:input:F1", "measurement_chain:input:F2",
                                             "measurement_chain:input:F2", "measurement_chain:input:F2"}));
  for (const Extension& x : inputs) {
    INFO(x.id << " " << x.variant << "\n" << x.mdl_text);
    test::check_candidate(x);
    CHECK(x.model.filters.empty());  // no output is touched: only the input's columns scale
    const bool second = x.target == "input:F2";
    const ir::Input& changed = x.model.inputs[second ? 1 : 0];
    const ir::Input& other = x.model.inputs[second ? 0 : 1];
    CHECK(frontend::write_input(other) == frontend::write_input(model.inputs[second ? 0 : 1]));
    if (x.variant == "reversed") {
      CHECK(x.new_parameters.empty());
      CHECK(ir::to_string(changed.direction.vector[0]) == "-1");
      continue;
    }
    REQUIRE(x.new_parameters.size() == 1);
    const std::string g = x.new_parameters[0].name;
    CHECK(ModelValues(x.model, {}).of_parameter(g) == (x.variant == "polarity" ? -1.0 : 1.0));
    REQUIRE(changed.gain);
    CHECK(ir::to_string(*changed.gain) == (second ? "gF2*" + g : g));
  }
}

TEST_CASE("a text that is not the model's is refused", "[diagnosis]") {
  const test::Example mdof2 = test::load("mdof2");
  const test::Example spindle = test::load("spindle");
  CHECK_THROWS_AS(enumerate_extensions(mdof2.model, spindle.text, {}), std::invalid_argument);
}
