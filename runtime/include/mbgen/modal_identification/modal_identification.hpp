// Experimental modal analysis of measured FRFs, no model needed (docs/modal.md):
//
//   modal_data        the FRFs of one or more files on one frequency axis, cut to a band
//   lscf              poles at every model order 1..N by the poly-reference least-squares complex-frequency
//                     method (PolyMAX): a right matrix-fraction model H = B A^-1 in the z-domain basis
//                     exp(i w dt j), dt = 1 / (2 f_hi), fitted by linear least squares through the reduced
//                     normal equations, with the highest denominator coefficient fixed to the identity
//   label_stability   the stabilization diagram: each pole compared with the nearest pole of the order below
//                     in frequency, damping and shape
//   select_physical_poles / select_poles_near
//                     the physical poles: clusters of poles stable over many orders, or the poles nearest
//                     given frequencies
//   lsfd              residues of every channel at those poles by least-squares frequency-domain fitting,
//                     with lower and upper residual terms
//   identify_modes    all of the above, and the mode table (MPC, MPD, auto-MAC)
//
// Pinocchio-style: algorithm(data, ..., options) -> result; no hidden state.
#pragma once

#include <Eigen/Core>

#include <complex>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "mbgen/data/frf_data.hpp"
#include "mbgen/data/uff.hpp"

