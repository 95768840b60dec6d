// Progress lines when stderr is not a terminal: one line per 10 % of the work, quiet prints
// nothing, the bar mode redraws one line in place and ends it with a newline.
#include "io/progress.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <string>

namespace lrigid {
namespace {

std::string run(Progress::Mode mode, int updates) {
  std::FILE* f = std::tmpfile();
  {
    Progress p("test", mode, f);
    for (int i = 1; i <= updates; ++i) p.update(double(i) / updates, "t = " + std::to_string(i));
  }
  std::rewind(f);
  std::string out;
  char buf[256];
  while (std::fgets(buf, sizeof buf, f)) out += buf;
  std::fclose(f);
  return out;
}

size_t count(const std::string& s, const std::string& what) {
  size_t n = 0;
  for (size_t p = s.find(what); p != std::string::npos; p = s.find(what, p + 1)) ++n;
  return n;
}

TEST(Progress, LinesEveryTenPercent) {
  const std::string out = run(Progress::Mode::Lines, 1000);
  EXPECT_EQ(count(out, "\n"), 10u) << out;
  EXPECT_NE(out.find("test:  10 %, t = 100, "), std::string::npos) << out;
  EXPECT_NE(out.find("test: 100 %, t = 1000, 0 s remaining"), std::string::npos) << out;
  EXPECT_EQ(out.find('\r'), std::string::npos);
}

TEST(Progress, FewUpdatesStillReportEachOne) {
  // 4 updates of 25 %: each crosses a 10 % mark
  EXPECT_EQ(count(run(Progress::Mode::Lines, 4), "\n"), 4u);
}

TEST(Progress, QuietPrintsNothing) { EXPECT_EQ(run(Progress::Mode::Quiet, 100), ""); }

TEST(Progress, BarRedrawsInPlaceAndEndsTheLine) {
  const std::string out = run(Progress::Mode::Bar, 50);
  EXPECT_GE(count(out, "\r"), 2u);  // first draw and the final 100 %
  EXPECT_EQ(count(out, "\n"), 1u);
  EXPECT_NE(out.find("[########################] 100 %"), std::string::npos) << out;
}

TEST(Progress, NotATerminalMeansLines) {
  // a file is never a terminal
  std::FILE* f = std::tmpfile();
  Progress p("x", Progress::Mode::Auto, f);
  EXPECT_EQ(p.mode(), Progress::Mode::Lines);
  std::fclose(f);
}

TEST(Progress, Durations) {
  EXPECT_EQ(Progress::format_duration(42.4), "42 s");
  EXPECT_EQ(Progress::format_duration(184), "3 min 04 s");
  EXPECT_EQ(Progress::format_duration(7500), "2 h 05 min");
  EXPECT_EQ(Progress::format_duration(-1), "?");
}

}  // namespace
}  // namespace lrigid
