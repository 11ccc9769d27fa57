#include "app/sweep_job.h"

#include <fcntl.h>
#include <pthread.h>
#include <sched.h>
#include <sys/file.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <thread>

#include "app/exit_codes.h"
#include "app/sweep_report.h"
#include "common/error.h"
#include "common/progress.h"
#include "common/quoting.h"
#include "common/subprocess.h"
#include "common/wall_clock.h"
#include "outputs/files.h"
#include "outputs/interrupt.h"

namespace aerobox {
namespace fs = std::filesystem;
using Json = nlohmann::json;
namespace {

using Clock = std::chrono::steady_clock;

std::string Host() {
  char name[256] = {};
  if (gethostname(name, sizeof(name) - 1) != 0) return "unknown";
  return name;
}

std::string SelfBinary() {
  std::error_code ec;
  const fs::path self = fs::read_symlink("/proc/self/exe", ec);
  if (ec) throw std::runtime_error("cannot find the aerobox binary (/proc/self/exe)");
  return self.string();
}

int CoreCount() {
  cpu_set_t set;
  if (sched_getaffinity(0, sizeof(set), &set) == 0) return std::max(1, CPU_COUNT(&set));
  return std::max(1U, std::thread::hardware_concurrency());
}

std::optional<long> EnvNumber(const char* name) {
  const char* text = std::getenv(name);
  if (text == nullptr || *text == '\0') return std::nullopt;
  char* end = nullptr;
  const long value = std::strtol(text, &end, 10);
  if (*end != '\0') {
    throw InputError({"environment", 0}, name,
                     std::string("expected an integer, got '") + text + "'");
  }
  return value;
}

// The shard a Slurm array task runs: its place among the array's tasks.
std::optional<Shard> SlurmShard() {
  const std::optional<long> id = EnvNumber("SLURM_ARRAY_TASK_ID");
  if (!id) return std::nullopt;
  const long min = EnvNumber("SLURM_ARRAY_TASK_MIN").value_or(0);
  const long step = std::max(1L, EnvNumber("SLURM_ARRAY_TASK_STEP").value_or(1));
  const std::optional<long> count = EnvNumber("SLURM_ARRAY_TASK_COUNT");
  if (!count || *count < 1) {
    throw InputError({"environment", 0}, "SLURM_ARRAY_TASK_COUNT",
                     "missing beside SLURM_ARRAY_TASK_ID");
  }
  Shard shard;
  shard.index = static_cast<int>((*id - min) / step);
  shard.count = static_cast<int>(*count);
  if (shard.index < 0 || shard.index >= shard.count) {
    throw InputError({"environment", 0}, "SLURM_ARRAY_TASK_ID",
                     std::to_string(*id) + " is not among the array's " + std::to_string(*count) +
                         " tasks from " + std::to_string(min));
  }
  return shard;
}

std::string ResultsName(const Shard& shard) {
  if (shard.Whole()) return "results.jsonl";
  return "results.shard-" + std::to_string(shard.index) + "-of-" + std::to_string(shard.count) +
         ".jsonl";
}

Json ParamsOf(const SweepRun& run) {
  Json params = Json::object();
  for (const Setting& s : run.settings) {
    // grid values are written so that JSON reads them as TOML does
    params[s.key] = Json::parse(s.value, nullptr, false);
    if (params[s.key].is_discarded()) params[s.key] = s.value;
  }
  return params;
}

Json Manifest(const Sweep& sweep) {
  Json runs = Json::array();
  for (const SweepRun& run : sweep.runs) {
    runs.push_back({{"index", run.index},
                    {"id", run.id},
                    {"scenario", run.label},
                    {"seed", run.seed},
                    {"params", ParamsOf(run)}});
  }
  Json grid = Json::array();
  for (const auto& [key, values] : sweep.grid) grid.push_back(key);
  return {{"name", sweep.name}, {"grid", grid}, {"runs", runs}};
}

// The lines of a results file that are whole (a run cut short leaves at most a partial last
// line, which is dropped), by run id.
std::map<std::string, Json> ReadResults(const fs::path& file, bool* partial_tail = nullptr) {
  std::map<std::string, Json> results;
  std::ifstream in(file);
  std::string line;
  while (std::getline(in, line)) {
    if (in.eof()) {  // no newline after it: cut short
      if (partial_tail) *partial_tail = true;
      break;
    }
    const Json result = Json::parse(line, nullptr, false);
    if (result.is_discarded() || !result.contains("id")) {
      throw InputError({file.string(), 0}, "results", "a line is not a run's result: " + line);
    }
    results.emplace(result["id"].get<std::string>(), result);
  }
  return results;
}

// Appends whole lines to a results file (under its lock).
class ResultsFile {
 public:
  explicit ResultsFile(const fs::path& path) : path_(path) {
    fd_ = open(path.c_str(), O_WRONLY | O_APPEND | O_CREAT | O_CLOEXEC, 0644);
    if (fd_ < 0) throw InputError({path.string(), 0}, "--out", "cannot write the results");
  }
  ~ResultsFile() { close(fd_); }
  ResultsFile(const ResultsFile&) = delete;
  ResultsFile& operator=(const ResultsFile&) = delete;

