// The only place aerobox writes files (input files are read by scenario/read_file.h).
#pragma once

#include <cstdio>
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

// The output folder: `requested`, or renders/<name>/ when it is empty; created, and proven
// writable (a probe file is written and removed) before any work starts. Throws InputError.
// `created`, when given, tells whether this call made the folder.
std::string PrepareOutputFolder(const std::string& requested, const std::string& name,
                                bool* created = nullptr);

}  // namespace aerobox
