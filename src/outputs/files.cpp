#include "outputs/files.h"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <sstream>
#include <stdexcept>
#include <system_error>

#include "common/error.h"
#include "common/fault_injection.h"
#include "outputs/interrupt.h"

namespace aerobox {
namespace fs = std::filesystem;

std::string PartialSuffix() { return "." + std::to_string(getpid()) + ".partial"; }

namespace {

// a run's staging folder, inside its output folder, and the list of what the last run wrote
const std::string kStagingPrefix = ".aerobox-staging.";
constexpr char kManifest[] = ".aerobox-files";
// what aerobox wrote into a folder before it kept a manifest there
constexpr const char* kLegacyOutputs[] = {"path.csv",     "trajectory.csv", "telemetry.csv",
                                          "summary.json", "overview.png",   "video.mp4",
                                          "report.html",  "frames"};

// An injected write failure for this file (see common/fault_injection.h).
bool WriteFails(const std::string& path) {
  const std::optional<std::string> name = InjectedFault("write");
  return name && fs::path(path).filename() == *name;
}

}  // namespace

void WriteFileAtomically(const std::string& path, const std::string& text) {
  const fs::path target(path);
  fs::path temporary = target;
  temporary += PartialSuffix();
  RegisterPartialFile(temporary.string());
  struct Unregister {
    std::string path;
    ~Unregister() { UnregisterPartialFile(path); }
  } unregister{temporary.string()};
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    if (!out) {
      throw InputError({path, 0}, "", std::string("cannot write: ") + std::strerror(errno));
    }
    out << text;
    out.flush();
    if (!out || WriteFails(path)) {
      std::error_code ignored;
      fs::remove(temporary, ignored);
      throw InputError({path, 0}, "", "writing failed (disk full?)");
    }
  }
  std::error_code ec;
  fs::rename(temporary, target, ec);
  if (ec) {
    std::error_code ignored;
    fs::remove(temporary, ignored);
    throw InputError({path, 0}, "", "cannot write: " + ec.message());
  }
}

StreamingFile::StreamingFile(std::string path)
    : path_(std::move(path)), partial_(path_ + PartialSuffix()) {
  RegisterPartialFile(partial_);
  file_ = std::fopen(partial_.c_str(), "wb");
  if (file_ == nullptr) {
    UnregisterPartialFile(partial_);
    throw InputError({path_, 0}, "", std::string("cannot write: ") + std::strerror(errno));
  }
}

StreamingFile::~StreamingFile() {
  if (file_ != nullptr) {
    std::fclose(file_);
    std::remove(partial_.c_str());
  }
  UnregisterPartialFile(partial_);
}

void StreamingFile::Append(const std::string& text) {
  if (file_ == nullptr) throw std::logic_error("StreamingFile: append after commit");
  if (std::fwrite(text.data(), 1, text.size(), file_) != text.size() || WriteFails(path_)) {
    throw InputError({path_, 0}, "", "writing failed (disk full?)");
  }
}

void StreamingFile::Commit() {
  if (file_ == nullptr) throw std::logic_error("StreamingFile: committed twice");
  const bool flushed = std::fflush(file_) == 0;
  const bool closed = std::fclose(file_) == 0;
  file_ = nullptr;
  if (!flushed || !closed) {
    std::remove(partial_.c_str());
    throw InputError({path_, 0}, "", "writing failed (disk full?)");
  }
  std::error_code ec;
  fs::rename(partial_, path_, ec);
  if (ec) {
    std::remove(partial_.c_str());
    throw InputError({path_, 0}, "", "cannot write: " + ec.message());
  }
}

FileLock::FileLock(std::string path, const std::string& where, const std::string& field,
                   const std::string& busy, const std::string& advice)
    : path_(std::move(path)) {
  while (true) {
    fd_ = open(path_.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd_ < 0) {
      throw InputError({where, 0}, field,
                       std::string("cannot write in the folder: ") + std::strerror(errno));
    }
    if (flock(fd_, LOCK_EX | LOCK_NB) != 0) {
      // the owner writes its process id just after taking the lock: wait a moment for it
      std::string pid;
      for (int attempt = 0; attempt < 20 && pid.empty(); ++attempt) {
        char holder[32] = {0};
        const ssize_t n = pread(fd_, holder, sizeof(holder) - 1, 0);
        pid = n > 0 ? std::string(holder, static_cast<size_t>(n)) : "";
        while (!pid.empty() && (pid.back() == '\n' || pid.back() == ' ')) pid.pop_back();
        if (pid.empty()) usleep(10000);
      }
      close(fd_);
      fd_ = -1;
      throw InputError({where, 0}, field,
                       busy + (pid.empty() ? "" : " (process " + pid + ")") + " " + advice);
    }
    // the file may have been removed by its last owner between our open and our lock
    struct stat opened {
    }, named{};
    if (fstat(fd_, &opened) == 0 && stat(path_.c_str(), &named) == 0 &&
        opened.st_ino == named.st_ino) {
      break;
    }
    close(fd_);
  }
  const std::string pid = std::to_string(getpid()) + "\n";
  if (ftruncate(fd_, 0) != 0 || pwrite(fd_, pid.data(), pid.size(), 0) < 0) {
    // the lock holds without the note of its owner
  }
  RegisterPartialFile(path_);  // the Ctrl-C watchdog removes it too
}