  void Append(const Json& result) {
    const std::string line = result.dump() + "\n";
    // one write: a reader never sees half a line, and an interruption leaves whole lines
    if (write(fd_, line.data(), line.size()) != static_cast<ssize_t>(line.size())) {
      throw InputError({path_.string(), 0}, "results", "writing a result failed (disk full?)");
    }
  }

 private:
  fs::path path_;
  int fd_ = -1;
};

struct Child {
  pid_t pid = 0;
  const SweepRun* run = nullptr;
  Clock::time_point started;
};

std::vector<std::string> FlyCommand(const SweepRun& run, const Sweep& sweep,
                                    const fs::path& folder) {
  std::vector<std::string> words = {SelfBinary(),
                                    "fly",
                                    run.scenario,
                                    "--seed",
                                    std::to_string(run.seed),
                                    "--out",
                                    (folder / "runs" / run.id).string(),
                                    "--quiet"};
  if (!run.video) words.push_back("--no-video");
  if (!sweep.keep.overview) words.push_back("--no-overview");
  if (!sweep.keep.telemetry) words.push_back("--no-telemetry");
  if (!sweep.keep.report) words.push_back("--no-report");
  for (const Setting& s : run.settings) {
    words.push_back("--set");
    words.push_back(s.key + "=" + s.value);
  }
  return words;
}

pid_t Spawn(const std::vector<std::string>& command, const fs::path& log) {
  ProcessSpec spec;
  spec.argv = command;
  spec.output = log.string();
  spec.error_to_output = true;
  spec.null_input = true;
  return StartProcess(spec);
}

std::string LastLine(const fs::path& file) {
  std::ifstream in(file);
  std::string line, last;
  while (std::getline(in, line)) {
    if (!line.empty()) last = line;
  }
  return last;
}

const char* StatusOfExit(int code) {
  switch (code) {
    case kExitReachedGoal:
      return "reached goal";
    case kExitNoPath:
      return "no path";
    case kExitNoTrajectory:
      return "no feasible trajectory";
    case kExitFlightFailed:
      return "flight failed";
    case kExitBadInput:
      return "bad input";
    default:
      return "error";
  }
}

Json ResultOf(const SweepRun& run, int code, double wall, const fs::path& folder) {
  Json result = {{"index", run.index},          {"id", run.id},
                 {"scenario", run.label},       {"seed", run.seed},
                 {"params", ParamsOf(run)},     {"exit_code", code},
                 {"status", StatusOfExit(code)}};
  const fs::path summary = folder / "runs" / run.id / "summary.json";
  if (code == kExitReachedGoal || code == kExitNoPath || code == kExitNoTrajectory ||
      code == kExitFlightFailed) {
    std::ifstream in(summary);
    const Json parsed = Json::parse(in, nullptr, false);
    if (!parsed.is_discarded()) result["summary"] = parsed;
  }
  if (!result.contains("summary")) {
    result["error"] = LastLine(folder / "runs" / (run.id + ".log"));
  }
  result["wall_time_s"] = wall;
  result["host"] = Host();
  return result;
}

// A bar on a terminal (kept when the sweep ends), else a line at every tenth of the runs.
class SweepProgress {
 public:
  SweepProgress(std::ostream& err, std::string name, size_t total, bool enabled)
      : display_(err, ProgressDisplay::StderrIsTerminal(), 0.0),
        name_(std::move(name)),
        total_(total),
        enabled_(enabled && total > 0),
        tty_(ProgressDisplay::StderrIsTerminal()) {}
  ~SweepProgress() { display_.Keep(); }

