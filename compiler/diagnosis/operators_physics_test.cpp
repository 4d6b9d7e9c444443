// What each operator does to the equations of motion, checked against matrices assembled by hand (exact, with
// GiNaC) or against the physics written another way (a point mass's moments about the origin).
#include "diagnosis/model_values.hpp"
#include "diagnosis/test_support.hpp"

#include <set>
#include <string>

using namespace mbgen;
using namespace mbgen::diagnosis;
using GiNaC::ex;
using symbolic::test::same;

namespace {

int coordinate(const symbolic::SymbolicModel& sm, const std::string& name) {
  for (std::size_t i = 0; i < sm.coordinates.size(); ++i)
    if (sm.coordinates[i].name() == name) return static_cast<int>(i);
  FAIL("no coordinate " << name);
  return -1;
}

symbolic::SymbolicModel derive(const ir::ModelIr& m) {
  symbolic::DeriveOptions o;
  o.transfer_functions = false;
  return symbolic::derive(m, o);
}

// A matrix of the extended model minus the nominal one (same coordinates). The two derivations have their own
// symbol objects: the nominal's are replaced by the extended model's of the same name first.
GiNaC::matrix difference(const symbolic::SymbolicModel& ext, const symbolic::SymbolicModel& nominal,
                         GiNaC::matrix symbolic::SymbolicModel::*which) {
  REQUIRE(ext.coordinates.size() == nominal.coordinates.size());
  GiNaC::exmap rename;
  for (const symbolic::FreeParameter& p : nominal.parameters)
    if (ext.parameter_index(p.name) >= 0) rename[p.sym] = symbolic::test::symbol_of(ext, p.name);
  return (ext.*which).sub(GiNaC::ex_to<GiNaC::matrix>((nominal.*which).subs(rename)));
}

void require_only(const GiNaC::matrix& d, const std::map<std::pair<int, int>, ex>& entries) {
  for (unsigned i = 0; i < d.rows(); ++i)
    for (unsigned j = 0; j < d.cols(); ++j) {
      const auto it = entries.find({static_cast<int>(i), static_cast<int>(j)});
      INFO("entry " << i << ", " << j << ": " << d(i, j));
      CHECK(same(d(i, j), it == entries.end() ? ex(0) : it->second));
    }
}

}  // namespace

TEST_CASE("compliant_ground:wall on mdof2 gives the hand-assembled three-mass chain", "[diagnosis][physics]") {
  const test::Example ex2 = test::load("mdof2");
  ExtensionContext ctx;
  ctx.peak_hz = {190};
  const Extension x = test::find(enumerate_extensions(ex2.model, ex2.text, ctx), "compliant_ground:wall");
  CHECK(x.model.bodies.size() == ex2.model.bodies.size() + 1);
  CHECK(x.model.find_body("wall"));
  CHECK_FALSE(x.model.is_ground("wall"));
  CHECK(x.model.is_ground("wall_fixed"));
  const symbolic::SymbolicModel sm = test::check_candidate(x);
  REQUIRE(sm.coordinates.size() == 3);
  const int w = coordinate(sm, "wall.x"), a = coordinate(sm, "mass1.x"), b = coordinate(sm, "mass2.x");
  auto p = [&](const char* n) { return symbolic::test::symbol_of(sm, n); };
  GiNaC::matrix K(3, 3), M(3, 3);
  K(w, w) = p("k_wall") + p("k11") + p("k22");
  K(w, a) = K(a, w) = -p("k11");
  K(w, b) = K(b, w) = -p("k22");
  K(a, a) = p("k11") + p("k12");
  K(b, b) = p("k22") + p("k12");
  K(a, b) = K(b, a) = -p("k12");
  M(w, w) = p("m_wall");
  M(a, a) = p("m1");
  M(b, b) = p("m2");
  CHECK(same(sm.K, K));
  CHECK(same(sm.M, M));
  // Start values: the ground's own mode (wall on its support alone) at the unexplained peak.
  const ModelValues v(x.model, {});
  const double f = std::sqrt(v.of_parameter("k_wall") / v.of_parameter("m_wall")) / (2 * M_PI);
  CHECK(f == Approx(190).epsilon(1e-5));
  CHECK(v.of_parameter("m_wall") == Approx(3 * (1.39 + 1.09)).epsilon(1e-5));
  // Its explanation is the wall's own resonance: the data must show it (docs/diagnosis.md, step 6).
  CHECK(x.resonating_bodies == std::vector<std::string>{"wall"});
}