FileLock::~FileLock() {
  UnregisterPartialFile(path_);
  std::remove(path_.c_str());
  close(fd_);  // releases the lock
}

OutputFolder::OutputFolder(const std::string& requested, const std::string& name) {
  const fs::path folder = requested.empty() ? fs::path("renders") / name : fs::path(requested);
  path_ = folder.string();
  std::error_code ec;
  const bool existed = fs::exists(folder, ec);
  fs::create_directories(folder, ec);
  created_ = !existed && !ec;
  if (ec || !fs::is_directory(folder)) {
    throw InputError({folder.string(), 0}, "--out",
                     "cannot create the output folder: " + ec.message());
  }
  // one run at a time per folder
  lock_ = std::make_unique<FileLock>(
      (folder / ".aerobox.lock").string(), path_, "--out", "another aerobox run",
      "is writing into this folder; wait for it or give another --out");
  // with the lock held, any other staging folder is a dead run's
  for (const fs::directory_entry& entry : fs::directory_iterator(folder, ec)) {
    if (entry.path().filename().string().rfind(kStagingPrefix, 0) == 0) {
      fs::remove_all(entry.path(), ec);
    }
  }
  staging_ = (folder / (kStagingPrefix + std::to_string(getpid()))).string();
  RegisterPartialFile(staging_);
  if (!fs::create_directory(staging_, ec) || ec) {
    UnregisterPartialFile(staging_);
    lock_.reset();
    throw InputError({path_, 0}, "--out", "cannot write in the output folder: " + ec.message());
  }
  // a folder this run made holds nothing but this run's: an abrupt end removes it whole
  if (created_) RegisterPartialFile(path_);
}

OutputFolder::~OutputFolder() {
  std::error_code ec;
  if (!staging_.empty()) {
    fs::remove_all(staging_, ec);  // a run that did not commit leaves the folder as it was
    UnregisterPartialFile(staging_);
  }
  if (!lock_) return;
  lock_.reset();
  // bad input leaves nothing behind: not even the folder this run made, when it stayed empty
  if (created_) UnregisterPartialFile(path_);
  if (created_ && fs::is_empty(path_, ec)) fs::remove(path_, ec);
}

InputError OutputFolder::Published(const InputError& error) const {
  std::string file = error.where().file;
  if (file.rfind(staging_ + "/", 0) == 0) {
    file = (fs::path(path_) / file.substr(staging_.size() + 1)).string();
  }
  return InputError({file, error.where().line}, error.field(), error.problem());
}

void OutputFolder::Commit() {
  if (committed_) throw std::logic_error("OutputFolder: committed twice");
  const fs::path folder(path_);
  std::error_code ec;
  std::set<std::string> written;
  for (const fs::directory_entry& entry : fs::directory_iterator(staging_, ec)) {
    written.insert(entry.path().filename().string());
  }
  // the earlier run's outputs: its manifest, and the names aerobox wrote before manifests
  std::set<std::string> earlier(std::begin(kLegacyOutputs), std::end(kLegacyOutputs));
  {
    std::ifstream manifest(folder / kManifest);
    std::string name;
    while (std::getline(manifest, name)) {
      if (!name.empty() && name.find('/') == std::string::npos && name[0] != '.') {
        earlier.insert(name);
      }
    }
  }
  for (const std::string& name : earlier) {
    if (written.count(name) == 0) fs::remove_all(folder / name, ec);
  }
  std::string manifest;
  for (const std::string& name : written) {
    const fs::path target = folder / name;
    if (fs::is_directory(target, ec)) fs::remove_all(target, ec);  // frames/ as a whole
    fs::rename(fs::path(staging_) / name, target, ec);
    if (ec) throw InputError({target.string(), 0}, "", "cannot move into place: " + ec.message());
    manifest += name + "\n";
  }
  WriteFileAtomically((folder / kManifest).string(), manifest);
  committed_ = true;
}

}  // namespace aerobox
