// The in-process backend of the runtime's Model interface: a model derived at run time (e.g. a model the
// diagnosis has just extended) evaluated from compiled expression tapes, with no C++ compile step.
// Agrees with the generated code to rounding.
#pragma once

#include <memory>

#include <mbgen/model.hpp>

#include "evaluator/expression_tape.hpp"
#include "symbolic/derive.hpp"
#include "symbolic/symbolic_model.hpp"

namespace mbgen::evaluator {

class SymbolicEvaluator final : public mbgen::Model {
 public:
  // Compiles M, C (with gyroscopic terms), K, B, Cd, Cv, Ca and their parameter derivatives. `sym` may be
  // destroyed afterwards.
  explicit SymbolicEvaluator(const symbolic::SymbolicModel& sym);

  const ModelInfo& info() const override { return info_; }
  void evaluate(const Eigen::VectorXd& p, ModelMatrices& out) const override;
  void derivatives(const Eigen::VectorXd& p, ModelDerivatives& out) const override;

 private:
  enum Matrix { kM, kC, kK, kB, kCd, kCv, kCa, kMatrixCount };
  struct Slot {
    Matrix matrix;
    int row, col, param;
  };

  void check_size(const Eigen::VectorXd& p) const;

  ModelInfo info_;
  int n_ = 0;
  std::vector<Slot> value_slots_, derivative_slots_;
  std::unique_ptr<ExpressionTape> values_, derivatives_;
};

// Parses nothing: derives `model` (with `--set` overrides in `options`) and compiles it.
std::unique_ptr<mbgen::Model> make_evaluator(const ir::ModelIr& model, const symbolic::DeriveOptions& options = {});

}  // namespace mbgen::evaluator
