// The only place aerobox writes files (input files are read by scenario/read_file.h).
#pragma once

#include <cstdio>
#include <filesystem>
#include <string>

namespace aerobox {

// Writes `text` to a temporary file beside `path`, then renames it over `path`, so that `path`
// is either complete or untouched. Throws InputError naming the file on any failure (and
// removes the temporary file).
void WriteFileAtomically(const std::string& path, const std::string& text);

// A file written as a run goes: appended under "<path>.partial", renamed to `path` by Commit().
// Destroyed without Commit() (a failure, an interruption), it removes the partial file, so
// `path` is complete or absent. Throws InputError naming the file when writing fails.
class StreamingFile {
 public:
  explicit StreamingFile(std::string path);
  ~StreamingFile();
  StreamingFile(const StreamingFile&) = delete;
  StreamingFile& operator=(const StreamingFile&) = delete;

  void Append(const std::string& text);
  void Commit();

 private:
  std::string path_;
  std::string partial_;
  std::FILE* file_ = nullptr;
};

// ".<process id>.partial": the suffix of this process's temporary files, so that two runs
// never write one temporary file.
std::string PartialSuffix();

// A run's output folder: `requested`, or renders/<name>/ when it is empty; created, locked
// against other aerobox runs (a second run into it stops with exit 2, naming the holder), and
// proven writable before any work starts. Throws InputError. Released when destroyed, and
// removed when this run made it and left it empty.
class OutputFolder {
 public:
  OutputFolder(const std::string& requested, const std::string& name);
  ~OutputFolder();
  OutputFolder(const OutputFolder&) = delete;
  OutputFolder& operator=(const OutputFolder&) = delete;

  const std::string& path() const { return path_; }

  // After a run: removes the outputs aerobox writes (path.csv ... video.mp4, frames/) that this
  // run did not write, so that the folder holds exactly this run's outputs.
  void RemoveStale() const;
  // After a run that failed with an exception: removes the outputs this run wrote, so that the
  // folder holds what it held before.
  void RemoveWritten() const;

 private:
  void RemoveOutputs(bool stale) const;

  std::string path_;
  std::string lock_path_;
  int lock_fd_ = -1;
  bool created_ = false;
  std::filesystem::file_time_type run_start_;
};

}  // namespace aerobox