TEST_CASE("compliant_ground:base on the spindle: the base is a translating body on one isotropic support",
          "[diagnosis][physics]") {
  const test::Example sp = test::load("spindle");
  const Extension x = test::find(enumerate_extensions(sp.model, sp.text, {}), "compliant_ground:base");
  const symbolic::SymbolicModel sm = test::check_candidate(x);
  CHECK(sm.coordinates.size() == 11 + 3);
  const ir::Body* base = x.model.find_body("base");
  REQUIRE(base);
  CHECK(base->dofs == std::vector<ir::Dof>{ir::Dof::X, ir::Dof::Y, ir::Dof::Z});
  // Centroid of the four mount points on the base, (0, -0.080, 0); spread: the corner distance.
  const ModelValues v(x.model, {});
  CHECK(v.of(base->position[1]) == Approx(-0.08));
  CHECK(v.of_parameter("r_base") == Approx(std::hypot(0.048, 0.060)).epsilon(1e-5));
  // Each base translation: the support plus the four mounts' stiffness along that axis.
  auto p = [&](const char* n) { return symbolic::test::symbol_of(sm, n); };
  CHECK(same(sm.K(coordinate(sm, "base.x"), coordinate(sm, "base.x")), p("k_base") + 4 * p("k_hbx")));
  CHECK(same(sm.K(coordinate(sm, "base.y"), coordinate(sm, "base.y")), p("k_base") + 4 * p("k_hby")));
  CHECK(same(sm.M(coordinate(sm, "base.z"), coordinate(sm, "base.z")), p("m_base")));
}

