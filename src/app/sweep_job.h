// aerobox sweep: many flights from one sweep file, in local processes or as a Slurm job array,
// with one JSON line per run and a report per cell of the grid.
#pragma once

#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "scenario/sweep.h"

namespace aerobox {

struct SweepOptions {
  std::string out_dir;         // "": renders/<sweep name>/
  int jobs = 0;                // processes at once (0: SLURM_CPUS_PER_TASK, else the cores)
  bool resume = false;         // run only the runs without a result
  std::optional<Shard> shard;  // none: from SLURM_ARRAY_TASK_* when set, else the whole sweep
  bool progress = true;        // a progress bar on standard error
};

// Runs the sweep's share of runs, each as `aerobox fly` in its own process, and writes
// results.jsonl (results.shard-I-of-N.jsonl for a shard), sweep.json and, for a whole sweep,
// the report. Throws InputError for bad options before any run.
int RunSweep(const Sweep& sweep, const SweepOptions& options, std::ostream& out, std::ostream& err);

// Prints the runs the options select (the shard's, or all), one line each, and runs nothing.
int ListSweep(const Sweep& sweep, const SweepOptions& options, std::ostream& out);

// Joins the results of the folders (shards of one sweep) into `out_dir` (default: the first)
// and writes the report; exit 1 when some run has no result.
int RunSweepMerge(const std::vector<std::string>& folders, const std::string& out_dir,
                  std::ostream& out, std::ostream& err);

struct SlurmOptions {
  int array = 0;          // tasks in the job array
  std::string out_dir;    // "": <sweep file's folder>/<sweep name>.slurm/
  std::string partition;  // "": the cluster's default
  std::string time;       // "": the partition's limit; else Slurm's form, e.g. 00:30:00
  int cpus = 1;           // per task: the processes each task runs at once
  bool submit = false;
  bool wait = false;  // with submit: until the merge job has finished
};

// Writes <out>/sweep.sbatch: submitted with sbatch it is the job array; run with bash it
// submits the array and a merge job that depends on it.
int RunSweepSlurm(const Sweep& sweep, const SlurmOptions& options, std::ostream& out,
                  std::ostream& err);

}  // namespace aerobox
