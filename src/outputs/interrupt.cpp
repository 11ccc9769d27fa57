#include "outputs/interrupt.h"

#include <semaphore.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <cstdio>
#include <mutex>
#include <set>
#include <thread>

namespace aerobox {
namespace {

constexpr auto kGrace = std::chrono::milliseconds(1000);  // for the cooperative stop

std::atomic<bool> stop_requested{false};
sem_t signalled;

std::mutex& PartialMutex() {
  static std::mutex mutex;
  return mutex;
}

std::set<std::string>& Partials() {
  static std::set<std::string> partials;
  return partials;
}

// Only async-signal-safe calls: an atomic store and sem_post.
void OnSigint(int) {
  stop_requested = true;
  sem_post(&signalled);
}

void Watchdog() {
  while (sem_wait(&signalled) != 0) {
  }
  // the flight notices at its next control step and leaves by itself within milliseconds;
  // what does not poll is ended here
  std::this_thread::sleep_for(kGrace);
  {
    const std::lock_guard<std::mutex> lock(PartialMutex());
    for (const std::string& path : Partials()) std::remove(path.c_str());
  }
  static const char kMessage[] = "\naerobox: interrupted\n";
  if (write(STDERR_FILENO, kMessage, sizeof(kMessage) - 1) < 0) {
    // nothing more to say
  }
  _exit(kInterruptedExitCode);
}

}  // namespace

void InstallInterruptHandler() {
  static std::once_flag once;
  std::call_once(once, [] {
    sem_init(&signalled, 0, 0);
    std::thread(Watchdog).detach();
    std::signal(SIGINT, OnSigint);
  });
}

const std::atomic<bool>& StopRequested() { return stop_requested; }

void RegisterPartialFile(const std::string& path) {
  const std::lock_guard<std::mutex> lock(PartialMutex());
  Partials().insert(path);
}

void UnregisterPartialFile(const std::string& path) {
  const std::lock_guard<std::mutex> lock(PartialMutex());
  Partials().erase(path);
}

}  // namespace aerobox
