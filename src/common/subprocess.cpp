#include "common/subprocess.h"

#include <fcntl.h>
#include <poll.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstring>
#include <stdexcept>

#include "common/stop.h"

extern char** environ;

namespace aerobox {
namespace {

constexpr int kPollMilliseconds = 10;  // how soon a stop request reaches the child

std::vector<std::string> Environment(const std::vector<std::string>& added) {
  std::vector<std::string> words = added;
  for (char** e = environ; *e != nullptr; ++e) {
    const std::string entry(*e);
    const std::string name = entry.substr(0, entry.find('=') + 1);
    bool replaced = false;
    for (const std::string& a : added) replaced = replaced || a.rfind(name, 0) == 0;
    if (!replaced) words.push_back(entry);
  }
  return words;
}

std::vector<char*> Pointers(std::vector<std::string>* words) {
  std::vector<char*> pointers;
  for (std::string& word : *words) pointers.push_back(word.data());
  pointers.push_back(nullptr);
  return pointers;
}

}  // namespace

pid_t StartProcess(const ProcessSpec& spec, int* output_pipe) {
  if (spec.argv.empty()) throw std::logic_error("StartProcess: no program");
  posix_spawnattr_t attributes;
  posix_spawnattr_init(&attributes);
  // the child starts with no signal blocked (the sweep blocks SIGCHLD to wait for its runs)
  sigset_t none;
  sigemptyset(&none);
  posix_spawnattr_setsigmask(&attributes, &none);
  posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETSIGMASK);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  int fds[2] = {-1, -1};
  if (output_pipe != nullptr) {
    if (pipe2(fds, O_CLOEXEC) != 0) throw std::runtime_error("cannot make a pipe");
    posix_spawn_file_actions_adddup2(&actions, fds[1], STDOUT_FILENO);
  } else if (!spec.output.empty()) {
    posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, spec.output.c_str(),
                                     O_WRONLY | O_CREAT | O_TRUNC, 0644);
  }
  if (spec.error_to_output)
    posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
  if (spec.null_input) {
    posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  }
  std::vector<std::string> words = spec.argv;
  std::vector<std::string> environment = Environment(spec.environment);
  std::vector<char*> argv = Pointers(&words);
  std::vector<char*> envp = Pointers(&environment);
  pid_t pid = 0;
  const int code = posix_spawn(&pid, argv[0], &actions, &attributes, argv.data(), envp.data());
  posix_spawn_file_actions_destroy(&actions);
  posix_spawnattr_destroy(&attributes);
  if (fds[1] >= 0) close(fds[1]);
  if (code != 0) {
    if (fds[0] >= 0) close(fds[0]);
    throw std::runtime_error("cannot start " + spec.argv[0] + ": " + std::strerror(code));
  }
  if (output_pipe != nullptr) *output_pipe = fds[0];
  return pid;
}

int ExitCodeOf(int wait_status) {
  if (WIFEXITED(wait_status)) return WEXITSTATUS(wait_status);
  if (WIFSIGNALED(wait_status)) return 128 + WTERMSIG(wait_status);
  return 1;
}

int RunProcess(const ProcessSpec& spec, const std::function<void(const std::string&)>& on_output) {
  int fd = -1;
  const pid_t pid = StartProcess(spec, on_output ? &fd : nullptr);
  bool forwarded = false;
  int status = 0;
  char buffer[4096];
  while (true) {
    if (StopRequested() && !forwarded) {
      kill(pid, SIGINT);
      forwarded = true;
    }
    if (fd >= 0) {
      // its output as it comes, waking at least every few milliseconds for a stop request
      pollfd readable{fd, POLLIN, 0};
      if (poll(&readable, 1, kPollMilliseconds) > 0) {
        const ssize_t n = read(fd, buffer, sizeof(buffer));
        if (n > 0) {
          on_output(std::string(buffer, static_cast<size_t>(n)));
          continue;
        }
        if (n == 0 || errno != EINTR) {
          close(fd);  // end of its output
          fd = -1;
        }
      }
      continue;
    }
    const pid_t done = waitpid(pid, &status, WNOHANG);
    if (done == pid) break;
    if (done < 0 && errno != EINTR) throw std::runtime_error("lost " + spec.argv[0]);
    usleep(kPollMilliseconds * 1000);
  }
  return ExitCodeOf(status);
}

}  // namespace aerobox