TEST_CASE("compliant_ground:base on feet: a six-coordinate block below the mounts, standing on a foot under each",
          "[diagnosis][physics]") {
  const test::Example sp = test::load("spindle");
  const std::vector<Extension> xs = enumerate_extensions(sp.model, sp.text, {});
  const auto it = std::find_if(xs.begin(), xs.end(), [](const Extension& x) { return x.variant == "on feet"; });
  REQUIRE(it != xs.end());
  const Extension& x = *it;
  CHECK(x.id == "compliant_ground:base");
  const symbolic::SymbolicModel sm = test::check_candidate(x);
  CHECK(sm.coordinates.size() == 11 + 6);
  const ir::Body* base = x.model.find_body("base");
  REQUIRE(base);
  CHECK(base->dofs.size() == 6);
  CHECK(x.resonating_bodies == std::vector<std::string>{"base"});
  int feet = 0;
  for (const ir::Element& e : x.model.elements) feet += e.name.rfind("base_foot", 0) == 0;
  CHECK(feet == 4);
  // Hand-assembled, about the base's centre of mass, which lies d_base below the mounts' base points (down is -y:
  // from the spindle's and housing's centre of mass at the origin to the mounts' centroid at y = -0.080). Each
  // mount's base point lies at (+-0.048, +d, +-0.060) from it, each foot at (+-0.048, -d, +-0.060). A spring3
  // along global axes at offset r adds k_y r_x^2 + k_x r_y^2 to the rotation about z, k_z r_x^2 + k_x r_z^2 about y,
  // k_y r_z^2 + k_z r_y^2 about x, and -k_x r_y to the coupling of x with the rotation about z.
  auto p = [&](const char* n) { return symbolic::test::symbol_of(sm, n); };
  const ex fx = p("k_basex"), fy = p("k_basey"), fz = p("k_basez");  // feet
  const ex mx = p("k_hbx"), my = p("k_hby"), mz = p("k_hbz");        // mounts
  const ex d = p("d_base");
  const ex dx2 = GiNaC::numeric(48, 1000) * GiNaC::numeric(48, 1000), dz2 = GiNaC::numeric(6, 100) * GiNaC::numeric(6, 100);
  const auto K = [&](const char* a, const char* b) { return sm.K(coordinate(sm, a), coordinate(sm, b)); };
  CHECK(same(K("base.x", "base.x"), 4 * (fx + mx)));
  CHECK(same(K("base.rz", "base.rz"), 4 * ((fy + my) * dx2 + (fx + mx) * d * d)));
  CHECK(same(K("base.ry", "base.ry"), 4 * ((fz + mz) * dx2 + (fx + mx) * dz2)));
  CHECK(same(K("base.rx", "base.rx"), 4 * ((fy + my) * dz2 + (fz + mz) * d * d)));
  // The feet below the centre of mass and the mounts above it pull the translation and the rocking together in
  // opposite senses: the coupling the block's depth brings.
  CHECK(same(K("base.x", "base.rz"), 4 * d * (fx - mx)));
  CHECK_FALSE(same(K("base.x", "base.rz"), 0));  // can fail
  const ex m = p("m_base");
  CHECK(same(sm.M(coordinate(sm, "base.x"), coordinate(sm, "base.x")), m));
  CHECK(same(sm.M(coordinate(sm, "base.ry"), coordinate(sm, "base.ry")), m * p("r_basey") * p("r_basey")));
  CHECK(same(sm.M(coordinate(sm, "base.rz"), coordinate(sm, "base.rz")), m * p("r_basez") * p("r_basez")));
  CHECK(same(sm.M(coordinate(sm, "base.rx"), coordinate(sm, "base.rx")), m * p("r_basex") * p("r_basex")));
  // It estimates the mass, the depth, the radii of gyration about the axes the force along x turns the base about
  // (y and z; about x the inertia is known), and per-axis stiffnesses and dampings of the feet.
  std::vector<std::string> fresh;
  for (const NewParameter& np : x.new_parameters) fresh.push_back(np.name);
  CHECK(fresh == std::vector<std::string>{"m_base", "d_base", "r_basey", "r_basez", "k_basex", "c_basex", "k_basey",
                                          "c_basey", "k_basez", "c_basez"});
  const ir::Parameter* rx = x.model.find_parameter("r_basex");
  REQUIRE(rx);
  CHECK(rx->role == ir::Role::Known);
  // Its start from the simple variant's estimate: the same mass; the simple base's support shared by the four feet
  // along x (the axis the force turns the base about, so its translation there is the simple base's), ten times
  // stiffer across as the operator's own start has it; each foot a quarter of the damping.
  const Extension::VariantStart& from = x.start_from_variant;
  CHECK(from.variant == "simple");
  const auto simple = std::find_if(xs.begin(), xs.end(), [](const Extension& e) { return e.variant == "simple"; });
  REQUIRE(simple != xs.end());
  std::vector<std::string> simple_new;
  for (const NewParameter& np : simple->new_parameters) simple_new.push_back(np.name);
  REQUIRE(simple_new == std::vector<std::string>{"m_base", "k_base", "c_base"});
  using Source = std::pair<std::string, double>;
  CHECK(from.from == std::map<std::string, Source>{{"m_base", {"m_base", 1.0}},
                                                   {"k_basex", {"k_base", 0.25}},
                                                   {"k_basey", {"k_base", 2.5}},
                                                   {"k_basez", {"k_base", 2.5}},
                                                   {"c_basex", {"c_base", 0.25}},
                                                   {"c_basey", {"c_base", 0.25}},
                                                   {"c_basez", {"c_base", 0.25}}});
}

TEST_CASE("added_mass changes the mass by exactly ma and the moments about the origin as a point mass does",
          "[diagnosis][physics]") {
  const test::Example sp = test::load("spindle");
  const std::vector<Extension> xs = enumerate_extensions(sp.model, sp.text, {});
  for (const char* body : {"spindle", "housing"}) {
    INFO(body);
    const Extension& x = test::find(xs, std::string("added_mass:") + body);
    const symbolic::SymbolicModel sm = test::check_candidate(x);
    const std::string ma = std::string("ma_") + body;
    const ir::Body& before = *sp.model.find_body(body);
    const ir::Body& after = *x.model.find_body(body);
    const GiNaC::ex m0 = symbolic::test::symbol_of(sm, before.mass.text);
    CHECK(same(sm.M(coordinate(sm, std::string(body) + ".y"), coordinate(sm, std::string(body) + ".y")),
               m0 + symbolic::test::symbol_of(sm, ma)));

    // Moments about the origin at a non-trivial added mass: body + point mass at p, written directly.
    ModelValues v(x.model, {{ma, 1.7}});
    const double m = v.of(before.mass), mass = 1.7;
    const ir::Attachment& at = std::string(body) == "spindle" ? x.model.inputs[0].at : x.model.outputs[2].at;
    const double p[3] = {v.of(at.point[0]), v.of(at.point[1]), v.of(at.point[2])};
    double c0[3], c1[3];
    for (int k = 0; k < 3; ++k) {
      c0[k] = v.of(before.position[k]);
      c1[k] = v.of(after.position[k]);
    }
    CHECK(v.of(after.mass) == Approx(m + mass));
    for (int k = 0; k < 3; ++k) CHECK((m + mass) * c1[k] == Approx(m * c0[k] + mass * p[k]).margin(1e-12));
    auto tensor = [&](const ir::Body& b, int i, int j) {
      const int index[3][3] = {{0, 3, 4}, {3, 1, 5}, {4, 5, 2}};
      const auto& e = b.inertia[index[i][j]];
      return e ? v.of(*e) : 0.0;
    };
    // Second moments about the origin: J + m (|c|^2 E - c c^T) for each part.
    auto about_origin = [](double mass_, const double* c, int i, int j) {
      const double c2 = c[0] * c[0] + c[1] * c[1] + c[2] * c[2];
      return mass_ * ((i == j ? c2 : 0.0) - c[i] * c[j]);
    };
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        INFO("inertia " << i << j);
        const double expected = tensor(before, i, j) + about_origin(m, c0, i, j) + about_origin(mass, p, i, j);
        CHECK(tensor(after, i, j) + about_origin(m + mass, c1, i, j) == Approx(expected).margin(1e-12));
      }
  }
}

