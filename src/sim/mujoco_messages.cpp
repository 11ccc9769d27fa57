#include "sim/mujoco_messages.h"

#include <mujoco/mujoco.h>

#include <cstdio>
#include <cstdlib>
#include <mutex>

namespace aerobox {
namespace {

std::mutex& WarningMutex() {
  static std::mutex mutex;
  return mutex;
}

std::vector<std::string>& Warnings() {
  static std::vector<std::string> warnings;
  return warnings;
}

void OnError(const char* message) {
  std::fprintf(stderr, "aerobox: MuJoCo error: %s\n", message);
  std::exit(1);
}

void OnWarning(const char* message) {
  const std::lock_guard<std::mutex> lock(WarningMutex());
  Warnings().emplace_back(message);
}

}  // namespace

void InstallMujocoMessageHandlers() {
  static std::once_flag once;
  std::call_once(once, [] {
    mju_user_error = OnError;
    mju_user_warning = OnWarning;
  });
}

std::vector<std::string> TakeMujocoWarnings() {
  const std::lock_guard<std::mutex> lock(WarningMutex());
  std::vector<std::string> taken;
  taken.swap(Warnings());
  return taken;
}

}  // namespace aerobox
