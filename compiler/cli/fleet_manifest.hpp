// A fleet manifest (docs/fleets.md): many machines, each monitored on its own series of data sets, as independent
// items that an existing batch engine runs (GNU parallel, Slurm job arrays, Kubernetes indexed Jobs):
//
//   # comment lines and blank lines are skipped
//   machine,model,data
//   mill-01,models/spindle.mdl,data/mill-01/*.csv
//   mill-02,models/spindle.mdl,data/mill-02/day-*.csv;data/mill-02/extra.uff
//
// Paths are relative to the manifest's directory; `data` holds one or more glob patterns separated by `;`, each
// expanded in sorted order (and then ordered by the files' `# time=` lines, as `monitor` does). Each item's output is
// a directory OUT/MACHINE written whole or not at all, with a digest of everything the result depends on, so that a
// rerun skips the items whose inputs did not change (idempotent, resumable).
#pragma once

#include <string>
#include <vector>

namespace mbgen::cli {

struct FleetItem {
  std::string machine;                  // [A-Za-z0-9_.-]+, not starting with '.', unique in the manifest
  std::string model;                    // path as usable from the working directory
  std::vector<std::string> data;        // the expanded data files, sorted
  int line = 0;                         // the manifest line (for messages)
};

// Reads and checks a manifest; bad content throws FitError "FILE:LINE:COLUMN: error: ..." (exit status 1).
std::vector<FleetItem> read_fleet_manifest(const std::string& path);

// The item named by `selector`: a 0-based index (as Slurm's SLURM_ARRAY_TASK_ID or Kubernetes'
// JOB_COMPLETION_INDEX give it) or a machine name. Unknown: CLI::ValidationError (usage, exit 2).
const FleetItem& select_fleet_item(const std::vector<FleetItem>& items, const std::string& selector);

// 64-bit FNV-1a of a file's bytes, as 16 hex digits: detects changed inputs (not a cryptographic hash).
std::string file_digest(const std::string& path);

}  // namespace mbgen::cli