TEST_CASE("moment_stiffness:bearing_fx adds one rotational spring about y between spindle and housing",
          "[diagnosis][physics]") {
  const test::Example sp = test::load("spindle");
  const Extension x = test::find(enumerate_extensions(sp.model, sp.text, {}), "moment_stiffness:bearing_fx");
  const symbolic::SymbolicModel sm = test::check_candidate(x);
  const symbolic::SymbolicModel nominal = derive(sp.model);
  const ex kr = symbolic::test::symbol_of(sm, "kr_bearing_fx"), cr = symbolic::test::symbol_of(sm, "cr_bearing_fx");
  const int s = coordinate(sm, "spindle.ry"), h = coordinate(sm, "housing.ry");
  require_only(difference(sm, nominal, &symbolic::SymbolicModel::K), {{{s, s}, kr}, {{h, h}, kr}, {{s, h}, -kr}, {{h, s}, -kr}});
  require_only(difference(sm, nominal, &symbolic::SymbolicModel::C), {{{s, s}, cr}, {{h, h}, cr}, {{s, h}, -cr}, {{h, s}, -cr}});
}

TEST_CASE("connection:base-spindle adds an isotropic spring at the spindle's centre of mass", "[diagnosis][physics]") {
  const test::Example sp = test::load("spindle");
  const Extension x = test::find(enumerate_extensions(sp.model, sp.text, {}), "connection:base-spindle");
  const symbolic::SymbolicModel sm = test::check_candidate(x);
  const symbolic::SymbolicModel nominal = derive(sp.model);
  const ex k = symbolic::test::symbol_of(sm, "k_base_spindle");
  const int cx = coordinate(sm, "spindle.x"), cy = coordinate(sm, "spindle.y"), cz = coordinate(sm, "spindle.z");
  require_only(difference(sm, nominal, &symbolic::SymbolicModel::K), {{{cx, cx}, k}, {{cy, cy}, k}, {{cz, cz}, k}});
}

TEST_CASE("gyroscopic:spindle couples the spindle's tilts at 2 pi n_sp J_szz", "[diagnosis][physics]") {
  const test::Example sp = test::load("spindle");
  ExtensionContext ctx;
  ctx.varying_parameters = {"n_sp"};
  const Extension x = test::find(enumerate_extensions(sp.model, sp.text, ctx), "gyroscopic:spindle");
  CHECK(x.new_parameters.empty());
  const symbolic::SymbolicModel sm = test::check_candidate(x);
  const ex n = symbolic::test::symbol_of(sm, "n_sp");
  const ex jz = symbolic::test::symbol_of(sm, "m_s") *
                (pow(symbolic::test::symbol_of(sm, "R_so"), 2) + pow(symbolic::test::symbol_of(sm, "R_si"), 2)) / 2;
  const int rx = coordinate(sm, "spindle.rx"), ry = coordinate(sm, "spindle.ry");
  const ex g = sm.G(rx, ry);
  CHECK((same(g, 2 * GiNaC::Pi * n * jz) || same(g, -2 * GiNaC::Pi * n * jz)));
  require_only(sm.G, {{{rx, ry}, g}, {{ry, rx}, -g}});
}

