// The diagnosis loop's fixed thresholds, each with its reason, in one place. The selection rules a user may tune
// (delta BIC, validation gain, the extended model's residual and remaining findings, the number of extensions) are
// DiagnoseOptions (diagnose.hpp); these are the rules' inner constants, measured on the test cases
// (tests/diagnosis) and explained in docs/diagnosis.md.
#pragma once

namespace mbgen::diagnosis::thresholds {

// An extension explains a discrepancy when the residual's excess over the noise (mean normalized residual minus 1)
// at least halves; less is a partial, likely wrong, explanation. The same fraction judges whether a single finding
// still shows in the extended model.
inline constexpr double kExplainedExcessFraction = 0.5;

// A partial explanation is taken for a further round only while the rounds left could bring the residual near the
// noise (DiagnoseOptions::max_final_residual) at this many times its own pace. Greedy selection takes the largest
// gain first, so a later round usually gains less; an effect that another one masked may gain a little more (a
// spindle's low-pass once its base was in: 125 against the base's 118).
inline constexpr double kPartialPaceMargin = 2.0;

// A fit pressed an estimate against a bound when the data pull it beyond by more than this in chi-square
// (ParameterEstimate::pull_chi2): a parameter the data barely see may drift to a bound with nothing pulling it.
inline constexpr double kBoundPullChi2 = 10.0;

// An estimate stands at a bound within this fraction of it (for a bound at zero: of its prior, since a bounded fit
// approaches zero by factors and never reaches it).
inline constexpr double kAtBoundRelative = 1e-3;

// A candidate's new parameter whose std exceeds this fraction of its value is not determined by the data: it is held
// at its start value and the candidate fitted again.
inline constexpr double kPoorlyDetermined = 0.5;

// Two candidates within this much in BIC fit equally well (a torsion spring at two points between the same bodies
// is one extension): the first in enumeration order is taken, so the choice does not hang on rounding.
inline constexpr double kBicTie = 0.01;

// The BIC winner of a round is taken only when its validation error (held-back data) is at most this factor of the
// lowest among the qualifying candidates: equally right models differ there by noise (a few per cent; 2 % in the
// test cases), while two partial explanations of an effect outside the library differed by a factor 2.2-2.3.
inline constexpr double kValidationDisagreement = 1.5;

// Peaks of the measured FRFs that suggest start frequencies for new modes: a data peak within this relative distance
// of a peak of the prior model is accounted for by it.
inline constexpr double kPriorPeakMatch = 0.08;
// A peak counts at this prominence (dB) as a start for an output's own candidates, and at the stronger one as
// evidence of a missing mode.
inline constexpr double kPeakProminenceDb = 3.0;
inline constexpr double kStrongPeakProminenceDb = 6.0;
// A peak's rise must also stand this many standard deviations out of the noise: in data near the noise level,
// noise alone makes wiggles of several dB.
inline constexpr double kPeakNoiseSigmas = 4.0;
// Two peaks within this relative distance are one peak, seen again (or on another output).
inline constexpr double kSamePeak = 0.02;

// The extended model must not move a mode the nominal model had right: a frequency shift it shows with no finding
// of the nominal model within this relative distance rejects the extension. (An mdof2 support with a Maxwell
// element, from a record, was "explained" by a compliant wall and a 6 us delay that moved the first mode by 4.5 %,
// a mode the nominal model fitted; in every correct extension of the test cases a remaining shift lies within 0.5 %
// of a nominal finding.)
inline constexpr double kNewShiftDistance = 0.05;

// A candidate that explains the data by a new body's resonance (a compliant ground, a resonator) must show one:
// some mode of the new body carries at least this share of a measured channel's response at the mode's frequency
// (new_body_modes.hpp). A term under a tenth of the response changes it there by under 1 dB: no peak of it shows.
// (Correct walls, bases and resonators of the test cases carry 0.53-0.99 of some channel's response; the heavy walls,
// 390-1700 kg damped at 9-68 % of critical, that "explained" an mdof2 support with a Maxwell element carried
// 0.001-0.02.)
inline constexpr double kShownModeShare = 0.1;

// Sensor candidates are offered for an output the model misses alone: its mean excess over the noise (mean
// normalized residual minus 1) above this, and at least kSensorAloneRatio times every other output's. A sensor
// changes one output; a discrepancy every output shows belongs to the structure.
inline constexpr double kSensorAloneExcess = 0.5;
inline constexpr double kSensorAloneRatio = 2.0;

}  // namespace mbgen::diagnosis::thresholds
