#include "direct_equations.hpp"

#include "estimation/excited_block.hpp"

#include "mbgen/data/frf_noise.hpp"
#include "numerics/constants.hpp"

#include <Eigen/SVD>

#include <algorithm>
#include <cmath>
#include <complex>
#include <numeric>

namespace mbgen::methods {

namespace {

using cd = std::complex<double>;
using numerics::kPi;
// Relative singular value below which the (weighted) output map is taken as rank-deficient.
constexpr double kRankTolerance = 1e-9;
// Time records: lines up to this fraction of the sample rate (aliasing, see the header).
constexpr double kTimeBandFraction = 0.1;

std::string where(const DataSet& d) { return d.file().empty() ? std::string("data set") : d.file(); }

std::string join(const std::vector<std::string>& v) {
  std::string s;
  for (const auto& x : v) s += (s.empty() ? "" : ", ") + x;
  return s;
}

Eigen::VectorXd with_set_values(const ModelInfo& info, const DataSet& d, Eigen::VectorXd p) {
  for (const auto& [name, value] : d.set()) {
    const int idx = info.parameter_index(name);
    if (idx < 0) throw FitError(where(d) + ": `# set " + name + "`: the model has no parameter " + name);
    p[idx] = value.value;
  }
  return p;
}

// The model coordinates (of `coordinates`) that the rows of `map` cannot give: those outside its row space.
std::vector<std::string> missing_coordinates(const ModelInfo& info, const Eigen::MatrixXcd& map,
                                             const std::vector<int>& coordinates) {
  const Eigen::Index n = map.cols();
  Eigen::MatrixXcd V(n, 0);
  if (map.rows() > 0) {
    const Eigen::JacobiSVD<Eigen::MatrixXcd> svd(map, Eigen::ComputeFullV);
    const Eigen::VectorXd s = svd.singularValues();
    Eigen::Index rank = 0;
    while (rank < s.size() && s[rank] > kRankTolerance * s[0]) ++rank;
    V = svd.matrixV().leftCols(rank);
  }
  std::vector<std::string> out;
  for (Eigen::Index c = 0; c < n; ++c) {
    const double seen = V.row(c).squaredNorm();  // |projection of e_c onto the row space|^2
    if (seen < 1 - 1e-6) out.push_back(info.coordinates[static_cast<std::size_t>(coordinates[static_cast<std::size_t>(c)])]);
  }
  return out;
}

[[noreturn]] void refuse(const ModelInfo& info, const DataSet& d, const std::string& what, const Eigen::MatrixXcd& map,
                         const std::vector<int>& coordinates, const std::vector<std::string>& outputs) {
  std::vector<std::string> all;
  for (int c : coordinates) all.push_back(info.coordinates[static_cast<std::size_t>(c)]);
  throw FitError(where(d) + ": error: --method direct needs the motion of every coordinate the input" + what +
                 " moves (" + std::to_string(coordinates.size()) + ": " + join(all) + "), but the outputs measured (" +
                 std::to_string(outputs.size()) + ": " + join(outputs) + ") cannot give " +
                 join(missing_coordinates(info, map, coordinates)) +
                 " (it needs as many independent outputs as coordinates)");
}

// X = map^+ y weighted by the outputs' noise sigma (total complex standard deviations); S with cov X = S S^H.
// False when the weighted map is rank-deficient (e.g. acceleration outputs at w = 0).
bool recover(const Eigen::MatrixXcd& map, const Eigen::VectorXcd& y, const Eigen::VectorXd& sigma, Eigen::VectorXcd& x,
             Eigen::MatrixXcd& S) {
  const Eigen::MatrixXcd Wm = sigma.cwiseInverse().asDiagonal() * map;
  const Eigen::JacobiSVD<Eigen::MatrixXcd> svd(Wm, Eigen::ComputeThinU | Eigen::ComputeThinV);
  const Eigen::VectorXd s = svd.singularValues();
  if (s.size() < map.cols() || s[0] <= 0 || s[s.size() - 1] < kRankTolerance * s[0]) return false;
  const Eigen::VectorXd inv = s.cwiseInverse();
  x = svd.matrixV() * inv.asDiagonal() * svd.matrixU().adjoint() * sigma.cwiseInverse().asDiagonal() * y;
  S = svd.matrixV() * inv.asDiagonal();
  return true;
}

Eigen::MatrixXcd output_map(const ModelMatrices& m, const std::vector<int>& rows, double w) {
  Eigen::MatrixXcd T(static_cast<Eigen::Index>(rows.size()), m.Cd.cols());
  for (std::size_t r = 0; r < rows.size(); ++r) {
    const Eigen::Index o = rows[r];
    T.row(static_cast<Eigen::Index>(r)) =
        m.Cd.row(o).cast<cd>() + cd(0, w) * m.Cv.row(o).cast<cd>() - w * w * m.Ca.row(o).cast<cd>();
  }
  return T;
}

void add_frf_blocks(const ModelInfo& info, const DataSet& d, int set, const ModelMatrices& m,
                    const ModelDerivatives& md, DirectEquations& out) {
  const FrfData& f = std::get<FrfData>(d.content);
  if (f.channels.empty() || f.f_hz.size() == 0) throw FitError(where(d) + ": no FRF channels or frequencies");
  std::vector<int> inputs, outputs;
  for (const FrfChannel& c : f.channels) {
    const int o = info.output_index(c.output), i = info.input_index(c.input);
    if (o < 0) throw FitError(where(d) + ": channel " + c.output + "/" + c.input + ": the model has no output " + c.output);
    if (i < 0) throw FitError(where(d) + ": channel " + c.output + "/" + c.input + ": the model has no input " + c.input);
    if (std::find(inputs.begin(), inputs.end(), i) == inputs.end()) inputs.push_back(i);
    if (std::find(outputs.begin(), outputs.end(), o) == outputs.end()) outputs.push_back(o);
  }
  std::vector<int> column(info.parameters.size());
  std::iota(column.begin(), column.end(), 0);
  int usable_inputs = 0;
  for (int input : inputs) {
    // The coordinates this input moves, and the channels measured with it.
    std::vector<const FrfChannel*> channels;
    std::vector<int> rows;  // model output of each channel
    std::vector<std::string> names;
    for (const FrfChannel& c : f.channels)
      if (info.input_index(c.input) == input) {
        channels.push_back(&c);
        rows.push_back(info.output_index(c.output));
        names.push_back(c.output);
      }
    const estimation::ReducedModel red = estimation::reduce_to_excited_block(m, &md, {input}, rows, column);
    const Eigen::Index n = static_cast<Eigen::Index>(red.coordinates.size());
    if (n == 0) continue;  // the input moves nothing the model has
    std::vector<int> own_rows(rows.size());
    std::iota(own_rows.begin(), own_rows.end(), 0);
    // Structural check at a line inside the band (not at w = 0, where acceleration outputs see nothing).
    const Eigen::Index mid = f.f_hz.size() / 2;
    const double w_mid = 2 * kPi * std::max(f.f_hz[mid], f.f_hz[f.f_hz.size() - 1] / 2);
    const Eigen::MatrixXcd T_mid = output_map(red.m, own_rows, w_mid);
    if (missing_coordinates(info, T_mid, red.coordinates).size() > 0) {
      if (inputs.size() == 1) refuse(info, d, " " + info.inputs[static_cast<std::size_t>(input)], T_mid, red.coordinates, names);
      out.notes.push_back(where(d) + ": input " + info.inputs[static_cast<std::size_t>(input)] +
                          " left out: its outputs cannot give " + join(missing_coordinates(info, T_mid, red.coordinates)));
      continue;
    }
    std::vector<Eigen::VectorXd> sigma;
    // The noise level from the data's line-to-line scatter (frf_noise.hpp), without the coherence: a file's
    // coherence is rounded (truthgen writes 6 digits), and at a sharp resonance 1 - coh falls below the rounding,
    // so its shape there is wrong by orders of magnitude, which sets the weights.
    for (const FrfChannel* c : channels) {
      FrfChannel plain = *c;
      plain.coherence.reset();
      sigma.push_back(frf_noise(f.f_hz, plain).sigma);
    }
    ++usable_inputs;
    for (Eigen::Index k = 0; k < f.f_hz.size(); ++k) {
      const double w = 2 * kPi * f.f_hz[k];
      Eigen::VectorXcd y(static_cast<Eigen::Index>(channels.size()));
      Eigen::VectorXd s(y.size());
      for (std::size_t c = 0; c < channels.size(); ++c) {
        y[static_cast<Eigen::Index>(c)] = channels[c]->values[k];
        s[static_cast<Eigen::Index>(c)] = std::max(sigma[c][k], 1e-300);
      }
      EquationBlock b;
      b.set = set;
      b.omega = w;
      b.kind = 0;
      b.rows = red.coordinates;  // model coordinates for now; renumbered at the end
      if (!recover(output_map(red.m, own_rows, w), y, s, b.x, b.noise)) {
        ++out.lines_skipped;
        continue;
      }
      b.force = Eigen::VectorXcd::Zero(static_cast<Eigen::Index>(info.inputs.size()));
      b.force[input] = 1;
      out.blocks.push_back(std::move(b));
    }
  }
  if (usable_inputs == 0) throw FitError(where(d) + ": error: --method direct: no input of this data set moves a coordinate the outputs can give");
}

// Continuous Fourier integrals over the record [t0, t0 + T], T = (N - 1) dt, at w = 2 pi k / T, k = 1..K:
// outputs by the periodic trapezoid sum (equal to the continuous integral up to aliasing), held inputs exactly.
void add_time_blocks(const ModelInfo& info, const DataSet& d, int set, const ModelMatrices& m,
                     const ModelDerivatives& md, DirectEquations& out) {
  const TimeRecord& t = std::get<TimeRecord>(d.content);
  const Eigen::Index N = t.samples();
  if (N < 16) throw FitError(where(d) + ": error: --method direct needs a record of at least 16 samples");
  require_inputs(t, info.inputs);
  std::vector<int> inputs(info.inputs.size()), outputs;
  std::iota(inputs.begin(), inputs.end(), 0);
  std::vector<std::string> names;
  for (std::size_t o = 0; o < info.outputs.size(); ++o)
    if (t.find(info.outputs[o])) {
      outputs.push_back(static_cast<int>(o));
      names.push_back(info.outputs[o]);
    }
  if (outputs.empty()) throw FitError(where(d) + ": the record has none of the model's outputs");
  std::vector<int> column(info.parameters.size());
  std::iota(column.begin(), column.end(), 0);
  const estimation::ReducedModel red = estimation::reduce_to_excited_block(m, &md, inputs, outputs, column);
  const Eigen::Index n = static_cast<Eigen::Index>(red.coordinates.size());
  if (n == 0) throw FitError(where(d) + ": error: --method direct: the record's inputs move no coordinate");
  // One kind of output: the end terms of a mixed set would multiply the unknown parameters (docs/methods.md).
  int kind = -1;
  std::vector<int> used;
  std::vector<std::string> used_names;
  for (std::size_t r = 0; r < outputs.size(); ++r) {
    const Eigen::Index o = static_cast<Eigen::Index>(r);
    const bool kinds[3] = {red.m.Cd.row(o).any(), red.m.Cv.row(o).any(), red.m.Ca.row(o).any()};
    const int count = int(kinds[0]) + int(kinds[1]) + int(kinds[2]);
    if (count == 0) continue;
    const int k = kinds[0] ? 0 : kinds[1] ? 1 : 2;
    if (count > 1 || (kind >= 0 && k != kind))
      throw FitError(where(d) + ": error: --method direct on time records needs outputs of one kind (all "
                     "displacements, all velocities or all accelerations); " + names[r] +
                     " differs from the others (use FRFs of the record instead)");
    kind = k;
    used.push_back(static_cast<int>(r));
    used_names.push_back(names[r]);
  }
  const Eigen::MatrixXd& map = kind == 0 ? red.m.Cd : kind == 1 ? red.m.Cv : red.m.Ca;
  Eigen::MatrixXcd T(static_cast<Eigen::Index>(used.size()), n);
  for (std::size_t r = 0; r < used.size(); ++r) T.row(static_cast<Eigen::Index>(r)) = map.row(used[r]).cast<cd>();
  if (!missing_coordinates(info, T, red.coordinates).empty()) refuse(info, d, "s", T, red.coordinates, used_names);

  const double dt = t.dt(), length = dt * double(N - 1);
  const Eigen::Index K = static_cast<Eigen::Index>(std::floor(kTimeBandFraction / dt * length));
  if (K < 4)
    throw FitError(where(d) + ": error: --method direct needs a record longer than 40 samples (its lines up to a tenth "
                   "of the sample rate are used)");
  // Signals: used outputs, then the model inputs.
  const Eigen::Index no = static_cast<Eigen::Index>(used.size()), ni = static_cast<Eigen::Index>(info.inputs.size());
  Eigen::MatrixXd sig(N, no + ni);
  Eigen::VectorXd sigma(no);
  for (Eigen::Index r = 0; r < no; ++r) {
    sig.col(r) = t.at(used_names[static_cast<std::size_t>(r)]).values;
    // Noise per output: white, proportional to its RMS, as the output-error fit weights records. A white sequence
    // of variance v has Fourier sums of variance N v dt^2: so scaled, the solver's noise scale is the noise's
    // variance relative to the output's mean square (1e-4 at 40 dB).
    const double level = std::sqrt(sig.col(r).squaredNorm() / double(N));
    sigma[r] = (level > 0 ? level : 1.0) * dt * std::sqrt(double(N));
  }
  for (Eigen::Index i = 0; i < ni; ++i) sig.col(no + i) = t.at(info.inputs[static_cast<std::size_t>(i)]).values;
  const bool first_order = t.hold == HoldMode::None;
  const int group = out.nuisance_groups++;
  for (Eigen::Index k = 1; k <= K; ++k) {
    const double w = 2 * kPi * double(k) / length;
    // Sums over n = 0..N-2 of signal_n e^{-i w n dt}, and of signal_{n+1} e^{-i w n dt} for the first-order hold.
    Eigen::VectorXcd s0 = Eigen::VectorXcd::Zero(no + ni), s1 = Eigen::VectorXcd::Zero(ni);
    const cd step = std::polar(1.0, -w * dt);
    cd phasor = 1;
    for (Eigen::Index j = 0; j + 1 < N; ++j) {
      if (j % 64 == 0) phasor = std::polar(1.0, -w * dt * double(j));  // no drift of the recurrence
      for (Eigen::Index c = 0; c < no + ni; ++c) s0[c] += sig(j, c) * phasor;
      if (first_order)
        for (Eigen::Index i = 0; i < ni; ++i) s1[i] += sig(j + 1, no + i) * phasor;
      phasor *= step;
    }
    EquationBlock b;
    b.set = set;
    b.omega = w;
    b.kind = kind;
    b.rows = red.coordinates;
    b.nuisance = group;
    Eigen::VectorXcd y(no);
    for (Eigen::Index r = 0; r < no; ++r) y[r] = dt * (s0[r] + 0.5 * (sig(N - 1, r) - sig(0, r)));
    if (!recover(T, y, sigma, b.x, b.noise)) {
      ++out.lines_skipped;
      continue;
    }
    // Held input: integral over each interval of u_j (zero order) or of the line from u_j to u_{j+1}.
    const cd s(0, w), e = std::exp(-s * dt);
    const cd whole = (1.0 - e) / s;                             // int_0^dt e^{-s tau} d tau
    const cd ramp = (1.0 - e * (1.0 + s * dt)) / (dt * s * s);  // int_0^dt (tau/dt) e^{-s tau} d tau
    b.force.resize(ni);
    for (Eigen::Index i = 0; i < ni; ++i)
      b.force[i] = first_order ? (whole - ramp) * s0[no + i] + ramp * s1[i] : whole * s0[no + i];
    out.blocks.push_back(std::move(b));
  }
  out.notes.push_back(where(d) + ": " + std::to_string(K) + " lines up to " + std::to_string(double(K) / length) +
                      " Hz of the record (a tenth of its sample rate), " +
                      (kind == 0 ? "displacements" : kind == 1 ? "velocities" : "accelerations") + " " +
                      join(used_names) + (first_order ? ", first-order hold" : ", zero-order hold"));
}

}  // namespace

DirectEquations direct_equations(const Model& model, const std::vector<DataSet>& data, const Eigen::VectorXd& values) {
  const ModelInfo& info = model.info();
  if (data.empty()) throw FitError("fit: no data sets given");
  DirectEquations out;
  ModelMatrices m;
  ModelDerivatives md;
  for (std::size_t s = 0; s < data.size(); ++s) {
    const Eigen::VectorXd p = with_set_values(info, data[s], values);
    model.evaluate(p, m);
    model.derivatives(p, md);
    if (data[s].is_frf())
      add_frf_blocks(info, data[s], static_cast<int>(s), m, md, out);
    else
      add_time_blocks(info, data[s], static_cast<int>(s), m, md, out);
  }
  // Renumber the blocks' model coordinates into the union of those used.
  for (const EquationBlock& b : out.blocks) out.coordinates.insert(out.coordinates.end(), b.rows.begin(), b.rows.end());
  std::sort(out.coordinates.begin(), out.coordinates.end());
  out.coordinates.erase(std::unique(out.coordinates.begin(), out.coordinates.end()), out.coordinates.end());
  for (EquationBlock& b : out.blocks)
    for (int& r : b.rows)
      r = static_cast<int>(std::lower_bound(out.coordinates.begin(), out.coordinates.end(), r) - out.coordinates.begin());
  if (out.blocks.empty()) throw FitError("fit: --method direct: no line of the data gives the coordinates' motion");
  return out;
}

}  // namespace mbgen::methods