TEST_CASE("resonator:mass1 on mdof2: a mass on a spring at mass1, tuned to the peak", "[diagnosis][physics]") {
  const test::Example ex2 = test::load("mdof2");
  ExtensionContext ctx;
  ctx.peak_hz = {190, 40};
  const Extension x = test::find(enumerate_extensions(ex2.model, ex2.text, ctx), "resonator:mass1");
  const symbolic::SymbolicModel sm = test::check_candidate(x);
  const int a = coordinate(sm, "mass1.x"), b = coordinate(sm, "mass2.x"), r = coordinate(sm, "res_mass1.x");
  auto p = [&](const char* n) { return symbolic::test::symbol_of(sm, n); };
  GiNaC::matrix K(3, 3);
  K(a, a) = p("k11") + p("k12") + p("kr_mass1");
  K(b, b) = p("k22") + p("k12");
  K(r, r) = p("kr_mass1");
  K(a, b) = K(b, a) = -p("k12");
  K(a, r) = K(r, a) = -p("kr_mass1");
  CHECK(same(sm.K, K));
  const ModelValues v(x.model, {});
  CHECK(v.of_parameter("mr_mass1") == Approx(0.02 * 1.39));
  CHECK(std::sqrt(v.of_parameter("kr_mass1") / v.of_parameter("mr_mass1")) / (2 * M_PI) == Approx(190).epsilon(1e-5));
  CHECK(x.resonating_bodies == std::vector<std::string>{"res_mass1"});
}

TEST_CASE("untie_parameter:k_hbx: one variant per mount, and with its copy at k_hbx the equations are the nominal ones",
          "[diagnosis][physics]") {
  const test::Example sp = test::load("spindle");
  ExtensionContext ctx;
  ctx.values["k_hbx"] = 7.5e7;  // a fitted value: the copy starts at half of it (a loosened element)
  std::vector<std::string> variants;
  for (const Extension& x : enumerate_extensions(sp.model, sp.text, ctx)) {
    if (x.id != "untie_parameter:k_hbx") continue;
    variants.push_back(x.variant);
    REQUIRE(x.new_parameters.size() == 1);
    const std::string copy = "k_hbx_" + x.variant;
    CHECK(x.new_parameters[0].name == copy);
    CHECK(x.model.find_parameter("k_hbx") != nullptr);  // the other three mounts still share it
    CHECK(ModelValues(x.model, {}).of_parameter(copy) == 3.75e7);
    // Only the variant's own element reads the copy.
    for (const ir::Element& e : x.model.elements) {
      if (e.kind != ir::ElementKind::Spring3) continue;
      CHECK(ir::to_string(e.stiffness[0]) == (e.name == x.variant ? copy : std::string("k_hbx")));
    }
    const symbolic::SymbolicModel sm = test::check_candidate(x);
    const symbolic::SymbolicModel nominal = derive(sp.model);
    GiNaC::exmap to_nominal;
    for (const symbolic::FreeParameter& fp : sm.parameters)
      if (nominal.parameter_index(fp.name) >= 0) to_nominal[fp.sym] = symbolic::test::symbol_of(nominal, fp.name);
    to_nominal[symbolic::test::symbol_of(sm, copy)] = symbolic::test::symbol_of(nominal, "k_hbx");
    const GiNaC::matrix K = GiNaC::ex_to<GiNaC::matrix>(sm.K.subs(to_nominal));
    CHECK(same(K, nominal.K));
    // At another value the copy changes the equations (the comparison can fail).
    GiNaC::exmap apart = to_nominal;
    apart[symbolic::test::symbol_of(sm, copy)] = 2 * symbolic::test::symbol_of(nominal, "k_hbx");
    CHECK_FALSE(same(GiNaC::ex_to<GiNaC::matrix>(sm.K.subs(apart)), nominal.K));
  }
  CHECK(variants == std::vector<std::string>{"mount1", "mount2", "mount3", "mount4"});
}

