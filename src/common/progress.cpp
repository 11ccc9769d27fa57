#include "common/progress.h"

#include <unistd.h>

namespace aerobox {

ProgressDisplay::ProgressDisplay(std::ostream& err, bool terminal, double interval)
    : err_(err), terminal_(terminal), interval_(interval) {}

ProgressDisplay::~ProgressDisplay() { Clear(); }

bool ProgressDisplay::StderrIsTerminal() { return isatty(STDERR_FILENO) != 0; }

void ProgressDisplay::Show(const std::string& text, bool force) {
  const auto now = std::chrono::steady_clock::now();
  if (shown_ && !force && std::chrono::duration<double>(now - last_).count() < interval_) return;
  shown_ = true;
  last_ = now;
  if (!terminal_) {
    err_ << text << "\n" << std::flush;
    return;
  }
  // padded over what the longer line before it left
  const std::string pad(width_ > text.size() ? width_ - text.size() : 0, ' ');
  err_ << "\r" << text << pad << std::flush;
  width_ = text.size();
}

void ProgressDisplay::Clear() {
  if (!terminal_ || width_ == 0) return;
  err_ << "\r" << std::string(width_, ' ') << "\r" << std::flush;
  width_ = 0;
}

void ProgressDisplay::Keep() {
  if (!terminal_ || width_ == 0) return;
  err_ << "\n" << std::flush;
  width_ = 0;
}

}  // namespace aerobox
