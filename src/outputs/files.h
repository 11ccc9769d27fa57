// The only place aerobox writes files (input files are read by map/read_file.h).
#pragma once

#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>

#include "common/error.h"

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

// The one lock of aerobox: an advisory lock on the file `path` (made if missing) that notes its
// owner's process id, one holder at a time across processes. When another process holds it,
// throws InputError at `where` for `field`: "<busy> (process N); <advice>". Released, and the
// file removed, when destroyed; a Ctrl-C's last resort removes the file too.
class FileLock {
 public:
  FileLock(std::string path, const std::string& where, const std::string& field,
           const std::string& busy, const std::string& advice);
  ~FileLock();
  FileLock(const FileLock&) = delete;
  FileLock& operator=(const FileLock&) = delete;

 private:
  std::string path_;
  int fd_ = -1;
};

// A run's output folder: `requested`, or renders/<name>/ when it is empty; created, locked
// against other aerobox runs (a second run into it stops with exit 2, naming the holder), and
// proven writable before any work starts. Throws InputError.
//
// The folder holds one whole run, never a mix: a run writes into staging(), a hidden folder
// inside, and Commit() swaps its files in when the run has ended (removing the earlier run's
// outputs, named in the folder's manifest, .aerobox-files). Destroyed without Commit() (bad
// input, a failure, Ctrl-C), it removes the staging folder: the earlier run stays untouched.
// The lock is released when destroyed, and the folder removed when this run made it and left
// it empty.
class OutputFolder {
 public:
  OutputFolder(const std::string& requested, const std::string& name);
  ~OutputFolder();
  OutputFolder(const OutputFolder&) = delete;
  OutputFolder& operator=(const OutputFolder&) = delete;

  // The folder, as users name it (for messages).
  const std::string& path() const { return path_; }
  // Where this run writes its files until Commit().
  const std::string& staging() const { return staging_; }
  // Moves this run's files into the folder in place of the earlier run's. Throws InputError.
  void Commit();
  // Runs `work`, which writes into staging(): an InputError naming a file there is thrown again
  // naming it where the user will look for it, in path().
  template <typename Work>
  auto Run(Work&& work) const -> decltype(work()) {
    try {
      return work();
    } catch (const InputError& error) {
      throw Published(error);
    }
  }
  InputError Published(const InputError& error) const;

 private:
  std::string path_;
  std::string staging_;
  std::unique_ptr<FileLock> lock_;
  bool created_ = false;
  bool committed_ = false;
};

}  // namespace aerobox
