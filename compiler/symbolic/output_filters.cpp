#include "symbolic/output_filters.hpp"

#include "frontend/diagnostics.hpp"

namespace mbgen::symbolic {

namespace {

struct Section {
  GiNaC::ex a1, a0, b2, b1, b0;
};

GiNaC::matrix grown(const GiNaC::matrix& m, unsigned rows, unsigned cols) {
  GiNaC::matrix out(rows, cols);
  for (unsigned i = 0; i < m.rows(); ++i)
    for (unsigned j = 0; j < m.cols(); ++j) out(i, j) = m(i, j);
  return out;
}

std::vector<Section> sections_of(const ir::Filter& f, const ParameterTable& params) {
  if (f.kind == ir::FilterKind::Delay) {
    // The Pade sections divide by the time: a delay of zero (or less) at the parameters' values has no sections.
    const GiNaC::ex time = params.convert(*f.time);
    const GiNaC::ex at = GiNaC::evalf(time.subs(params.values()));
    if (GiNaC::is_a<GiNaC::numeric>(at) &&
        !(GiNaC::ex_to<GiNaC::numeric>(at).is_real() && GiNaC::ex_to<GiNaC::numeric>(at).is_positive()))
      throw frontend::ModelError(params.model().file, f.time->loc,
                                 "filter `{}`: its delay time is {:.6g} s at the parameters' values; a delay must be "
                                 "positive (for none, remove the filter)",
                                 f.name, GiNaC::ex_to<GiNaC::numeric>(at).real().to_double());
    const GiNaC::ex t = time / f.sections;
    return std::vector<Section>(static_cast<std::size_t>(f.sections),
                                Section{6 / t, 12 / (t * t), 1, -6 / t, 12 / (t * t)});
  }
  if (f.kind == ir::FilterKind::Gain) return {};  // no state (add_output_filters scales the output's rows)
  const GiNaC::ex wc = 2 * GiNaC::Pi * params.convert(*f.cutoff);
  switch (f.kind) {
    case ir::FilterKind::Lowpass2:
      return {Section{2 * params.convert(*f.damping) * wc, wc * wc, 0, 0, wc * wc}};
    case ir::FilterKind::Highpass2:
      return {Section{2 * params.convert(*f.damping) * wc, wc * wc, 1, 0, 0}};
    case ir::FilterKind::Highpass1:
      return {Section{3 * wc, 2 * wc * wc, 1, 2 * wc, 0}};
    case ir::FilterKind::Delay:
    case ir::FilterKind::Gain:
      break;
  }
  return {};
}

}  // namespace

void add_output_filters(const ParameterTable& params, SymbolicModel& out) {
  const ir::ModelIr& model = *out.model;
  if (model.filters.empty()) return;
  std::vector<std::vector<Section>> sections;
  unsigned states = 0;
  for (const ir::Filter& f : model.filters) {
    sections.push_back(sections_of(f, params));
    states += static_cast<unsigned>(sections.back().size());
  }
  const unsigned n0 = out.M.rows(), n = n0 + states;
  for (GiNaC::matrix* m : {&out.M, &out.C, &out.G, &out.K}) *m = grown(*m, n, n);
  out.B = grown(out.B, n, out.B.cols());
  for (GiNaC::matrix* m : {&out.Cd, &out.Cv, &out.Ca}) *m = grown(*m, m->rows(), n);

  unsigned w = n0;
  for (std::size_t k = 0; k < model.filters.size(); ++k) {
    const ir::Filter& f = model.filters[k];
    unsigned o = 0;
    while (o < model.outputs.size() && model.outputs[o].name != f.output) ++o;
    if (o == model.outputs.size())
      throw frontend::ModelError(model.file, f.loc, "filter `" + f.name + "`: no output `" + f.output + "`");
    if (f.kind == ir::FilterKind::Gain) {  // no state: the output's rows scaled (a constant commutes with the rest)
      const GiNaC::ex g = params.convert(*f.factor);
      if (GiNaC::evalf(g.subs(params.values())).is_zero())
        throw frontend::ModelError(model.file, f.factor->loc,
                                   "filter `{}`: its gain factor is 0 at the parameters' values: the output would read "
                                   "nothing",
                                   f.name);
      for (unsigned i = 0; i < w; ++i) {
        out.Cd(o, i) = g * out.Cd(o, i);
        out.Cv(o, i) = g * out.Cv(o, i);
        out.Ca(o, i) = g * out.Ca(o, i);
      }
      continue;
    }
    for (std::size_t j = 0; j < sections[k].size(); ++j, ++w) {
      const Section& sec = sections[k][j];
      const std::string state = sections[k].size() == 1 ? "w" : "w" + std::to_string(j + 1);
      out.coordinates.push_back({f.name, ir::Dof::X, state});
      // The section w'' + a1 w' + a0 w = y_in, with y_in = Cd q + Cv q' + Ca q'' (the output's rows so far), and
      // y_out = b2 y_in + (b1 - b2 a1) w' + (b0 - b2 a0) w, is written for the state z = a0 w:
      //   z'' / a0 + (a1 / a0) z' + z - y_in = 0,   y_out = b2 y_in + ((b1 - b2 a1) z' + (b0 - b2 a0) z) / a0.
      // Every entry then stays bounded whatever the filter's constants: a delay near zero (a0 = 12 / t^2) reads
      // (t^2 / 12) z'' + (t / 2) z' + z = y_in, y_out = y_in - t z', which is y_in at t = 0. Written for w, its
      // pivot of K - w^2 M + jw C grew as 1 / t^2 against the structure's, and the FRF's singularity test failed
      // (frame3's delay candidates, whose fits seek t -> 0, at 0.03 Hz). Every a0 is positive.
      out.M(w, w) = 1 / sec.a0;
      out.C(w, w) = sec.a1 / sec.a0;
      out.K(w, w) = 1;
      for (unsigned i = 0; i < w; ++i) {
        out.M(w, i) = -out.Ca(o, i);
        out.C(w, i) = -out.Cv(o, i);
        out.K(w, i) = -out.Cd(o, i);
      }
      for (unsigned i = 0; i < w; ++i) {
        out.Cd(o, i) = sec.b2 * out.Cd(o, i);
        out.Cv(o, i) = sec.b2 * out.Cv(o, i);
        out.Ca(o, i) = sec.b2 * out.Ca(o, i);
      }
      out.Cd(o, w) = (sec.b0 - sec.b2 * sec.a0) / sec.a0;
      out.Cv(o, w) = (sec.b1 - sec.b2 * sec.a1) / sec.a0;
    }
  }
}

}  // namespace mbgen::symbolic
