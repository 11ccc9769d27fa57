#include "app/files.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <system_error>

#include "app/interrupt.h"
#include "common/error.h"
#include "common/fault_injection.h"

namespace aerobox {
namespace fs = std::filesystem;

namespace {

// An injected write failure for this file (see common/fault_injection.h).
bool WriteFails(const std::string& path) {
  const std::optional<std::string> name = InjectedFault("write");
  return name && fs::path(path).filename() == *name;
}

}  // namespace

void WriteFileAtomically(const std::string& path, const std::string& text) {
  const fs::path target(path);
  fs::path temporary = target;
  temporary += ".partial";
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
    : path_(std::move(path)), partial_(path_ + ".partial") {
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

std::string PrepareOutputFolder(const std::string& requested, const std::string& name,
                                bool* created) {
  const fs::path folder = requested.empty() ? fs::path("renders") / name : fs::path(requested);
  std::error_code ec;
  const bool existed = fs::exists(folder, ec);
  fs::create_directories(folder, ec);
  if (created != nullptr) *created = !existed && !ec;
  if (ec || !fs::is_directory(folder)) {
    throw InputError({folder.string(), 0}, "--out",
                     "cannot create the output folder: " + ec.message());
  }
  const fs::path probe = folder / ".aerobox-write-test";
  WriteFileAtomically(probe.string(), "");
  fs::remove(probe, ec);
  return folder.string();
}

}  // namespace aerobox