TEST_CASE("untie_parameter with two users offers one variant: freeing either is the same model", "[diagnosis]") {
  const std::string text =
      "model two\nparam m = 1 \"kg\"\nparam k = 100 \"N/m\" estimate in [0, 1e6]\nground wall\n"
      "body a { mass m\n at (0, 0, 0)\n dof x }\n"
      "spring s1 { from wall\n to a\n along x\n stiffness k }\n"
      "spring s2 { from wall\n to a\n along x\n stiffness k }\n"
      "input F force on a along x\noutput d displacement of a along x\n";
  const ir::ModelIr m = frontend::parse_string(text, "two.mdl");
  const std::vector<Extension> xs = enumerate_extensions(m, text, {});
  REQUIRE(std::count_if(xs.begin(), xs.end(), [](const Extension& x) { return x.id == "untie_parameter:k"; }) == 1);
  const Extension& x = test::find(xs, "untie_parameter:k");
  CHECK(x.variant == "s1");
  test::check_candidate(x);
}

TEST_CASE("sensor_dynamics:d2 on mdof2: d2 reads a mass on a spring-damper at mass2, tuned to its peak",
          "[diagnosis][physics]") {
  const test::Example ex2 = test::load("mdof2");
  ExtensionContext ctx;
  ctx.peak_hz = {40, 190};
  ctx.output_peak_hz["d2"] = {190, 40};
  const std::vector<Extension> xs = enumerate_extensions(ex2.model, ex2.text, ctx);
  CHECK(std::none_of(xs.begin(), xs.end(), [](const Extension& x) { return x.id == "sensor_dynamics:d1"; }));
  const Extension& x = test::find(xs, "sensor_dynamics:d2");
  CHECK(x.resonating_bodies.empty());  // a sensor's mounting may resonate above the band: only its tail shows
  const symbolic::SymbolicModel sm = test::check_candidate(x);
  REQUIRE(sm.coordinates.size() == 3);
  const int a = coordinate(sm, "mass1.x"), b = coordinate(sm, "mass2.x"), s = coordinate(sm, "sensor_d2.x");
  auto p = [&](const char* n) { return symbolic::test::symbol_of(sm, n); };
  // Hand-assembled: the sensor mass ms on k_s = ms (2 pi fs)^2, c_s = 2 zs ms (2 pi fs) between mass2 and itself.
  const ex w = 2 * GiNaC::Pi * p("fs_d2");
  const ex ks = p("ms_d2") * w * w, cs = 2 * p("zs_d2") * p("ms_d2") * w;
  GiNaC::matrix K(3, 3), C(3, 3), M(3, 3), Cd(2, 3);
  K(a, a) = p("k11") + p("k12");
  K(b, b) = p("k22") + p("k12") + ks;
  K(s, s) = ks;
  K(a, b) = K(b, a) = -p("k12");
  K(b, s) = K(s, b) = -ks;
  C(a, a) = p("c11") + p("c12");
  C(b, b) = p("c22") + p("c12") + cs;
  C(s, s) = cs;
  C(a, b) = C(b, a) = -p("c12");
  C(b, s) = C(s, b) = -cs;
  M(a, a) = p("m1");
  M(b, b) = p("m2");
  M(s, s) = p("ms_d2");
  Cd(0, a) = 1;  // d1 still reads mass1
  Cd(1, s) = 1;  // d2 reads the sensor
  CHECK(same(sm.K, K));
  CHECK(same(sm.C, C));
  CHECK(same(sm.M, M));
  CHECK(same(sm.Cd, Cd));
  CHECK_FALSE(same(sm.K, M));  // the comparison can fail
  const ModelValues v(x.model, {});
  CHECK(v.of_parameter("ms_d2") == Approx(1e-3 * 1.09));
  CHECK(v.of_parameter("fs_d2") == Approx(190));
  CHECK(x.model.find_parameter("ms_d2")->role == ir::Role::Known);
  REQUIRE(x.new_parameters.size() == 2);  // fs_d2 and zs_d2: the data determine the resonance, not the mass
  // The output statement is replaced in place; the text keeps the old one commented out.
  CHECK(x.mdl_text.find("output d2 displacement of sensor_d2 along x") != std::string::npos);
}

TEST_CASE("free_parameter:c12 changes the role only", "[diagnosis][physics]") {
  const test::Example ex2 = test::load("mdof2");
  const Extension x = test::find(enumerate_extensions(ex2.model, ex2.text, {}), "free_parameter:c12");
  CHECK(x.freed_parameters == std::vector<std::string>{"c12"});
  CHECK(x.new_parameters.empty());
  CHECK(x.model.find_parameter("c12")->role == ir::Role::Estimate);
  CHECK(x.mdl_text.find("\"N s/m\"  estimate") != std::string::npos);
  ir::ModelIr back = x.model;
  for (ir::Parameter& p : back.parameters)
    if (p.name == "c12") p.role = ir::Role::Fixed;
  CHECK(frontend::write_model(back) == frontend::write_model(ex2.model));
}

