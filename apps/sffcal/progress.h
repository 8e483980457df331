// A one-line progress display: redrawn in place on a terminal, a plain line every `every`
// fraction of the work otherwise (logs stay readable).
#pragma once

#include <unistd.h>

#include <cstdio>
#include <string>

namespace sffcal {

class ProgressLine {
 public:
  explicit ProgressLine(double every = 0.05) : every_(every), tty_(isatty(fileno(stdout)) != 0) {}

  /// `fraction` in [0, 1] of the work done, `text` the rest of the line. A negative fraction
  /// (work of unknown length) shows the text alone, and only on a terminal.
  void update(double fraction, const std::string& text) {
    if (tty_) {
      if (fraction < 0.0) std::printf("\r%s\033[K", text.c_str());
      else std::printf("\r%5.1f %% %s\033[K", 100.0 * fraction, text.c_str());
      std::fflush(stdout);
      open_ = true;
    } else if (fraction >= 0.0 && fraction >= next_) {
      std::printf("%5.1f %% %s\n", 100.0 * fraction, text.c_str());
      std::fflush(stdout);
      while (next_ <= fraction) next_ += every_;
    }
  }
  /// Ends the line (on a terminal) before other output.
  void finish() {
    if (open_) std::printf("\n");
    open_ = false;
  }
  ~ProgressLine() { finish(); }

 private:
  double every_, next_ = 0.0;
  bool tty_, open_ = false;
};

}  // namespace sffcal