  void Done(bool failed) {
    ++done_;
    failed_ += failed;
    if (!enabled_) return;
    const int tenth = static_cast<int>(10 * done_ / total_);
    if (!tty_ && tenth == last_tenth_ && done_ != total_) return;
    last_tenth_ = tenth;
    const double wall = Seconds(begin_);
    const double left = wall / static_cast<double>(done_) * static_cast<double>(total_ - done_);
    constexpr int kWidth = 24;
    const int filled = static_cast<int>(kWidth * done_ / total_);
    std::ostringstream line;
    line << std::fixed << std::setprecision(0) << "sweep " << name_ << ": ["
         << std::string(filled, '#') << std::string(kWidth - filled, '.') << "] " << done_ << "/"
         << total_ << " runs, " << failed_ << " failed, " << wall << " s, about " << left
         << " s left";
    display_.Show(line.str());
  }

 private:
  ProgressDisplay display_;
  std::string name_;
  size_t total_;
  bool enabled_;
  bool tty_;
  size_t done_ = 0;
  size_t failed_ = 0;
  int last_tenth_ = 0;
  Clock::time_point begin_ = Clock::now();
};

fs::path PrepareFolder(const std::string& requested, const std::string& fallback) {
  const fs::path folder = requested.empty() ? fs::path(fallback) : fs::path(requested);
  std::error_code ec;
  fs::create_directories(folder / "runs", ec);
  if (ec) {
    throw InputError({folder.string(), 0}, "--out", "cannot create the folder: " + ec.message());
  }
  return folder;
}

// The runs of the manifests of `folders` must be the same sweep's.
Json CommonManifest(const std::vector<fs::path>& folders) {
  Json manifest;
  for (const fs::path& folder : folders) {
    std::ifstream in(folder / "sweep.json");
    if (!in) {
      throw InputError({(folder / "sweep.json").string(), 0}, "merge",
                       "not a sweep's folder (no sweep.json)");
    }
    const Json here = Json::parse(in, nullptr, false);
    if (here.is_discarded() || !here.contains("runs")) {
      throw InputError({(folder / "sweep.json").string(), 0}, "merge", "not a sweep manifest");
    }
    if (manifest.is_null()) {
      manifest = here;
    } else if (here["runs"] != manifest["runs"]) {
      throw InputError({(folder / "sweep.json").string(), 0}, "merge",
                       "holds another sweep than " + (folders.front() / "sweep.json").string());
    }
  }
  return manifest;
}

}  // namespace

int RunSweep(const Sweep& sweep, const SweepOptions& options, std::ostream& out,
             std::ostream& err) {
  // every option checked before a run starts
  const std::optional<Shard> from_slurm = options.shard ? std::nullopt : SlurmShard();
  const Shard shard = options.shard.value_or(from_slurm.value_or(Shard()));
  int jobs = options.jobs;
  if (jobs == 0) {
    jobs = static_cast<int>(EnvNumber("SLURM_CPUS_PER_TASK").value_or(CoreCount()));
  }
  if (jobs < 1 || jobs > 1024) {
    throw InputError({"command line", 0}, "-j", "expected 1 to 1024 processes");
  }
  const fs::path folder = PrepareFolder(options.out_dir, "renders/" + sweep.name);
  const fs::path results_path = folder / ResultsName(shard);
  // "<results>.lock", held while a sweep reads, repairs and appends its results file, so that
  // two processes never run the same shard into one folder
  const FileLock lock(results_path.string() + ".lock", results_path.string(), "--out",
                      "another aerobox sweep", "is running into these results now");
  const Json manifest = Manifest(sweep);
  bool partial_tail = false;
  std::map<std::string, Json> done;
  if (fs::exists(results_path) && fs::file_size(results_path) > 0) {
    if (!options.resume) {
      throw InputError({results_path.string(), 0}, "--out",
                       "holds results already: --resume runs only the runs without one, or "
                       "give another --out");
    }
    std::ifstream in(folder / "sweep.json");
    const Json before = Json::parse(in, nullptr, false);
    if (!before.is_discarded() && before["runs"] != manifest["runs"]) {
      throw InputError({(folder / "sweep.json").string(), 0}, "--resume",
                       "the folder holds another sweep's results (the sweep file changed?)");
    }
    done = ReadResults(results_path, &partial_tail);
  }
  if (partial_tail) {  // a run cut short mid-line: keep the whole lines only
    std::string whole;
    for (const SweepRun& run : sweep.runs) {
      if (const auto it = done.find(run.id); it != done.end()) whole += it->second.dump() + "\n";
    }
    WriteFileAtomically(results_path.string(), whole);
  }
  WriteFileAtomically((folder / "sweep.json").string(), manifest.dump(1) + "\n");

  std::vector<const SweepRun*> todo;
  size_t in_shard = 0;
  for (const SweepRun& run : sweep.runs) {
    if (!shard.Contains(run)) continue;
    ++in_shard;
    if (done.count(run.id) == 0) todo.push_back(&run);
  }
  out << "sweep " << sweep.name << ": " << sweep.runs.size() << " runs";
  if (!shard.Whole()) {
    out << ", shard " << shard.index << "/" << shard.count << " runs " << in_shard;
  }
  if (in_shard != todo.size()) out << ", " << in_shard - todo.size() << " done before";
  out << "; " << todo.size() << " to run, " << jobs << " at a time -> " << results_path.string()
      << "\n"
      << std::flush;

  ResultsFile results(results_path);
  SweepProgress progress(err, sweep.name, todo.size(), options.progress);
  // SIGCHLD blocked, so that the loop below sleeps until a run ends (and the mask is restored
  // on every way out)
  sigset_t child_signal;
  sigemptyset(&child_signal);
  sigaddset(&child_signal, SIGCHLD);
  sigset_t previous_mask;
  pthread_sigmask(SIG_BLOCK, &child_signal, &previous_mask);
  struct RestoreMask {
    sigset_t mask;
    ~RestoreMask() { pthread_sigmask(SIG_SETMASK, &mask, nullptr); }
  } restore{previous_mask};
  std::vector<Child> running;
  size_t next = 0;
  int failed = 0;
  bool interrupted = false;
  const Clock::time_point begin = Clock::now();
  while ((!interrupted && next < todo.size()) || !running.empty()) {
    if (StopRequested() && !interrupted) {
      interrupted = true;
      for (const Child& child : running) kill(child.pid, SIGINT);
    }
    while (!interrupted && next < todo.size() && static_cast<int>(running.size()) < jobs) {
      const SweepRun& run = *todo[next++];
      const fs::path log = folder / "runs" / (run.id + ".log");
      running.push_back({Spawn(FlyCommand(run, sweep, folder), log), &run, Clock::now()});
    }
    int status = 0;
    const pid_t pid = waitpid(-1, &status, WNOHANG);
    if (pid <= 0) {
      // until a run ends (SIGCHLD), or 50 ms to look at Ctrl-C again
      const timespec timeout{0, 50'000'000};
      sigtimedwait(&child_signal, nullptr, &timeout);
      continue;
    }
    const auto child = std::find_if(running.begin(), running.end(),
                                    [pid](const Child& c) { return c.pid == pid; });
    if (child == running.end()) continue;
    const int code = WIFEXITED(status) ? WEXITSTATUS(status) : kExitUnexpected;
    const bool stopped =
        code == kExitInterrupted || (WIFSIGNALED(status) && WTERMSIG(status) == SIGINT);
    if (!(interrupted && stopped)) {
      const Json result = ResultOf(*child->run, code, Seconds(child->started), folder);
      results.Append(result);
      const bool ok = code == kExitReachedGoal;
      failed += !ok;
      progress.Done(!ok);
    }
    running.erase(child);
  }
  if (interrupted) {
    err << "aerobox: sweep interrupted: the runs that finished are in " << results_path.string()
        << "; --resume runs the rest\n";
    return kExitInterrupted;
  }
  out << "sweep " << sweep.name << ": " << todo.size() << " runs in " << std::fixed
      << std::setprecision(1) << Seconds(begin) << " s, " << failed
      << " did not reach their goal\n";
  if (shard.Whole()) {
    // the results in the sweep's order, whatever order the runs finished in
    const std::map<std::string, Json> all = ReadResults(results_path);
    std::string lines;
    for (const SweepRun& run : sweep.runs) {
      if (const auto it = all.find(run.id); it != all.end()) lines += it->second.dump() + "\n";
    }
    WriteFileAtomically(results_path.string(), lines);
    const std::vector<std::string> written = WriteSweepReport(manifest, all, folder.string());
    out << "report: " << written.front() << "\n";
  } else {
    out << "shard " << shard.index << "/" << shard.count
        << " done; join the shards with: aerobox sweep merge " << folder.string() << "\n";
  }
  return kExitReachedGoal;
}

int ListSweep(const Sweep& sweep, const SweepOptions& options, std::ostream& out) {
  const std::optional<Shard> from_slurm = options.shard ? std::nullopt : SlurmShard();
  const Shard shard = options.shard.value_or(from_slurm.value_or(Shard()));
  size_t listed = 0;
  out << "index  id                scenario  seed  grid\n";
  for (const SweepRun& run : sweep.runs) {
    if (!shard.Contains(run)) continue;
    ++listed;
    out << std::setw(5) << run.index << "  " << run.id << "  " << run.label << "  " << run.seed
        << " ";
    for (const Setting& s : run.settings) out << " " << s.key << "=" << s.value;
    out << (run.video ? "  (video)" : "") << "\n";
  }
  out << "sweep " << sweep.name << ": " << sweep.runs.size() << " runs (" << sweep.scenarios.size()
      << " scenario(s) x "
      << sweep.runs.size() / std::max<size_t>(1, sweep.scenarios.size()) /
             std::max<size_t>(1, sweep.seeds.size())
      << " grid cell(s) x " << sweep.seeds.size() << " seed(s))";
  if (!shard.Whole()) out << "; shard " << shard.index << "/" << shard.count << ": " << listed;
  out << "\n";
  return kExitReachedGoal;
}

int RunSweepMerge(const std::vector<std::string>& folders, const std::string& out_dir,
                  std::ostream& out, std::ostream& err) {
  if (folders.empty()) throw InputError({"command line", 0}, "merge", "expected a folder");
  std::vector<fs::path> paths(folders.begin(), folders.end());
  const Json manifest = CommonManifest(paths);
  const fs::path target = out_dir.empty() ? paths.front() : fs::path(out_dir);
  std::map<std::string, Json> all;
  int files = 0;
  for (const fs::path& folder : paths) {
    for (const fs::directory_entry& entry : fs::directory_iterator(folder)) {
      const std::string name = entry.path().filename().string();
      if (name.rfind("results", 0) != 0 || entry.path().extension() != ".jsonl") continue;
      ++files;
      for (auto& [id, result] : ReadResults(entry.path())) all.emplace(id, std::move(result));
    }
  }
  std::error_code ec;
  fs::create_directories(target, ec);
  if (ec) throw InputError({target.string(), 0}, "--out", "cannot create: " + ec.message());
  std::string lines;
  size_t missing = 0;
  std::set<std::string> known;
  for (const Json& run : manifest["runs"]) {
    const std::string id = run["id"].get<std::string>();
    known.insert(id);
    const auto it = all.find(id);
    if (it == all.end()) {
      ++missing;
      continue;
    }
    lines += it->second.dump() + "\n";
  }
  if (target != paths.front() || paths.size() > 1) {
    WriteFileAtomically((target / "sweep.json").string(), manifest.dump(1) + "\n");
  }
  WriteFileAtomically((target / "results.jsonl").string(), lines);
  const std::vector<std::string> written = WriteSweepReport(manifest, all, target.string());
  const size_t total = manifest["runs"].size();
  out << "merge: " << total - missing << " of " << total << " runs from " << files
      << " result file(s) -> " << (target / "results.jsonl").string()
      << "\nreport: " << written.front() << "\n";
  if (missing > 0) {
    err << "aerobox: warning: " << missing << " of " << total
        << " runs have no result (a shard did not run or was cut short: run it again with "
           "--resume)\n";
    return kExitUnexpected;
  }
  return kExitReachedGoal;
}

int RunSweepSlurm(const Sweep& sweep, const SlurmOptions& options, std::ostream& out,
                  std::ostream& err) {
  if (options.array < 1 || options.array > 100000) {
    throw InputError({"command line", 0}, "--array", "expected 1 to 100000 tasks");
  }
  if (options.cpus < 1 || options.cpus > 1024) {
    throw InputError({"command line", 0}, "--cpus", "expected 1 to 1024 per task");
  }
  const auto plain = [](const std::string& text, const char* option) {
    if (text.find_first_of(" \t\n'\"\\$`;&|<>") != std::string::npos) {
      throw InputError({"command line", 0}, option, "expected a single word, got '" + text + "'");
    }
  };
  plain(options.partition, "--partition");
  plain(options.time, "--time");
  const fs::path sweep_file = fs::absolute(sweep.file).lexically_normal();
  const fs::path folder = options.out_dir.empty()
                              ? sweep_file.parent_path() / (sweep.name + ".slurm")
                              : fs::absolute(options.out_dir).lexically_normal();
  std::error_code ec;
  fs::create_directories(folder / "logs", ec);
  if (ec) throw InputError({folder.string(), 0}, "--out", "cannot create: " + ec.message());
  const auto quoted = ShellQuoted;
  const std::string binary = quoted(SelfBinary());
  const fs::path script = folder / "sweep.sbatch";
  std::ostringstream text;
  text << "#!/bin/bash\n"
       << "# aerobox sweep " << sweep.name << " (" << sweep.runs.size() << " runs) as a Slurm job "
       << "array of " << options.array << " tasks.\n"
       << "#   sbatch " << script.string() << "    the array alone\n"
       << "#   bash " << script.string()
       << "      the array and a merge job after it (--wait: until the merge has run; other "
          "arguments go to the merge's sbatch)\n"
       << "#SBATCH --job-name=aerobox-" << sweep.name << "\n"
       << "#SBATCH --array=0-" << options.array - 1 << "\n"
       << "#SBATCH --ntasks=1\n"
       << "#SBATCH --cpus-per-task=" << options.cpus << "\n"
       << "#SBATCH --output=" << (folder / "logs" / "task-%A_%a.log").string() << "\n";
  if (!options.partition.empty()) text << "#SBATCH --partition=" << options.partition << "\n";
  if (!options.time.empty()) text << "#SBATCH --time=" << options.time << "\n";
  text << "set -euo pipefail\n"
       << "cd " << quoted(fs::current_path().string()) << "\n"
       << "if [ -z \"${SLURM_JOB_ID:-}\" ]; then\n"
       << "  wait_for_merge=0\n"
       << "  if [ \"${1:-}\" = --wait ]; then wait_for_merge=1; shift; fi\n"
       << "  array=$(sbatch --parsable " << quoted(script.string()) << ")\n"
       << "  array=${array%%;*}\n"
       << "  echo \"aerobox: submitted the array, job $array\"\n"
       << "  merge=$(sbatch --parsable --dependency=afterany:\"$array\" --job-name=aerobox-"
       << sweep.name << "-merge --ntasks=1 --cpus-per-task=1";
  if (!options.partition.empty()) text << " --partition=" << options.partition;
  text << " --output=" << quoted((folder / "logs" / "merge-%j.log").string())
       << " \"$@\" --wrap=" << quoted(binary + " sweep merge " + quoted(folder.string())) << ")\n"
       << "  merge=${merge%%;*}\n"
       << "  echo \"aerobox: submitted the merge, job $merge, after job $array\"\n"
       << "  [ \"$wait_for_merge\" = 1 ] || exit 0\n"
       << "  # sbatch --wait polls ever more slowly: squeue twice a second instead\n"
       << "  while [ -n \"$(squeue -h -j \"$merge\" -o %i 2> /dev/null)\" ]; do sleep 0.5; done\n"
       << "  code=$(scontrol show job \"$merge\" 2> /dev/null | sed -n "
          "'s/.* ExitCode=\\([0-9]*\\):.*/\\1/p')\n"
       << "  echo \"aerobox: the merge job ended, exit code ${code:-unknown}\"\n"
       << "  exit \"${code:-1}\"\n"
       << "fi\n"
       << "# an array task: its shard comes from SLURM_ARRAY_TASK_ID, _MIN and _COUNT\n"
       << "exec " << binary << " sweep " << quoted(sweep_file.string()) << " --out "
       << quoted(folder.string()) << " -j \"${SLURM_CPUS_PER_TASK:-1}\" --resume\n";
  WriteFileAtomically(script.string(), text.str());
  fs::permissions(script, fs::perms::owner_exec | fs::perms::group_exec | fs::perms::others_exec,
                  fs::perm_options::add);
  out << script.string() << "\n";
  if (!options.submit) {
    out << "submit it with: bash " << script.string() << "   (the array, then the merge)\n";
    return kExitReachedGoal;
  }
  ProcessSpec spec;
  spec.argv = {"/bin/bash", script.string()};
  if (options.wait) spec.argv.push_back("--wait");
  const int code = RunProcess(spec);
  if (StopRequested()) {
    err << "aerobox: interrupted: the jobs already submitted keep running (scancel stops them)\n";
    return kExitInterrupted;
  }
  if (code != 0) {
    err << "aerobox: error: " << script.string()
        << (options.wait
                ? " failed: sbatch's message, or the merge's (logs/merge-*.log), says why\n"
                : " failed: sbatch's message is above\n");
    return kExitUnexpected;
  }
  return kExitReachedGoal;
}

}  // namespace aerobox