TEST_CASE("no output is left without a filter of its own: the same misfit on every output is not the sensors'",
          "[diagnosis][physics]") {
  const test::Example ex2 = test::load("mdof2");
  ExtensionContext ctx;
  ctx.outputs_with_findings = {"d1", "d2"};
  ctx.band_lo_hz = 10;
  ctx.band_hi_hz = 400;
  const auto sensor_ids = [&](const ir::ModelIr& model, const std::string& text) {
    std::set<std::string> ids;
    for (const Extension& x : enumerate_extensions(model, text, ctx))
      if (x.operator_name == "sensor_dynamics") ids.insert(x.id);
    return ids;
  };
  CHECK(sensor_ids(ex2.model, ex2.text) == std::set<std::string>{"sensor_dynamics:d1", "sensor_dynamics:d2"});
  const Extension* delayed = nullptr;
  const std::vector<Extension> xs = enumerate_extensions(ex2.model, ex2.text, ctx);
  for (const Extension& x : xs)
    if (x.id == "sensor_dynamics:d2" && x.variant == "delay") delayed = &x;
  REQUIRE(delayed);
  // With d2 delayed, d1 is the last output without a filter: d2 may get another, d1 none.
  CHECK(sensor_ids(delayed->model, delayed->mdl_text) == std::set<std::string>{"sensor_dynamics:d2"});
}

TEST_CASE("sensor_dynamics:d2's signal-chain forms: one filter on d2 each, started from the residual's delay",
          "[diagnosis][physics]") {
  const test::Example ex2 = test::load("mdof2");
  ExtensionContext ctx;
  ctx.outputs_with_findings = {"d2"};
  ctx.output_delay_s["d2"] = 4e-4;
  ctx.band_lo_hz = 10;
  ctx.band_hi_hz = 400;
  const std::vector<Extension> xs = enumerate_extensions(ex2.model, ex2.text, ctx);
  std::map<std::string, const Extension*> by_variant;
  for (const Extension& x : xs)
    if (x.id == "sensor_dynamics:d2") by_variant[x.variant] = &x;
  REQUIRE(by_variant.size() == 3);  // no peak: no mounting resonance
  const auto filter_of = [&](const char* variant) -> const ir::Filter& {
    const Extension& x = *by_variant.at(variant);
    test::check_candidate(x);
    REQUIRE(x.model.filters.size() == 1);
    CHECK(x.model.filters[0].output == "d2");
    CHECK(x.model.bodies.size() == ex2.model.bodies.size());  // the structure is untouched
    return x.model.filters[0];
  };
  const ModelValues lp(by_variant.at("low-pass")->model, {});
  CHECK(filter_of("low-pass").kind == ir::FilterKind::Lowpass2);
  // A low-pass of damping ratio z lags like a delay 2 z / wc below its cutoff: the start matches the delay.
  CHECK(2 * lp.of(*filter_of("low-pass").damping) / (2 * M_PI * lp.of(*filter_of("low-pass").cutoff)) ==
        Approx(4e-4).epsilon(1e-3));
  const ModelValues hp(by_variant.at("high-pass")->model, {});
  CHECK(filter_of("high-pass").kind == ir::FilterKind::Highpass1);
  CHECK(hp.of(*filter_of("high-pass").cutoff) == Approx(5.0));  // half the band's lowest line
  const ModelValues dl(by_variant.at("delay")->model, {});
  const ir::Filter& delay = filter_of("delay");
  CHECK(delay.kind == ir::FilterKind::Delay);
  CHECK(dl.of(*delay.time) == Approx(4e-4));
  // Enough sections for four times the start over the band: w tau / N < 1.7 at 400 Hz.
  CHECK(2 * M_PI * 400 * 4 * 4e-4 / delay.sections < 1.7);
  const ir::Parameter* tau = by_variant.at("delay")->model.find_parameter("td_d2");
  REQUIRE(tau);
  REQUIRE(tau->upper);
  CHECK(2 * M_PI * 400 * dl.of(*tau->upper) / delay.sections == Approx(1.7));
}
