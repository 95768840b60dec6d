// foam2grid's progress display (the runtime's lrigid::Progress): plain lines when stderr is not
// a terminal, a bar redrawn in place on a terminal (a pseudo-terminal from script(1)), nothing
// with -q. Runs the transient tiny case (5 written times) converted as a .pvd series.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <regex>
#include <sstream>

#include "foam2grid/case_fixture.h"

namespace fs = std::filesystem;
using namespace foam2grid_test;

namespace {

std::string convert_command(const std::string& w, const std::string& flags) {
  return quote(foam2grid_bin()) + " " + quote(prepared_case("tinyTransient")) + " -o " +
         quote(w + "/flow.pvd") + " --time all --spacing 0.01 " + flags;
}

size_t count(const std::string& s, const std::string& what) {
  size_t n = 0;
  for (size_t p = s.find(what); p != std::string::npos; p = s.find(what, p + 1)) ++n;
  return n;
}

}  // namespace

TEST(Foam2gridProgress, PipedOutputHasPlainLinesUpToTheLastTime) {
  const std::string w = work_dir("progress_lines");
  std::string out;
  ASSERT_EQ(run(convert_command(w, ""), &out), 0) << out;  // a pipe, not a terminal
  EXPECT_EQ(out.find('\r'), std::string::npos) << out;
  EXPECT_EQ(out.find("\033["), std::string::npos) << out;
  const std::regex line(R"(^foam2grid: +(\d+) %, time (\d+)/(\d+) \(([^)]*) s\): )"
                        R"((\d+) of (\d+) points resampled, .* remaining$)");
  const std::regex fluid(R"(resampled, (\d+) of (\d+) points in the fluid$)");
  std::istringstream in(out);
  std::string s, last_fluid, last_total;
  std::vector<int> percent, time_index;
  std::smatch m;
  std::string last_time, last_points, last_of;  // of the last progress line
  while (std::getline(in, s)) {
    if (std::regex_search(s, m, fluid)) {
      last_fluid = m[1];
      last_total = m[2];
    }
    if (!std::regex_match(s, m, line)) continue;
    percent.push_back(std::stoi(m[1]));
    time_index.push_back(std::stoi(m[2]));
    EXPECT_EQ(m[3], "5") << s;
    last_time = m[4];
    last_points = m[5];
    last_of = m[6];
  }
  // 5 times: every time's end crosses a 10 % mark, so at least one line per time
  ASSERT_GE(percent.size(), 5u) << out;
  for (size_t i = 1; i < percent.size(); ++i) {
    EXPECT_GT(percent[i], percent[i - 1]) << out;
    EXPECT_GE(time_index[i], time_index[i - 1]) << out;
  }
  for (int t = 1; t <= 5; ++t) {
    EXPECT_NE(std::find(time_index.begin(), time_index.end(), t), time_index.end()) << t;
  }
  EXPECT_EQ(percent.back(), 100);
  EXPECT_EQ(time_index.back(), 5);
  // the last line's count is the last time's points in the fluid, of all grid points
  EXPECT_EQ(last_points, last_fluid) << out;
  EXPECT_EQ(last_of, last_total) << out;
  EXPECT_EQ(last_time, "1") << out;  // the last written time of the case, s
}

TEST(Foam2gridProgress, QuietPrintsNothing) {
  const std::string w = work_dir("progress_quiet");
  for (const char* flag : {"-q", "--quiet"}) {
    std::string out;
    ASSERT_EQ(run(convert_command(w, flag), &out), 0) << out;
    EXPECT_EQ(out, "") << flag;
    EXPECT_TRUE(fs::exists(w + "/flow.pvd"));
  }
}

TEST(Foam2gridProgress, TerminalGetsABarUnlessCi) {
  const std::string w = work_dir("progress_bar");
  // script(1) (bsdutils, always installed in Debian) runs the command on a pseudo-terminal
  const std::string cmd = convert_command(w, "");
  std::string bar, ci;
  ASSERT_EQ(run("env -u CI TERM=xterm script -qec " + quote(cmd) + " /dev/null", &bar), 0) << bar;
  EXPECT_GE(count(bar, "\r\033[K"), 1u) << bar;  // log lines clear the bar before printing
  EXPECT_NE(bar.find("foam2grid [########################] 100 % time 5/5 (1 s): "),
            std::string::npos)
      << bar;
  EXPECT_EQ(bar.find("foam2grid: 100 %"), std::string::npos) << bar;
  // CI=true on a terminal: plain lines again
  ASSERT_EQ(run("env CI=true TERM=xterm script -qec " + quote(cmd) + " /dev/null", &ci), 0) << ci;
  EXPECT_EQ(ci.find("[####"), std::string::npos) << ci;
  EXPECT_NE(ci.find("foam2grid: 100 %, time 5/5 (1 s): "), std::string::npos) << ci;
}
