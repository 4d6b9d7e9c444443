// Operational (output-only) modal analysis of response time records, no force measured (docs/modal.md,
// "Output-only modal analysis"):
//
//   response_data     the responses of one or more records on one time grid, the channels and references chosen
//   ssi_cov           covariance-driven stochastic subspace identification: output correlations R_k (by FFT), the
//                     block Toeplitz matrix of R_1..R_2i-1, its SVD, the observability matrix of each model order,
//                     A and C by its shift; poles and shapes at orders 2, 4, .. N, a stabilization diagram
//   fdd               frequency-domain decomposition: the singular values and vectors of the output spectral
//                     matrix per line, peaks of the first singular value, shapes from its singular vector, and
//                     the damping by EFDD from the correlation function of the single-mode bell
//   identify_output_only
//                     either, with the FRF path's stabilization and automatic pole selection for SSI-cov, and the
//                     mode table (MPC, MPD, auto-MAC)
//   response_setups, identify_setups
//                     records of several setups (roving sensors with shared references), identified one by one and
//                     merged
//
// Shapes are unscaled (no force, no modal mass): unit norm over the channels, the largest component real and
// positive. Pinocchio-style: algorithm(data, options) -> result; no hidden state.
#pragma once

#include <Eigen/Core>

#include <complex>
#include <functional>
#include <string>
#include <vector>

#include "mbgen/modal_identification/modal_identification.hpp"
#include "mbgen/data/time_record.hpp"

