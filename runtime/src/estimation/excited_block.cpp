#include "excited_block.hpp"

#include "dynamics/model_checks.hpp"
#include "mbgen/estimation/fit.hpp"

#include <numeric>
#include <string>

namespace mbgen::estimation {

namespace {

// Union-find over coordinates.
class Components {
 public:
  explicit Components(Eigen::Index n) : parent_(static_cast<std::size_t>(n)) {
    std::iota(parent_.begin(), parent_.end(), 0);
  }
  int root(int i) {
    while (parent_[static_cast<std::size_t>(i)] != i) {
      parent_[static_cast<std::size_t>(i)] = parent_[static_cast<std::size_t>(parent_[static_cast<std::size_t>(i)])];
      i = parent_[static_cast<std::size_t>(i)];
    }
    return i;
  }
  void join(int a, int b) { parent_[static_cast<std::size_t>(root(a))] = root(b); }

 private:
  std::vector<int> parent_;
};

void check_entries(const std::vector<DerivativeEntry>& entries, const Eigen::MatrixXd& X, const char* matrix) {
  for (const auto& e : entries)
    if (e.row < 0 || e.row >= X.rows() || e.col < 0 || e.col >= X.cols())
      throw FitError(std::string("model derivative entry of ") + matrix + " out of range (parameter " +
                     std::to_string(e.param) + ", row " + std::to_string(e.row) + ", column " +
                     std::to_string(e.col) + ")");
}

// Copies the entries that are wanted and whose row and column survive, renumbered.
void copy_entries(const std::vector<DerivativeEntry>& in, const std::vector<int>& column, const std::vector<int>& row_map,
                  const std::vector<int>& col_map, std::vector<DerivativeEntry>& out) {
  out.clear();
  for (const auto& e : in) {
    if (e.param < 0 || e.param >= static_cast<int>(column.size())) continue;
    const int j = column[static_cast<std::size_t>(e.param)];
    const int r = row_map[static_cast<std::size_t>(e.row)], c = col_map[static_cast<std::size_t>(e.col)];
    if (j < 0 || r < 0 || c < 0 || e.value == 0) continue;
    out.push_back({j, r, c, e.value});
  }
}

}  // namespace

ReducedModel reduce_to_excited_block(const ModelMatrices& m, const ModelDerivatives* d, const std::vector<int>& inputs,
                                     const std::vector<int>& outputs, const std::vector<int>& column) {
  detail::check_matrices(m, "fit");
  const Eigen::Index n = m.M.rows();
  if (d) {
    check_entries(d->M, m.M, "M");
    check_entries(d->C, m.C, "C");
    check_entries(d->K, m.K, "K");
    check_entries(d->B, m.B, "B");
    check_entries(d->Cd, m.Cd, "Cd");
    check_entries(d->Cv, m.Cv, "Cv");
    check_entries(d->Ca, m.Ca, "Ca");
  }
  Components comp(n);
  for (const Eigen::MatrixXd* X : {&m.M, &m.C, &m.K})
    if (X->rows() == n && X->cols() == n)
      for (Eigen::Index c = 0; c < n; ++c)
        for (Eigen::Index r = 0; r < n; ++r)
          if ((*X)(r, c) != 0) comp.join(static_cast<int>(r), static_cast<int>(c));
  if (d)
    for (const auto* list : {&d->M, &d->C, &d->K})
      for (const auto& e : *list) comp.join(e.row, e.col);

  // Blocks reached by the inputs in use, through B or through a derivative of B.
  std::vector<bool> excited_root(static_cast<std::size_t>(n), false);
  std::vector<bool> input_used(static_cast<std::size_t>(m.B.cols()), false);
  for (int i : inputs) input_used[static_cast<std::size_t>(i)] = true;
  for (int i : inputs)
    for (Eigen::Index r = 0; r < n; ++r)
      if (m.B(r, i) != 0) excited_root[static_cast<std::size_t>(comp.root(static_cast<int>(r)))] = true;
  if (d)
    for (const auto& e : d->B)
      if (input_used[static_cast<std::size_t>(e.col)]) excited_root[static_cast<std::size_t>(comp.root(e.row))] = true;

  ReducedModel out;
  std::vector<int> coord_map(static_cast<std::size_t>(n), -1);
  for (int q = 0; q < static_cast<int>(n); ++q)
    if (excited_root[static_cast<std::size_t>(comp.root(q))]) {
      coord_map[static_cast<std::size_t>(q)] = static_cast<int>(out.coordinates.size());
      out.coordinates.push_back(q);
    }
  const auto nr = static_cast<Eigen::Index>(out.coordinates.size());
  const auto ni = static_cast<Eigen::Index>(inputs.size()), no = static_cast<Eigen::Index>(outputs.size());
  out.m.M.resize(nr, nr);
  out.m.C.resize(nr, nr);
  out.m.K.resize(nr, nr);
  out.m.B.resize(nr, ni);
  out.m.Cd.resize(no, nr);
  out.m.Cv.resize(no, nr);
  out.m.Ca.resize(no, nr);
  for (Eigen::Index a = 0; a < nr; ++a) {
    const Eigen::Index qa = out.coordinates[static_cast<std::size_t>(a)];
    for (Eigen::Index b = 0; b < nr; ++b) {
      const Eigen::Index qb = out.coordinates[static_cast<std::size_t>(b)];
      out.m.M(a, b) = m.M(qa, qb);
      out.m.C(a, b) = m.C(qa, qb);
      out.m.K(a, b) = m.K(qa, qb);
    }
    for (Eigen::Index i = 0; i < ni; ++i) out.m.B(a, i) = m.B(qa, inputs[static_cast<std::size_t>(i)]);
    for (Eigen::Index o = 0; o < no; ++o) {
      const Eigen::Index mo = outputs[static_cast<std::size_t>(o)];
      out.m.Cd(o, a) = m.Cd(mo, qa);
      out.m.Cv(o, a) = m.Cv(mo, qa);
      out.m.Ca(o, a) = m.Ca(mo, qa);
    }
  }
  if (d) {
    std::vector<int> input_map(static_cast<std::size_t>(m.B.cols()), -1), output_map(static_cast<std::size_t>(m.Cd.rows()), -1);
    for (std::size_t i = 0; i < inputs.size(); ++i) input_map[static_cast<std::size_t>(inputs[i])] = static_cast<int>(i);
    for (std::size_t o = 0; o < outputs.size(); ++o) output_map[static_cast<std::size_t>(outputs[o])] = static_cast<int>(o);
    copy_entries(d->M, column, coord_map, coord_map, out.d.M);
    copy_entries(d->C, column, coord_map, coord_map, out.d.C);
    copy_entries(d->K, column, coord_map, coord_map, out.d.K);
    copy_entries(d->B, column, coord_map, input_map, out.d.B);
    copy_entries(d->Cd, column, output_map, coord_map, out.d.Cd);
    copy_entries(d->Cv, column, output_map, coord_map, out.d.Cv);
    copy_entries(d->Ca, column, output_map, coord_map, out.d.Ca);
  }
  return out;
}

}  // namespace mbgen::estimation
