#include "common/stop.h"

#include <unistd.h>

#include <atomic>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <mutex>
#include <set>

namespace aerobox {
namespace {

std::atomic<bool> stop_requested{false};
static_assert(std::atomic<bool>::is_always_lock_free, "set from a signal handler");

std::mutex& PartialMutex() {
  static std::mutex mutex;
  return mutex;
}

std::set<std::string>& Partials() {
  static std::set<std::string> partials;
  return partials;
}

}  // namespace

Interrupted::Interrupted(const std::string& during)
    : std::runtime_error("interrupted while " + during), during_(during) {}

void RequestStop() noexcept { stop_requested.store(true, std::memory_order_relaxed); }

bool StopRequested() noexcept { return stop_requested.load(std::memory_order_relaxed); }

void ClearStopRequest() noexcept { stop_requested.store(false, std::memory_order_relaxed); }

void RegisterPartialFile(const std::string& path) {
  const std::lock_guard<std::mutex> lock(PartialMutex());
  Partials().insert(path);
}

void UnregisterPartialFile(const std::string& path) {
  const std::lock_guard<std::mutex> lock(PartialMutex());
  Partials().erase(path);
}

void RemovePartialFiles() {
  const std::lock_guard<std::mutex> lock(PartialMutex());
  std::error_code ignored;
  for (const std::string& path : Partials()) std::filesystem::remove_all(path, ignored);
}

void ExitInterrupted(const std::string& during) {
  RemovePartialFiles();
  std::cout.flush();
  std::cerr << "\naerobox: interrupted while " << during << "; no output written or changed"
            << std::endl;
  std::fflush(nullptr);
  _exit(kInterruptedExitCode);
}

}  // namespace aerobox
