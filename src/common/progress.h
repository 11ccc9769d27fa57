// Progress on standard error, one way for every command (fly's frames, a sweep's bar, each
// benchmark's stage): on a terminal one line rewritten in place, wiped or kept when the work
// ends; elsewhere (a log, a pipe) whole lines, at most one every `interval` seconds, so that a
// log stays short.
#pragma once

#include <chrono>
#include <ostream>
#include <string>

namespace aerobox {

class ProgressDisplay {
 public:
  // `terminal`: rewrite one line in place. `interval` [s]: the least time between two lines
  // that are not forced (a terminal's included: a line rewritten faster cannot be read).
  ProgressDisplay(std::ostream& err, bool terminal, double interval);
  ~ProgressDisplay();  // wipes a line left on a terminal
  ProgressDisplay(const ProgressDisplay&) = delete;
  ProgressDisplay& operator=(const ProgressDisplay&) = delete;

  // Whether standard error is a terminal.
  static bool StderrIsTerminal();

  // Shows `text` (one line, without "\n"); skipped when the last was shown less than the
  // interval ago, unless `force`.
  void Show(const std::string& text, bool force = false);
  // Wipes the line from a terminal (a no-op elsewhere).
  void Clear();
  // Ends the line on a terminal, so that it stays (a no-op elsewhere).
  void Keep();

 private:
  std::ostream& err_;
  bool terminal_;
  double interval_;   // [s]
  size_t width_ = 0;  // of the line on the terminal now; 0: none
  bool shown_ = false;
  std::chrono::steady_clock::time_point last_;
};

}  // namespace aerobox
