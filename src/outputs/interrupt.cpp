#include "outputs/interrupt.h"

#include <semaphore.h>
#include <unistd.h>

#include <csignal>
#include <mutex>
#include <thread>

namespace aerobox {
namespace {

sem_t signalled;

// Only async-signal-safe calls: an atomic store and sem_post.
void OnSigint(int) {
  RequestStop();
  sem_post(&signalled);
}

void Watchdog() {
  while (sem_wait(&signalled) != 0) {
  }
  // every long loop checks the flag and the command leaves by itself, well before this
  std::this_thread::sleep_for(kInterruptGrace);
  RemovePartialFiles();
  static const char kMessage[] =
      "\naerobox: interrupted: the work under way did not stop within 2 s of Ctrl-C (a bug: "
      "please report the command); ended by the watchdog, temporary files removed\n";
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

}  // namespace aerobox
