// Stopping on request (Ctrl-C), cooperatively. One process-wide flag: the SIGINT handler sets it
// (outputs/interrupt.h) and every long loop checks it at a point where stopping is clean: RRT*'s
// and the lattice's iterations, Ipopt's iterations, the flight's physics steps, the renderer's
// frames and the encoder, the comparison's and the benchmarks' cases. A check that finds it set
// throws Interrupted, which unwinds (destructors remove temporary files) to the command, which
// exits 130. Checking costs one relaxed atomic load.
#pragma once

#include <stdexcept>
#include <string>
#include <type_traits>

namespace aerobox {

// Thrown where a stop request was found; what() names the work that was under way.
class Interrupted : public std::runtime_error {
 public:
  explicit Interrupted(const std::string& during);
  // The work under way, e.g. "planning the path (RRT*, 52000 iterations)".
  const std::string& during() const { return during_; }

 private:
  std::string during_;
};

// Asks every long loop to stop. Async-signal-safe (a lock-free atomic store).
void RequestStop() noexcept;
// Whether a stop was asked for (and not cleared since).
bool StopRequested() noexcept;
// Forgets a handled request: a long-lived process (the Python package) keeps running after it.
void ClearStopRequest() noexcept;
// Throws Interrupted(during) when a stop was asked for.
inline void ThrowIfStopRequested(const std::string& during) {
  if (StopRequested()) throw Interrupted(during);
}
inline void ThrowIfStopRequested(const char* during) {
  if (StopRequested()) throw Interrupted(during);
}
// The same, with the words made only then: `describe()` returns them.
template <typename Describe, typename = std::enable_if_t<std::is_invocable_v<Describe>>>
void ThrowIfStopRequested(Describe&& describe) {
  if (StopRequested()) throw Interrupted(describe());
}

// The temporary files and folders being written now (thread-safe): what ExitInterrupted and the
// Ctrl-C watchdog (outputs/interrupt.h) remove before they end the process.
void RegisterPartialFile(const std::string& path);
void UnregisterPartialFile(const std::string& path);
void RemovePartialFiles();

// For a stop request that finds work that cannot be stopped (a thread inside a library, such as
// a GL context being made): removes the partial files, says what was under way on stderr and
// ends the process at once with exit code 130, without unwinding.
[[noreturn]] void ExitInterrupted(const std::string& during);

// What a process stopped by Ctrl-C ends with: the shell's code for SIGINT (128 + 2).
inline constexpr int kInterruptedExitCode = 130;

}  // namespace aerobox