namespace mbgen {

// Response records prepared for output-only identification: the same channels on the same sampling interval.
struct ResponseData {
  std::vector<std::string> files;
  std::vector<std::string> channels;  // response names, in the first record's column order
  std::vector<int> references;        // indices into channels: the correlations' reference channels
  double dt = 0;
  std::vector<Eigen::MatrixXd> records;  // per record: samples x channels, each channel's mean removed
  std::vector<std::string> notes;        // what was left out and why, for the user
};

struct ResponseSelection {
  std::vector<std::string> ignore;      // signals that are not responses (a measured force): left out with a note
  std::vector<std::string> references;  // empty: every channel is a reference
};

// A record needs this many samples; each method also needs the record longer than the lags it uses (SSI-cov
// 2 x block rows; FDD 16 or more).
constexpr Eigen::Index kMinResponseSamples = 256;

// Collects the records' signals (all but `ignore`). Throws DataError naming the file for: no records, no response
// left, a record whose channels or sampling interval (relative 1e-6) differ from the first's, fewer than
// kMinResponseSamples samples, a non-finite sample, a channel that is constant; and for an unknown reference or
// ignored name.
ResponseData response_data(const std::vector<TimeRecord>& records, const ResponseSelection& selection = {});

// Output correlations R_k = E[y_(t+k) y_ref,t^T] (channels x references), k = 0..lags-1, from all records (each
// record's sums over its own samples, the unbiased estimate N - k), by FFT of the zero-padded channels.
std::vector<Eigen::MatrixXd> output_correlations(const ResponseData& data, Eigen::Index lags);

// ---- SSI-cov --------------------------------------------------------------------------------------------------

struct SsiCovOptions {
  int max_order = 0;   // highest model order (states; odd ones rounded up); 0: 48
  int block_rows = 0;  // i: the Toeplitz matrix holds R_1..R_(2i-1); 0: enough for max_order, at least 32
  std::function<void(int order, int max_order)> progress;
};

// The poles (one of each conjugate pair, 0 < f < Nyquist) and their shapes C psi at orders 2, 4, .. max_order;
// DiagramPole::order is the model order (states). Stability labels not set yet. Throws std::invalid_argument when
// the records are too short for the lags or the channels x block rows cannot hold the order.
struct SsiCovDiagram {
  StabilizationDiagram diagram;
  int block_rows = 0;
  Eigen::VectorXd singular_values;  // of the block Toeplitz matrix, for the choice of the order
  // Per diagram pole: its resonance peak |phi| |g| / |1 - |mu|| (R_k = sum phi mu^(k-1) g^T) relative to the
  // largest of its order: how much of the responses it explains.
  std::vector<double> contribution;
};
SsiCovDiagram ssi_cov(const ResponseData& data, const SsiCovOptions& options = {});

// ---- FDD / EFDD -----------------------------------------------------------------------------------------------

struct FddOptions {
  // The spectral matrix is the Fourier transform of the correlations times exp(-|tau| / window_s) (a
  // positive-definite lag window that adds the known decay 1 / window_s to every mode, removed from EFDD's
  // damping), over lags up to 8 window_s. 0: a twentieth of the shortest record.
  double window_s = 0;
  double prominence_db = 10;  // a peak of the first singular value stands this far above the lower valleys
  double bell_mac = 0.8;      // EFDD: the mode's bell is the lines around the peak whose vector has this MAC
  double bell_db = 20;        // with the peak's, and whose first singular value is within this of the peak's
  double lo_hz = 0, hi_hz = 0;  // peaks searched in lo..hi (0: from the third line to 0.95 Nyquist)
};

struct FddPeak {
  double f_hz = 0;        // the peak's line (FDD)
  double efdd_f_hz = 0;   // undamped frequency from the bell's correlation function (EFDD); NaN when it failed
  double zeta = 0;        // EFDD, window decay removed; NaN when it failed
  // From records: the residue of the mode's pole term in the half spectra; from FRFs: the first singular vector at
  // the peak.
  Eigen::VectorXcd shape;
  double sv_db = 0;       // first singular value at the peak [dB]
  int bell_lines = 0;     // lines in the bell
  std::string note;       // why EFDD failed, empty otherwise
};

struct FddResult {
  Eigen::VectorXd f_hz;        // lines
  Eigen::MatrixXd singular;    // lines x channels: singular values of the spectral matrix, descending
  std::vector<FddPeak> peaks;  // by frequency
  double window_s = 0;                  // 0: no lag window (FRFs)
  std::vector<std::string> frf_inputs;  // fdd_of_frfs: where the white forces act; empty for records
  bool frf_transposed = false;          // fdd_of_frfs: the FRFs read by reciprocity (fewer outputs than inputs)
};
FddResult fdd(const ResponseData& data, const FddOptions& options = {});

// FRFs read as the spectra of unmeasured unit white forces at their inputs: the output spectral matrix
// G(f) = H(f) H(f)^H (outputs x outputs, the sum over the inputs; with fewer outputs than inputs, a roving
// hammer, H^T by reciprocity: the responses at the inputs to forces at the outputs) on the FRFs' own lines, no
// lag window, then FDD's peaks and EFDD as for records (the bell's correlation function at the interval
// frf_equivalent_dt).
// Peaks are searched over the FRFs' band (options.lo_hz/hi_hz narrow it). The lines must lie on the multiples of
// their spacing (std::invalid_argument otherwise). A check of the estimator on measured data, not an analysis in
// operation: the force is known to be the FRFs' input.
FddResult fdd_of_frfs(const ModalData& frfs, const FddOptions& options = {});
double frf_equivalent_dt(const ModalData& frfs);  // 1 / (2 f_max): the correlation's interval

// ---- the whole analysis ---------------------------------------------------------------------------------------

enum class OutputOnlyMethod { SsiCov, Fdd };
const char* output_only_method_name(OutputOnlyMethod m);  // "ssi-cov", "fdd"

struct OutputOnlyOptions {
  OutputOnlyMethod method = OutputOnlyMethod::SsiCov;
  SsiCovOptions ssi;
  // A physical pole of SSI-cov is in the diagram from the order that makes room for it up to the highest, so its
  // cluster must span half the orders (LSCF's 30 % let clusters of the correlations' estimation error through).
  SelectionOptions selection = {StabilizationCriteria{}, 0.5};
  // SSI-cov: a selected cluster whose median contribution (SsiCovDiagram::contribution) is below this is dropped:
  // the correlations' own estimation error forms clusters stable over many orders but explaining almost nothing
  // (on mdof2 up to 1.1e-5 of the strongest mode's peak, true modes with a tenth of the truth's strongest response
  // 0.01 have 1e-4: docs/modal.md).
  double min_contribution = 3e-5;
  FddOptions fdd;
};

struct OperationalMode {
  double f_hz = 0, zeta = 0;  // SSI-cov: the cluster's median; FDD: EFDD's (the peak's line when it failed)
  std::complex<double> lambda;
  Eigen::VectorXcd shape;  // unit norm, largest component real and positive (unscaled)
  double mpc = 0, mpd_deg = 0;
  int support = 0;          // SSI-cov: orders in the cluster; FDD: lines in the bell
  double f_scatter_hz = 0;  // SSI-cov: standard deviation of f over the cluster (not an uncertainty); FDD: NaN
  double zeta_scatter = 0;
  double contribution = 0;  // SSI-cov: the median over the cluster of SsiCovDiagram::contribution; FDD: NaN
};

struct OutputOnlyIdentification {
  OutputOnlyMethod method = OutputOnlyMethod::SsiCov;
  SsiCovDiagram ssi;  // SSI-cov only
  FddResult fdd;      // FDD only
  std::vector<OperationalMode> modes;  // by frequency
  std::vector<RejectedPole> rejected;  // SSI-cov: selected clusters dropped, with the reason
  Eigen::MatrixXd auto_mac;
};

OutputOnlyIdentification identify_output_only(const ResponseData& data, const OutputOnlyOptions& options = {});

// FDD of FRFs (fdd_of_frfs), the mode table as for records; options.method must be Fdd (std::invalid_argument
// otherwise: SSI-cov needs records). frf_responses gives the responses for the JSON and report: files, channels
// the FRFs' outputs (their inputs when transposed, as fdd_of_frfs), every one a reference, dt
// frf_equivalent_dt, no records, a note saying what was assumed.
OutputOnlyIdentification identify_output_only_frfs(const ModalData& frfs, const OutputOnlyOptions& options);
ResponseData frf_responses(const ModalData& frfs);

// ---- several setups: roving sensors with shared references ---------------------------------------------------

// The records grouped by their responses (after `ignore`), one ResponseData per group (setup), in order of first
// appearance. The references are selection.references, or else the responses every setup has (with one setup:
// all, as response_data). Throws DataError naming a file when setups share no response or a reference is missing
// from one, and for what response_data refuses.
std::vector<ResponseData> response_setups(const std::vector<TimeRecord>& records,
                                          const ResponseSelection& selection = {});

struct MergedSetups {
  ResponseData data;  // all files, the union of the responses (by first appearance), references the shared ones;
                      // no records (the setups were not measured together)
  std::vector<ResponseData> setups;
  std::vector<OutputOnlyIdentification> per_setup;
  OutputOnlyIdentification result;  // the merged modes (no diagram or spectrum of its own)
};

// Each setup identified on its own; a mode of the first setup is kept when every other setup has a mode within
// criteria.frequency of it (the nearest). Its f and zeta are the means over the setups (f_scatter_hz and
// zeta_scatter their standard deviations over the setups), its shape the first setup's, extended by each other
// setup's shape scaled to it by least squares on the reference responses (complex factor). Modes missing from a
// setup are listed in result.rejected. Throws DataError naming a setup's first file where identify_output_only
// throws std::invalid_argument.
MergedSetups identify_setups(std::vector<ResponseData> setups, const OutputOnlyOptions& options = {});

// The shape scaled as the mode table gives it: unit norm, its largest component real and positive.
Eigen::VectorXcd normalize_shape(const Eigen::VectorXcd& shape);

}  // namespace mbgen
