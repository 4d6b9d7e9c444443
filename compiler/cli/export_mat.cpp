#include "cli/export_mat.hpp"

#include <mbgen/dynamics/model_modes.hpp>
#include <mbgen/dynamics/state_space.hpp>

#include "cli/mat_file.hpp"
#include "cli/version.hpp"

namespace mbgen::cli {

namespace {

Eigen::MatrixXd column(const std::vector<double>& v) {
  return Eigen::Map<const Eigen::VectorXd>(v.data(), static_cast<Eigen::Index>(v.size()));
}

}  // namespace

std::string export_mat(const std::string& model_path, const std::string& what, const ModelInfo& info,
                       const Eigen::VectorXd& p, const ModelMatrices& m, const FrfResult* frf) {
  MatFile mat;
  mat.text("schema", "mbgen-export/1");
  mat.text("model", model_path);
  mat.text("what", what);
  std::vector<std::string> names;
  for (const ParameterInfo& parameter : info.parameters) names.push_back(parameter.name);
  mat.texts("parameter_names", names);
  mat.matrix("parameter_values", p);
  mat.texts("coordinates", info.coordinates);
  mat.texts("inputs", info.inputs);
  mat.texts("outputs", info.outputs);
  if (what == "matrices") {
    mat.matrix("M", m.M);
    mat.matrix("C", m.C);
    mat.matrix("K", m.K);
    mat.matrix("B", m.B);
    mat.matrix("Cd", m.Cd);
    mat.matrix("Cv", m.Cv);
    mat.matrix("Ca", m.Ca);
  } else if (what == "state-space") {
    const StateSpace ss = state_space(m);
    mat.matrix("A", ss.A);
    mat.matrix("B", ss.B);
    mat.matrix("C", ss.C);
    mat.matrix("D", ss.D);
  } else if (what == "modes") {
    const std::vector<Mode> modes = modal_analysis(m.M, m.C, m.K);
    std::vector<double> f, zeta;
    std::vector<std::complex<double>> eigenvalues, shapes;
    for (const Mode& mode : modes) {
      f.push_back(mode.f_hz);
      zeta.push_back(mode.zeta);
      eigenvalues.push_back(mode.eigenvalue);
      for (Eigen::Index c = 0; c < mode.shape.size(); ++c) shapes.push_back(mode.shape[c]);  // column by column
    }
    mat.matrix("f_hz", column(f));
    mat.matrix("zeta", column(zeta));
    mat.complex_array("eigenvalue", {modes.size(), 1}, eigenvalues);
    mat.complex_array("shape", {info.coordinates.size(), modes.size()}, shapes);
  } else {
    // H(k, o, i): MATLAB's order runs over the lines first, then the outputs, then the inputs.
    std::vector<std::complex<double>> h;
    for (std::size_t i = 0; i < info.inputs.size(); ++i)
      for (std::size_t o = 0; o < info.outputs.size(); ++o)
        for (const Eigen::MatrixXcd& line : frf->H)
          h.push_back(line(static_cast<Eigen::Index>(o), static_cast<Eigen::Index>(i)));
    mat.matrix("f_hz", column(frf->freqs_hz));
    mat.complex_array("H", {frf->freqs_hz.size(), info.outputs.size(), info.inputs.size()}, h);
  }
  // No date in the header: the same input gives the same bytes.
  return mat.bytes("MATLAB 5.0 MAT-file, Created by: " + version_text() + " export");
}

}  // namespace mbgen::cli
