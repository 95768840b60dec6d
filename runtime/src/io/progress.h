// Progress of a long job on stderr (lrigid run, foam2grid; validation/lib/progress.py is the
// same display for the Python studies).
//  - on a terminal (isatty(stderr), TERM not "dumb", CI unset): one line redrawn in place with a
//    bar, percent done, the caller's detail text and the estimated time remaining;
//  - otherwise (piped, CI): a plain line at every 10 % of the work;
//  - quiet: nothing.
#pragma once
#include <chrono>
#include <cstdio>
#include <string>

namespace lrigid {

class Progress {
 public:
  enum class Mode { Auto, Bar, Lines, Quiet };

  // `label` starts every line ("lrigid"); Auto picks Bar or Lines as described above.
  explicit Progress(std::string label, Mode mode = Mode::Auto, std::FILE* out = stderr);
  ~Progress();
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  // `fraction` of the work done in [0, 1]; `detail` e.g. "t = 1.20 s, moving 12, landed 3".
  // Cheap when nothing is due: call it as often as convenient.
  void update(double fraction, const std::string& detail);
  // Prints `text` as a line of its own (quiet: nothing): in Bar mode above the bar, which is
  // redrawn under it, so log messages and the bar do not garble each other.
  void message(const std::string& text);
  // Ends the bar's line (Bar mode); later updates are ignored.
  void finish();

  Mode mode() const { return mode_; }

  // Formats seconds as "12 s", "3 min 04 s" or "2 h 05 min".
  static std::string format_duration(double seconds);

 private:
  std::string label_;
  Mode mode_;
  std::FILE* out_;
  std::chrono::steady_clock::time_point start_, last_draw_;
  double next_line_ = 0.1;  // Lines mode: next fraction to report
  std::string bar_line_;    // Bar mode: the line last drawn
  bool drawn_ = false, done_ = false;
};

}  // namespace lrigid
