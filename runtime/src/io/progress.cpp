#include "io/progress.h"

#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <cstring>

namespace lrigid {

namespace {

bool stderr_is_terminal(std::FILE* out) {
  if (out != stderr || !::isatty(STDERR_FILENO)) return false;
  const char* ci = std::getenv("CI");
  if (ci && *ci && std::strcmp(ci, "false") != 0 && std::strcmp(ci, "0") != 0) return false;
  const char* term = std::getenv("TERM");
  return !(term && std::strcmp(term, "dumb") == 0);
}

}  // namespace

Progress::Progress(std::string label, Mode mode, std::FILE* out)
    : label_(std::move(label)), mode_(mode), out_(out) {
  if (mode_ == Mode::Auto) mode_ = stderr_is_terminal(out_) ? Mode::Bar : Mode::Lines;
  start_ = last_draw_ = std::chrono::steady_clock::now();
}

Progress::~Progress() { finish(); }

std::string Progress::format_duration(double s) {
  char buf[64];
  if (!std::isfinite(s) || s < 0) return "?";
  if (s < 60)
    std::snprintf(buf, sizeof buf, "%.0f s", s);
  else if (s < 3600)
    std::snprintf(buf, sizeof buf, "%d min %02d s", int(s / 60), int(s) % 60);
  else
    std::snprintf(buf, sizeof buf, "%d h %02d min", int(s / 3600), int(s / 60) % 60);
  return buf;
}

void Progress::update(double f, const std::string& detail) {
  if (mode_ == Mode::Quiet || done_) return;
  f = std::fmin(1.0, std::fmax(0.0, f));
  const auto now = std::chrono::steady_clock::now();
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  // remaining time from the mean rate so far; unknown until 1 % or 0.5 s of work
  const std::string eta = (f >= 0.01 || elapsed > 0.5) && f > 0
                              ? format_duration(elapsed * (1 - f) / f)
                              : std::string("?");
  if (mode_ == Mode::Lines) {
    if (f + 1e-12 < next_line_) return;  // after 100 % next_line_ is 1.1: printed once
    next_line_ = std::floor(f * 10 + 1e-9) / 10 + 0.1;
    std::fprintf(out_, "%s: %3.0f %%, %s, %s remaining\n", label_.c_str(), 100 * f, detail.c_str(),
                 eta.c_str());
    std::fflush(out_);
    return;
  }
  // Bar: redraw at most 10 times a second, and always at the end
  if (drawn_ && f < 1.0 && std::chrono::duration<double>(now - last_draw_).count() < 0.1) return;
  last_draw_ = now;
  constexpr int kWidth = 24;
  const int filled = int(std::lround(f * kWidth));
  std::string bar(size_t(filled), '#');
  bar.append(size_t(kWidth - filled), '.');
  char head[64];
  std::snprintf(head, sizeof head, "] %3.0f %% ", 100 * f);
  bar_line_ = label_ + " [" + bar + head + detail + ", ETA " + (f >= 1.0 ? "0 s" : eta);
  // \r back to column 0, \033[K clears what a longer earlier line left
  std::fprintf(out_, "\r%s\033[K", bar_line_.c_str());
  std::fflush(out_);
  drawn_ = true;
}

void Progress::message(const std::string& text) {
  if (mode_ == Mode::Quiet) return;
  if (mode_ == Mode::Bar && drawn_ && !done_) {
    std::fprintf(out_, "\r\033[K%s\n%s", text.c_str(), bar_line_.c_str());
  } else {
    std::fprintf(out_, "%s\n", text.c_str());
  }
  std::fflush(out_);
}

void Progress::finish() {
  if (done_) return;
  done_ = true;
  if (mode_ == Mode::Bar && drawn_) {
    std::fputc('\n', out_);
    std::fflush(out_);
  }
}

}  // namespace lrigid