namespace mbgen {

// What the measured FRFs are: output displacement, velocity or acceleration per unit force. The pole
// estimation does not depend on it; the residual terms of LSFD do (they model modes below and above the band
// as mass and stiffness lines of the receptance, multiplied by (i w)^power).
enum class FrfQuantity { Unknown, Receptance, Mobility, Accelerance };
const char* frf_quantity_name(FrfQuantity q);  // "unknown", "receptance", "mobility", "accelerance"
// 0, 1, 2 for receptance, mobility, accelerance; 0 for unknown (the data are then fitted as they are).
int frf_quantity_power(FrfQuantity q);

// Measured FRFs prepared for identification: every channel on one frequency axis.
struct ModalData {
  std::vector<std::string> files;    // where the channels came from, for messages and reports
  Eigen::VectorXd f_hz;              // the band's lines, all > 0, strictly increasing
  std::vector<std::string> outputs;  // distinct names, in order of first appearance
  std::vector<std::string> inputs;
  struct Channel {
    int output = 0, input = 0;  // indices into outputs / inputs
    std::string name;           // "OUTPUT/INPUT"
  };
  std::vector<Channel> channels;
  Eigen::MatrixXcd H;  // lines x channels
  FrfQuantity quantity = FrfQuantity::Unknown;
};

// The quantity a UFF file's FRF records (function type 4) declare by their ordinate's specific data type
// (record 9: 8 displacement, 11 velocity, 12 acceleration), when they all agree; else Unknown.
FrfQuantity uff_frf_quantity(const std::vector<Uff58Record>& records);
// The same for FRFs already read (FrfData::uff_ordinate_type): Unknown for CSV data.
FrfQuantity uff_frf_quantity(const FrfData& frf);

struct FrequencyBand {
  double lo_hz = 0;
  double hi_hz = std::numeric_limits<double>::infinity();
};

// Collects the channels of `files` (in file and column order) on the lines with lo <= f <= hi and f > 0 (the
// lower residual term is singular at 0 Hz). Throws DataError naming the file for: no files or channels, a
// channel that appears twice, files whose frequencies differ within the band, non-finite values, a channel zero
// or below kMinSignalMagnitude (mbgen/data/data_set.hpp) throughout the band, and a band holding fewer than
// kMinModalLines lines.
constexpr int kMinModalLines = 8;
ModalData modal_data(const std::vector<FrfData>& files, const FrequencyBand& band,
                     FrfQuantity quantity = FrfQuantity::Unknown);

// ---- poles --------------------------------------------------------------------------------------------------

struct LscfOptions {
  int max_order = 0;           // highest polynomial order; 0 chooses one from the data (lscf_default_max_order)
  bool poly_reference = true;  // false: common-denominator LSCF (one reference) whatever the data's layout
  std::function<void(int order, int max_order)> progress;  // called after each order
};

// One pole of the diagram (the member of a conjugate pair with positive frequency).
struct DiagramPole {
  int order = 0;
  std::complex<double> lambda;  // continuous-time pole [rad/s]
  double f_hz = 0;              // |lambda| / (2 pi)
  double zeta = 0;              // -Re(lambda) / |lambda|; negative for an unstable pole
  Eigen::VectorXcd shape;       // operational shape over the fit's rows (B(z) v), for the shape criterion
  enum class Stability { New, Frequency, FrequencyDamping, FrequencyShape, Stable };
  Stability stability = Stability::New;  // against the order below (label_stability)
};

struct StabilizationDiagram {
  int references = 1;              // columns of the matrix-fraction model (1: common-denominator LSCF)
  bool transposed = false;         // rows are the data's inputs, references its outputs (fewer outputs than inputs)
  double dt = 0;                   // sampling interval of the z-domain basis: 1 / (2 highest line)
  double lo_hz = 0, hi_hz = 0;     // the band: poles outside it are not kept
  std::vector<int> orders;         // 1..max_order
  std::vector<DiagramPole> poles;  // by order, then by frequency
};

// Default highest order: enough for about 32 / references pole pairs in the band, at most a quarter of the
// band's lines (the normal equations must stay well over-determined).
int lscf_default_max_order(const ModalData& data, int references);

// The poles of every order 1..max_order in the band (0 < f <= hi); stability labels not set yet.
// Throws std::invalid_argument for a max_order the band's lines cannot support.
StabilizationDiagram lscf(const ModalData& data, const LscfOptions& options = {});

// ---- stabilization and selection -----------------------------------------------------------------------------

struct StabilizationCriteria {
  double frequency = 0.01;  // relative change of f between orders
  double damping = 0.05;    // relative change of zeta
  double shape = 0.02;      // 1 - MAC of the shapes
  double max_zeta = 0.2;    // poles with zeta outside (0, max_zeta] are never physical
};

// Labels each pole against the nearest (in frequency) pole of the order below.
void label_stability(StabilizationDiagram& diagram, const StabilizationCriteria& criteria = {});

struct SelectionOptions {
  StabilizationCriteria criteria;
  // A cluster counts as physical when it holds poles of at least this fraction of the orders (and at least 3).
  double min_orders_fraction = 0.3;
};

// A physical pole: the median of a cluster of stable poles of different orders.
struct SelectedPole {
  std::complex<double> lambda;
  double f_hz = 0, zeta = 0;
  int support = 0;  // how many orders hold a pole of the cluster
  bool user_selected = false;
  std::vector<int> members;  // indices into diagram.poles
};

// Automatic selection (labels must be set): greedy clustering of the poles with 0 < zeta <= max_zeta that are
// stable in frequency and in damping or shape (in damping when the shapes have one entry). Two poles of
// different orders are neighbours within frequency + shape of the distance |dlambda|/|lambda| + (1 - MAC). The
// pole with the most neighbours (the nearest at each order) seeds a cluster of them, which leaves the pool; a
// cluster is physical when it spans min_orders_fraction of the orders and holds a fully stable pole.
// Repeated while a cluster is large enough. Sorted by frequency.
std::vector<SelectedPole> select_physical_poles(const StabilizationDiagram& diagram,
                                                const SelectionOptions& options = {});

// User selection: for each frequency, the best-supported cluster of poles within 2 % of it (fully stable
// poles first, then poles stable in frequency, then any pole of the highest order). Throws
// std::invalid_argument naming the frequency when no pole lies within 2 %, or two frequencies pick one pole.
std::vector<SelectedPole> select_poles_near(const StabilizationDiagram& diagram, const std::vector<double>& f_hz,
                                            const SelectionOptions& options = {});

// ---- residues ------------------------------------------------------------------------------------------------

struct LsfdOptions {
  bool lower_residual = true;  // modes below the band: LR / (i w)^2 in the receptance
  bool upper_residual = true;  // modes above the band: UR in the receptance
};

// H_c(w) = (i w)^p [ sum_r ( R_rc / (i w - lambda_r) + conj(R_rc) / (i w - conj(lambda_r)) ) + LR_c / (i w)^2 + UR_c ]
// with p = frf_quantity_power(data.quantity), fitted by linear least squares per channel.
struct LsfdResult {
  Eigen::MatrixXcd residues;      // modes x channels: the residues of the measured FRF, lambda_r^p R_rc
  Eigen::VectorXd lower, upper;   // per channel (0 when the term is off)
  Eigen::MatrixXcd synthesized;   // lines x channels, the fitted model at the data's lines
  Eigen::VectorXd channel_error;  // per channel: ||H - synthesized|| / ||H||
};

LsfdResult lsfd(const ModalData& data, const std::vector<std::complex<double>>& poles, const LsfdOptions& options = {});

// ---- pole refinement ------------------------------------------------------------------------------------------

// LSCF's poles are biased in noise (its linearized cost weights the data by the denominator); the refinement
// moves them to minimize the LSFD misfit itself, residues and residual terms eliminated (variable projection,
// Kaufman's Jacobian, Levenberg-Marquardt), each channel weighted by 1 / its RMS: the maximum-likelihood poles
// when every channel's noise is white with a level proportional to its RMS. A pole that would move more than
// max_shift in frequency or leave 0 < zeta <= max_zeta is held at its given value and the others are refined
// again. Standard deviations of f and zeta of the refined poles follow from the Jacobian and the misfit.
struct RefineOptions {
  int max_iterations = 50;
  double max_shift = 0.02;
  double max_zeta = 0.2;
};

struct RefinedPoles {
  std::vector<std::complex<double>> poles;
  std::vector<bool> refined;               // per pole: false when held at its given value
  std::vector<double> f_std_hz, zeta_std;  // NaN for poles not refined
  int iterations = 0;                      // of the last minimization
  double initial_cost = 0, cost = 0;       // weighted sums of squares
  std::vector<std::string> notes;          // per pole: why it was held (empty when refined)
};

RefinedPoles refine_poles(const ModalData& data, const std::vector<std::complex<double>>& poles,
                          const LsfdOptions& lsfd_options = {}, const RefineOptions& options = {});

// ---- mode indicators -----------------------------------------------------------------------------------------

// Modal phase collinearity (Pappa): 1 for a real (monophase) shape, 0 for components in quadrature.
double modal_phase_collinearity(const Eigen::VectorXcd& shape);
// Mean phase deviation [deg] from the best straight line through the origin, weighted by magnitude.
double mean_phase_deviation_deg(const Eigen::VectorXcd& shape);

// ---- the whole analysis --------------------------------------------------------------------------------------

struct ModalOptions {
  LscfOptions lscf;
  SelectionOptions selection;
  LsfdOptions lsfd;
  bool refine = true;
  RefineOptions refinement;
  std::vector<double> select_hz;  // empty: automatic selection
};

struct IdentifiedMode {
  double f_hz = 0, zeta = 0;
  double f_std_hz = 0, zeta_std = 0;  // from the refinement's Jacobian (NaN when not refined)
  bool refined = false;
  double lscf_f_hz = 0, lscf_zeta = 0;  // the selected cluster's median, before refinement
  std::complex<double> lambda;
  Eigen::VectorXcd residues;  // per channel (LsfdResult::residues row)
  double mpc = 0, mpd_deg = 0;
  int support = 0;
  bool user_selected = false;
};

// An automatically selected pole that the refinement could not hold (docs/modal.md), with the reason.
struct RejectedPole {
  SelectedPole pole;
  std::string reason;
};

struct ModalIdentification {
  std::string method;  // "plscf-lsfd" (several references) or "lscf-lsfd"
  StabilizationDiagram diagram;
  std::vector<IdentifiedMode> modes;  // sorted by frequency
  RefinedPoles refinement;
  std::vector<RejectedPole> rejected;
  LsfdResult fit;
  Eigen::MatrixXd auto_mac;  // modes x modes, over the residue vectors
};

ModalIdentification identify_modes(const ModalData& data, const ModalOptions& options = {});

}  // namespace mbgen
