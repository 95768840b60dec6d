// Bad input at the command line: build/bin/lrigid is run on broken scenes, grids,
// meshes and output directories in a fresh temporary directory. Each case asserts the
// documented exit code (docs/stability.md: 2 usage, 3 bad input, 4 output, 5 resource), that
// the message names the file, the key and the value, and that the output directory holds
// nothing that looks like a result (summary.json, trajectories.csv, bodies.pvd).
// An interrupted run (SIGINT, SIGTERM) must not leave final-looking files either.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

namespace fs = std::filesystem;

namespace {

const std::string kLrigid = std::string(LRIGID_BINARY_DIR) + "/bin/lrigid";

std::string slurp(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

void put(const fs::path& p, const std::string& text) {
  std::ofstream out(p, std::ios::binary);
  out << text;
}

// A valid scene (uniform flow, two spheres) with placeholders that cases replace.
std::string base_scene() {
  return R"({
  "version": 1,
  "fluid": {
    "density": 1.204,
    "kinematic_viscosity": 1.5e-5,
    "uniform": { "U": [1.0, 0.0, 0.0], "k": 0.1, "epsilon": 0.05 }
  },
  "gravity": [0, 0, -9.81],
  "effects": "auto",
  "integrator": { "scheme": "splitting", "dt": 0.001 },
  "duration": 0.05,
  "seed": 3,
  "bodies": [
    {
      "name": "bead",
      "shape": { "type": "sphere", "radius": 0.003 },
      "density": 30,
      "count": 2,
      "position": [0, 0, 1]
    }
  ],
  "output": { "dir": "out", "every": 0.01 }
}
)";
}

std::string replace(std::string s, const std::string& from, const std::string& to) {
  const size_t p = s.find(from);
  if (p == std::string::npos) throw std::runtime_error("test bug: no '" + from + "' in scene");
  return s.replace(p, from.size(), to);
}

// limits the child runs under: set by the test, not by the machine
struct Limits {
  rlim_t file_size = RLIM_INFINITY;     // RLIMIT_FSIZE, bytes (ulimit -f)
  rlim_t address_space = RLIM_INFINITY;  // RLIMIT_AS, bytes (ulimit -v)
  bool unprivileged = false;             // as root: run as nobody, so permissions apply
};

struct Result {
  int code = -1;       // exit code, or 128 + signal
  std::string err;     // stderr
};

class Cli : public ::testing::Test {
 protected:
  void SetUp() override {
    char tmpl[] = "/tmp/lrigid_cli_XXXXXX";
    ASSERT_NE(mkdtemp(tmpl), nullptr);
    dir_ = tmpl;
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }

  // Starts lrigid with `args` in dir_, stderr to a file; returns the child's pid.
  pid_t start(const std::vector<std::string>& args, const Limits& lim = {}) {
    const pid_t pid = fork();
    if (pid == 0) {
      if (chdir(dir_.c_str()) != 0) _exit(126);
      const std::string err = (dir_ / "stderr.txt").string();
      if (!freopen(err.c_str(), "w", stderr)) _exit(126);
      if (!freopen("/dev/null", "w", stdout)) _exit(126);
      if (lim.unprivileged && getuid() == 0 && (setgid(65534) != 0 || setuid(65534) != 0))
        _exit(126);
      const struct rlimit fs = {lim.file_size, lim.file_size};
      const struct rlimit as = {lim.address_space, lim.address_space};
      if (setrlimit(RLIMIT_FSIZE, &fs) != 0 || setrlimit(RLIMIT_AS, &as) != 0) _exit(126);
      std::vector<char*> argv;
      argv.push_back(const_cast<char*>(kLrigid.c_str()));
      for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
      argv.push_back(nullptr);
      execv(kLrigid.c_str(), argv.data());
      _exit(127);
    }
    return pid;
  }

  Result wait_for(pid_t pid) {
    int status = 0;
    waitpid(pid, &status, 0);
    Result r;
    r.code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    r.err = slurp(dir_ / "stderr.txt");
    return r;
  }

  // waits (up to 30 s) until a run in dir_/out is writing: its temporary trajectories exist
  bool wait_until_writing() {
    for (int i = 0; i < 600; ++i) {
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
      if (fs::exists(dir_ / "out"))
        for (const auto& e : fs::directory_iterator(dir_ / "out"))
          if (e.path().filename().string().rfind("trajectories.csv.", 0) == 0) return true;
    }
    return false;
  }

  Result run(const std::vector<std::string>& args, const Limits& lim = {}) {
    return wait_for(start(args, lim));
  }

  // Writes `scene` as scene.json and runs `lrigid run scene.json`.
  Result run_scene(const std::string& scene, const std::string& name = "scene.json") {
    put(dir_ / name, scene);
    return run({"run", name, "--quiet"});
  }

  // Nothing that looks like a finished result anywhere under dir_.
  void expect_no_results() {
    for (const auto& e : fs::recursive_directory_iterator(dir_)) {
      const std::string n = e.path().filename().string();
      EXPECT_NE(n, "summary.json") << e.path();
      EXPECT_NE(n, "trajectories.csv") << e.path();
      EXPECT_NE(n, "bodies.pvd") << e.path();
      EXPECT_NE(n, "landings.csv") << e.path();
      EXPECT_NE(n, "shapes.pvd") << e.path();
      EXPECT_NE(n, "animation.glb") << e.path();
    }
  }

  // The common assertions: exit code, every needle in the message, no results.
  void expect_error(const Result& r, int code, const std::vector<std::string>& needles) {
    EXPECT_EQ(r.code, code) << r.err;
    // usage errors come from CLI11 with its own wording
    if (code != 2) {
      EXPECT_NE(r.err.find("lrigid: error: "), std::string::npos) << r.err;
    }
    for (const auto& n : needles) {
      EXPECT_NE(r.err.find(n), std::string::npos) << "message lacks '" << n << "': " << r.err;
    }
    expect_no_results();
  }

  fs::path dir_;
};

TEST_F(Cli, ValidSceneRunsAndWritesResults) {
  // the base scene is good: the error cases below fail because of what they change
  const Result r = run_scene(base_scene());
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(fs::exists(dir_ / "out" / "summary.json"));
  EXPECT_TRUE(fs::exists(dir_ / "out" / "trajectories.csv"));
  EXPECT_TRUE(fs::exists(dir_ / "out" / "bodies.pvd"));
  for (const auto& e : fs::directory_iterator(dir_ / "out"))
    EXPECT_EQ(e.path().string().find(".tmp"), std::string::npos) << "left over: " << e.path();
}

TEST_F(Cli, UsageErrorsExit2) {
  expect_error(run({"run"}), 2, {});
  expect_error(run({"run", "scene.json", "--threads", "0"}), 2, {"threads"});
  expect_error(run({"frobnicate"}), 2, {"subcommand"});
}

TEST_F(Cli, MissingSceneFile) {
  expect_error(run({"run", "nope.json"}), 3, {"nope.json"});
}

TEST_F(Cli, MalformedJsonGivesLineAndColumn) {
  // line 8 is "gravity": [0, 0, -9.81] with the comma after it removed
  const std::string s =
      replace(base_scene(), "\"gravity\": [0, 0, -9.81],", "\"gravity\": [0, 0, -9.81]");
  expect_error(run_scene(s), 3, {"scene.json", "line 9", "column"});
}

TEST_F(Cli, TruncatedJson) {
  const std::string s = base_scene().substr(0, 200);
  expect_error(run_scene(s), 3, {"scene.json", "malformed JSON", "line"});
}

TEST_F(Cli, DuplicatedKeysRefused) {
  // nlohmann keeps the last of two equal keys; the scene must not change without a word
  expect_error(run_scene(replace(base_scene(), "\"seed\": 3,", "\"seed\": 3, \"seed\": 4,")), 3,
               {"scene.json", "seed", "duplicated key"});
  expect_error(
      run_scene(replace(base_scene(), "\"density\": 30,", "\"density\": 30, \"density\": 31,")),
      3, {"scene.json", "bodies.density", "duplicated key"});
}

TEST_F(Cli, DeepNestingRefusedWithoutCrash) {
  // 200,000 nested arrays where a number belongs: dumping them for the message overflowed the stack
  const int d = 200000;
  const std::string deep = std::string(d, '[') + std::string(d, ']');
  expect_error(run_scene(replace(base_scene(), "\"seed\": 3,", "\"seed\": " + deep + ",")), 3,
               {"scene.json", "seed", "nested deeper than 64"});
}

TEST_F(Cli, DirectoryAsSceneNamedAsSuch) {
  fs::create_directory(dir_ / "adir");
  expect_error(run({"run", "adir"}), 3, {"adir", "is a directory"});
}

TEST_F(Cli, EmptyOutputNameIsAUsageError) {
  // -o "" used to fall back on the scene's output.dir and write there
  put(dir_ / "scene.json", base_scene());
  expect_error(run({"run", "scene.json", "-o", "", "--quiet"}), 2, {"output", "empty"});
}

TEST_F(Cli, OutputDirThatIsNoPath) {
  // "" failed to create a directory (exit 4, no key); a NUL cut the path short: "o\u0000x"
  // was "o", and a directory of that name ended in exit 1 "basic_filebuf::underflow"
  fs::create_directory(dir_ / "o");
  expect_error(run_scene(replace(base_scene(), "\"dir\": \"out\"", "\"dir\": \"\"")), 3,
               {"scene.json", "output.dir", "must not be empty"});
  expect_error(run_scene(replace(base_scene(), "\"dir\": \"out\"", "\"dir\": \"o\\u0000x\"")), 3,
               {"scene.json", "output.dir", "NUL"});
  EXPECT_TRUE(fs::is_empty(dir_ / "o"));
}

TEST_F(Cli, HugeOutputEveryRefused) {
  // every / dt beyond 2^64 steps died of SIGFPE converting the output stride
  const std::string s = replace(base_scene(), "\"every\": 0.01", "\"every\": 1e300");
  expect_error(run_scene(s), 3, {"scene.json", "output.every", "1e+300", "at most 4e9 steps"});
}

TEST_F(Cli, HugePanelsRefusedBeforeTessellation) {
  // 2e9 panels tessellated a box at 80 MB/s before the solver's limit was checked
  const std::string s =
      replace(base_scene(), "\"shape\": { \"type\": \"sphere\", \"radius\": 0.003 }",
              "\"shape\": { \"type\": \"box\", \"size\": [0.01, 0.01, 0.002], "
              "\"panels\": 2000000000 }");
  expect_error(run_scene(s), 3, {"scene.json", "shape.panels", "2000000000", "[0, 10000]"});
}

TEST_F(Cli, NameThatWouldBreakCsvRefused) {
  // a comma or a quote in a type's name shifted the columns of trajectories.csv
  expect_error(run_scene(replace(base_scene(), "\"name\": \"bead\"", "\"name\": \"be,ad\"")), 3,
               {"scene.json", "bodies[0].name", "be,ad", "CSV field"});
  expect_error(run_scene(replace(base_scene(), "\"name\": \"bead\"", "\"name\": \"be\\\"ad\"")),
               3, {"scene.json", "bodies[0].name", "double quotes"});
}

TEST_F(Cli, ExtremeArtFactorRefused) {
  // a mean flow scaled by 1e300 made every force NaN: the bodies failed and the run exited 0
  expect_error(
      run_scene(replace(base_scene(), "\"seed\": 3,", "\"seed\": 3, \"art\": {\"mean_flow_scale\": 1e300},")),
      3, {"scene.json", "art.mean_flow_scale", "1e+300", "[0, 1000]"});
}

TEST_F(Cli, ShapeLengthsOutOfRangeRefused) {
  const std::string sphere = "\"shape\": { \"type\": \"sphere\", \"radius\": 0.003 }";
  // a box of 1e160 m hung in the boundary elements
  expect_error(run_scene(replace(base_scene(), sphere,
                                 "\"shape\": { \"type\": \"box\", \"size\": [1e160, 1, 1] }")),
               3, {"scene.json", "shape.size", "1e+160", "[1e-9, 1e6] m"});
  // tiny radii ended in exit 1 "carlson_rd: invalid arguments"
  expect_error(run_scene(replace(base_scene(), sphere,
                                 "\"shape\": { \"type\": \"ellipsoid\", \"semi_axes\": [1e-200, 1e-200, 2e-200] }")),
               3, {"scene.json", "shape.semi_axes", "[1e-9, 1e6] m"});
  expect_error(run_scene(replace(base_scene(), sphere,
                                 "\"shape\": { \"type\": \"sphere\", \"radius\": 1e-200 }")),
               3, {"scene.json", "shape.radius", "1e-200", "[1e-9, 1e6] m"});
}

TEST_F(Cli, BoxTooThinForTheBoundaryElements) {
  // a sheet of 1e6:1 ended in "tensor is not positive semi-definite" from the solver
  expect_error(run_scene(replace(base_scene(),
                                 "\"shape\": { \"type\": \"sphere\", \"radius\": 0.003 }",
                                 "\"shape\": { \"type\": \"box\", \"size\": [1, 1, 1e-6] }")),
               3, {"scene.json", "bodies[0].shape.size", "at most 1e5", "[1,1,1e-06]"});
}

TEST_F(Cli, TooManyVariantsRefusedBeforeAnyIsBuilt) {
  // 300 entries of 256 box variants: 76800 boundary-element solves (hours) before the count
  // of body types was checked
  std::string entries;
  for (int i = 0; i < 300; ++i)
    entries += std::string(i ? ", " : "") +
               "{\"name\": \"b\", \"shape\": {\"type\": \"box\", \"size\": [0.01, 0.01, 0.002]}, "
               "\"density\": 30, \"count\": 256, \"position\": [0, 0, 1], "
               "\"variation\": {\"size\": [1, 2], \"variants\": 256}}";
  std::string s = base_scene();
  const size_t a = s.find("\"bodies\": ["), b = s.find("],\n  \"output\"");
  s = s.substr(0, a) + "\"bodies\": [" + entries + s.substr(b);
  put(dir_ / "scene.json", s);
  // (refused when the scene is read: were the variants built first, the test would run into
  // ctest's timeout instead)
  expect_error(run({"run", "scene.json"}), 3, {"scene.json", "bodies", "65535", "76800"});
}

TEST_F(Cli, UnknownKeys) {
  expect_error(run_scene(replace(base_scene(), "\"seed\": 3,", "\"seed\": 3, \"colour\": 1,")), 3,
               {"scene.json", "colour", "unknown key"});
  expect_error(run_scene(replace(base_scene(), "\"density\": 30,", "\"density\": 30, \"mas\": 1,")),
               3, {"scene.json", "bodies[0]: unknown key \"mas\""});
}

TEST_F(Cli, TyposInRequiredKeysAreNamed) {
  // the key the user wrote is named, before any required key is found missing
  expect_error(run_scene(replace(base_scene(), "\"density\": 30", "\"densty\": 30")), 3,
               {"scene.json: bodies[0]: unknown key \"densty\" (did you mean \"density\"?)"});
  expect_error(run_scene(replace(base_scene(), "\"kinematic_viscosity\"", "\"kinematic_viscocity\"")),
               3, {"scene.json: fluid: unknown key \"kinematic_viscocity\" (did you mean "
                   "\"kinematic_viscosity\"?)"});
  expect_error(run_scene(replace(base_scene(), "\"position\": [0, 0, 1]",
                                 "\"spawn_bx\": [[0, 0, 1], [1, 1, 2]]")),
               3, {"bodies[0]: unknown key \"spawn_bx\" (did you mean \"spawn_box\"?)"});
  expect_error(run_scene(replace(base_scene(), "\"seed\": 3,", "\"seed\": 3, \"art.turbulence_scale\": 2,")),
               3, {"unknown key \"art.turbulence_scale\"", "nested", "\"art\": { \"turbulence_scale\""});
}

TEST_F(Cli, TyposInFlagsAreNamed) {
  put(dir_ / "scene.json", base_scene());
  expect_error(run({"run", "scene.json", "--sed", "4"}), 2,
               {"unknown flag \"--sed\" (did you mean \"--seed\"?)"});
  expect_error(run({"run", "scene.json", "--thread=2"}), 2,
               {"unknown flag \"--thread\" (did you mean \"--threads\"?)"});
}

TEST_F(Cli, WrongTypes) {
  expect_error(run_scene(replace(base_scene(), "\"duration\": 0.05", "\"duration\": \"ten\"")), 3,
               {"scene.json", "duration", "ten"});
  expect_error(run_scene(replace(base_scene(), "\"count\": 2", "\"count\": 2.5")), 3,
               {"scene.json", "bodies[0].count", "2.5"});
  expect_error(run_scene(replace(base_scene(), "\"gravity\": [0, 0, -9.81]", "\"gravity\": 9.81")),
               3, {"scene.json", "gravity", "9.81"});
}

TEST_F(Cli, NumberTooLargeForADouble) {
  // found by fuzz_scene: nlohmann::json throws out_of_range (406) for 1e999, which must still
  // be a bad-input error naming the file, not an internal error (exit 1)
  expect_error(run_scene(replace(base_scene(), "\"duration\": 0.05", "\"duration\": 1e999")), 3,
               {"scene.json", "1e999"});
}

// contact materials (docs/scene-format.md "Contacts"): a negative friction or rolling
// resistance, or one that is not a number, is named with its key and value by the binary too
TEST_F(Cli, BadContactMaterials) {
  const struct {
    const char* key;
    const char* value;
  } cases[] = {{"friction", "-1"}, {"rolling_resistance", "-0.01"},
               {"rolling_resistance", "\"low\""}};
  for (const auto& c : cases) {
    const std::string material = std::string("\"") + c.key + "\": " + c.value;
    SCOPED_TRACE(material);
    expect_error(run_scene(replace(base_scene(), "\"density\": 30",
                                   "\"density\": 30, \"contact\": {" + material + "}")),
                 3, {"scene.json", std::string("bodies[0].contact.") + c.key, c.value});
  }
}

struct BadValue {
  const char* from;
  const char* to;
  const char* key;    // expected in the message
  const char* value;  // expected in the message
};

TEST_F(Cli, NonPositiveSizesDensitiesStepsAndDurations) {
  const BadValue cases[] = {
      {"\"radius\": 0.003", "\"radius\": -0.003", "bodies[0].shape.radius", "-0.003"},
      {"\"radius\": 0.003", "\"radius\": 0", "bodies[0].shape.radius", "0"},
      {"\"type\": \"sphere\", \"radius\": 0.003", "\"type\": \"box\", \"size\": [0.1, -0.2, 0.1]",
       "bodies[0].shape.size", "-0.2"},
      {"\"type\": \"sphere\", \"radius\": 0.003",
       "\"type\": \"ellipsoid\", \"semi_axes\": [0.1, -1, 0.1]", "bodies[0].shape.semi_axes", "-1"},
      {"\"density\": 30", "\"density\": 0", "bodies[0].density", "0"},
      {"\"density\": 30", "\"density\": -30", "bodies[0].density", "-30"},
      {"\"density\": 1.204", "\"density\": -1.204", "fluid.density", "-1.204"},
      {"\"kinematic_viscosity\": 1.5e-5", "\"kinematic_viscosity\": 0",
       "fluid.kinematic_viscosity", "0"},
      {"\"dt\": 0.001", "\"dt\": 0", "integrator.dt", "0"},
      {"\"dt\": 0.001", "\"dt\": -0.001", "integrator.dt", "-0.001"},
      {"\"duration\": 0.05", "\"duration\": 0", "duration", "0"},
      {"\"duration\": 0.05", "\"duration\": -1", "duration", "-1"},
      {"\"count\": 2", "\"count\": 0", "bodies[0].count", "0"},
      {"\"every\": 0.01", "\"every\": 0", "output.every", "0"},
  };
  for (const BadValue& c : cases) {
    SCOPED_TRACE(std::string(c.from) + " -> " + c.to);
    expect_error(run_scene(replace(base_scene(), c.from, c.to)), 3,
                 {"scene.json", c.key, c.value});
  }
}

// Every number of a scene has a range; outside it a product in the step overflowed and the
// bodies failed (exit 0), or "auto" judged an effect by a non-finite number and dropped it
// (gravity 1e308: the bodies hung still).
TEST_F(Cli, QuantitiesOutOfRangeRefused) {
#define POS "\"position\": [0, 0, 1]"
  const BadValue cases[] = {
      {"\"gravity\": [0, 0, -9.81]", "\"gravity\": [0, 0, -1e308]", "gravity", "[-1e4, 1e4] m/s^2"},
      {"\"density\": 30", "\"density\": 1e308", "bodies[0].density", "[1e-6, 1e6] kg/m^3"},
      {"\"density\": 30", "\"density\": 1e-300", "bodies[0].density", "1e-300"},
      {"\"density\": 1.204", "\"density\": 1e308", "fluid.density", "[1e-6, 1e6] kg/m^3"},
      {"\"kinematic_viscosity\": 1.5e-5", "\"kinematic_viscosity\": 1e308",
       "fluid.kinematic_viscosity", "[1e-9, 1e3] m^2/s"},
      {"\"U\": [1.0, 0.0, 0.0]", "\"U\": [1e300, 0.0, 0.0]", "fluid.uniform.U", "[-1e5, 1e5] m/s"},
      {"\"k\": 0.1", "\"k\": 1e300", "fluid.uniform.k", "[0, 1e8]"},
      {"\"epsilon\": 0.05", "\"epsilon\": 1e300", "fluid.uniform.epsilon", "[0, 1e12]"},
      {POS, "\"position\": [1e308, 0, 1]", "bodies[0].position", "[-1e9, 1e9] m"},
      {POS, "\"spawn_box\": [[-1e308, 0, 0], [1e308, 1, 1]]", "bodies[0].spawn_box[0]", "1e+308"},
      {POS, POS ", \"velocity\": [1e300, 0, 0]", "bodies[0].velocity",
       "[-1e5, 1e5] m/s"},
      {POS, POS ", \"angular_velocity\": [0, 1e300, 0]",
       "bodies[0].angular_velocity", "[-1e6, 1e6] rad/s"},
      {"\"seed\": 3,", "\"seed\": 3, \"ground\": {\"z\": 1e308},", "ground.z", "[-1e9, 1e9] m"},
      {"\"density\": 30,", "\"density\": 30, \"variation\": {\"size\": [1e-300, 1e300]},",
       "bodies[0].variation.size", "[1e-9, 1e6] m"},
      {"\"density\": 30,", "\"density\": 30, \"variation\": {\"density\": [1e-300, 1e300]},",
       "bodies[0].variation.density", "[1e-6, 1e6] kg/m^3"},
      {"\"density\": 30,", "\"density\": 30, \"variation\": {\"spin\": [0, 1e300]},",
       "bodies[0].variation.spin", "1e6 rad/s"},
      // a step longer than the run: no step at all, an output of t = 0 only
      {"\"dt\": 0.001", "\"dt\": 1e300", "integrator.dt", "at most duration"},
  };
#undef POS
  for (const BadValue& c : cases) {
    SCOPED_TRACE(std::string(c.from) + " -> " + c.to);
    expect_error(run_scene(replace(base_scene(), c.from, c.to)), 3,
                 {"scene.json", c.key, c.value});
  }
}

TEST_F(Cli, RangesEndsRun) {
  // the ends of the ranges are valid: the bodies run to the end without failing
  std::string s = replace(base_scene(), "\"gravity\": [0, 0, -9.81]", "\"gravity\": [0, 1e4, -1e4]");
  s = replace(s, "\"position\": [0, 0, 1]",
              "\"position\": [1e9, -1e9, 1e9], \"velocity\": [1e5, -1e5, 1e5], "
              "\"angular_velocity\": [1e6, 0, -1e6]");
  s = replace(s, "\"U\": [1.0, 0.0, 0.0], \"k\": 0.1, \"epsilon\": 0.05",
              "\"U\": [1e5, 0.0, -1e5], \"k\": 1e8, \"epsilon\": 1e12");
  const Result r = run_scene(s);
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string summary = slurp(dir_ / "out" / "summary.json");
  EXPECT_NE(summary.find("\"failed\": 0"), std::string::npos) << summary;
  // the largest gravity in still air: "auto" keeps it (at 1e308 it dropped it)
  const Result g = run_scene(
      replace(base_scene(), "\"gravity\": [0, 0, -9.81]", "\"gravity\": [0, 0, -1e4]"));
  ASSERT_EQ(g.code, 0) << g.err;
  const std::string gs = slurp(dir_ / "out" / "summary.json");
  EXPECT_NE(gs.find("\"effects\": [\n        \"gravity\""), std::string::npos) << gs;
}

TEST_F(Cli, HugeQuaternionIsNormalized) {
  // the squares of [1e300, 1e300, 0, 0] overflowed: a NaN orientation and two failed bodies
  const Result r = run_scene(replace(base_scene(), "\"position\": [0, 0, 1]",
                                     "\"position\": [0, 0, 1], \"orientation\": [1e300, 1e300, 0, 0]"));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(slurp(dir_ / "out" / "summary.json").find("\"failed\": 0"), std::string::npos);
  // body 0 at t = 0: w = x = 1/sqrt(2)
  const std::string csv = slurp(dir_ / "out" / "trajectories.csv");
  EXPECT_NE(csv.find("\n0,bead,0,0,0,1,0.707106781,0.707106781,0,0,"), std::string::npos)
      << csv.substr(0, 300);
}

TEST_F(Cli, SeedOfTheWholeUnsignedRange) {
  // 2^64 - 1 is a seed (--seed takes it too); it was refused as "must be an integer >= 0"
  const Result r = run_scene(replace(base_scene(), "\"seed\": 3", "\"seed\": 18446744073709551615"));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(slurp(dir_ / "out" / "summary.json").find("18446744073709551615"), std::string::npos);
  fs::remove_all(dir_ / "out");
  expect_error(run_scene(replace(base_scene(), "\"seed\": 3", "\"seed\": -1")), 3,
               {"scene.json", "seed", "[0, 2^64 - 1]", "-1"});
}

TEST_F(Cli, EmptySceneFileNamedAsSuch) {
  put(dir_ / "empty.json", "");
  expect_error(run({"run", "empty.json"}), 3, {"empty.json", "is empty"});
  put(dir_ / "blank.json", " \n\t\n");
  expect_error(run({"run", "blank.json"}), 3, {"blank.json", "is empty"});
}

TEST_F(Cli, NotANumberFlagsRefused) {
  // CLI11's positive-number check lets NaN through: --tolerance nan ran
  put(dir_ / "scene.json", base_scene());
  expect_error(run({"run", "scene.json", "--tolerance", "nan"}), 2, {"--tolerance", "not a number"});
  expect_error(run({"run", "scene.json", "--tolerance", "0"}), 2, {"--tolerance", "relative error"});
  const Result r = run({"run", "scene.json", "--tolerance", "0"});
  EXPECT_LT(r.err.size(), 300u) << "the largest double printed in full: " << r.err;
  expect_error(run({"run", "scene.json", "--checkpoint-every", "nan"}), 2,
               {"--checkpoint-every", "not a number"});
}

// ---- grids ----

// A 2x2x2 ASCII .vti; `k` and `eps` are the 8 values of each, as text.
std::string vti(const std::string& k, const std::string& eps,
                const std::string& extent = "0 1 0 1 0 1") {
  std::ostringstream s;
  s << R"(<?xml version="1.0"?>
<VTKFile type="ImageData" version="1.0" byte_order="LittleEndian" header_type="UInt64">
<ImageData WholeExtent=")" << extent << R"(" Origin="-1 -1 -1" Spacing="2 2 2">
<Piece Extent=")" << extent << R"(">
<PointData>
<DataArray type="Float32" Name="U" NumberOfComponents="3" format="ascii">
1 0 0 1 0 0 1 0 0 1 0 0 1 0 0 1 0 0 1 0 0 1 0 0
</DataArray>
<DataArray type="Float32" Name="k" format="ascii">
)" << k << R"(
</DataArray>
<DataArray type="Float32" Name="epsilon" format="ascii">
)" << eps << R"(
</DataArray>
<DataArray type="UInt8" Name="valid" format="ascii">
1 1 1 1 1 1 1 1
</DataArray>
</PointData>
<CellData>
</CellData>
</Piece>
</ImageData>
</VTKFile>
)";
  return s.str();
}

std::string grid_scene(const std::string& file) {
  std::string s = replace(base_scene(),
                          R"("uniform": { "U": [1.0, 0.0, 0.0], "k": 0.1, "epsilon": 0.05 })",
                          "\"field\": \"" + file + "\"");
  return replace(s, "\"position\": [0, 0, 1]", "\"position\": [0, 0, 0]");
}

TEST_F(Cli, GoodAsciiGridRuns) {
  // the hand-written grid is valid, so the cases below fail for the defect they add
  put(dir_ / "g.vti",
      vti("0.1 0.1 0.1 0.1 0.1 0.1 0.1 0.1", "0.05 0.05 0.05 0.05 0.05 0.05 0.05 0.05"));
  const Result r = run_scene(grid_scene("g.vti"));
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(fs::exists(dir_ / "out" / "summary.json"));
}

TEST_F(Cli, MissingGrid) {
  expect_error(run_scene(grid_scene("missing.vti")), 3, {"missing.vti", "not found"});
}

TEST_F(Cli, UnreadableGrid) {
  put(dir_ / "junk.vti", "this is not XML\n\x01\x02\x03");
  expect_error(run_scene(grid_scene("junk.vti")), 3, {"junk.vti"});
  fs::create_directory(dir_ / "dir.vti");
  expect_error(run_scene(grid_scene("dir.vti")), 3, {"dir.vti"});
  put(dir_ / "g.txt", "x");
  expect_error(run_scene(grid_scene("g.txt")), 3, {"g.txt"});
}

TEST_F(Cli, GridWithoutReadPermission) {
  // VTK's reader called an unreadable grid "not a VTK XML ImageData (.vti) file"
  put(dir_ / "g.vti",
      vti("0.1 0.1 0.1 0.1 0.1 0.1 0.1 0.1", "0.05 0.05 0.05 0.05 0.05 0.05 0.05 0.05"));
  fs::permissions(dir_ / "g.vti", fs::perms::none);
  put(dir_ / "scene.json", grid_scene("g.vti"));
  fs::permissions(dir_, fs::perms::all);  // nobody may enter the folder, not read the grid
  Limits nobody;
  nobody.unprivileged = true;
  expect_error(run({"run", "scene.json", "--quiet", "-o", "/tmp/lrigid_cli_unreadable_out"}, nobody),
               3, {"g.vti", "cannot be read", "Permission denied"});
}

TEST_F(Cli, GridWithNaN) {
  put(dir_ / "nan.vti",
      vti("0.1 0.1 nan 0.1 0.1 0.1 0.1 0.1", "0.05 0.05 0.05 0.05 0.05 0.05 0.05 0.05"));
  expect_error(run_scene(grid_scene("nan.vti")), 3, {"nan.vti"});
}

TEST_F(Cli, GridWithNegativeK) {
  put(dir_ / "negk.vti",
      vti("0.1 0.1 -0.5 0.1 0.1 0.1 0.1 0.1", "0.05 0.05 0.05 0.05 0.05 0.05 0.05 0.05"));
  expect_error(run_scene(grid_scene("negk.vti")), 3, {"negk.vti", "k", "-0.5", "point 2"});
}

TEST_F(Cli, GridWithNegativeEpsilon) {
  put(dir_ / "nege.vti",
      vti("0.1 0.1 0.1 0.1 0.1 0.1 0.1 0.1", "0.05 0.05 0.05 0.05 -7 0.05 0.05 0.05"));
  expect_error(run_scene(grid_scene("nege.vti")), 3, {"nege.vti", "epsilon", "-7", "point 4"});
}

TEST_F(Cli, EmptyGrids) {
  put(dir_ / "empty.vti", "");
  expect_error(run_scene(grid_scene("empty.vti")), 3, {"empty.vti"});
  put(dir_ / "flat.vti", vti("0.1 0.1", "0.05 0.05", "0 1 0 0 0 0"));
  expect_error(run_scene(grid_scene("flat.vti")), 3, {"flat.vti", "dimensions"});
  put(dir_ / "empty.pvd", "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\">\n<Collection>\n"
                          "</Collection>\n</VTKFile>\n");
  expect_error(run_scene(grid_scene("empty.pvd")), 3, {"empty.pvd", "empty"});
}

TEST_F(Cli, SeriesTimeThatIsNotFinite) {
  // std::stod reads "nan": the message said "times must be distinct, 1 repeats"
  put(dir_ / "g.vti",
      vti("0.1 0.1 0.1 0.1 0.1 0.1 0.1 0.1", "0.05 0.05 0.05 0.05 0.05 0.05 0.05 0.05"));
  for (const char* t : {"nan", "inf"}) {
    SCOPED_TRACE(t);
    put(dir_ / "s.pvd", std::string("<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\">\n"
                                    "<Collection>\n<DataSet timestep=\"") + t +
                            "\" file=\"g.vti\"/>\n<DataSet timestep=\"1\" file=\"g.vti\"/>\n"
                            "</Collection>\n</VTKFile>\n");
    expect_error(run_scene(grid_scene("s.pvd")), 3,
                 {"s.pvd", "DataSet.timestep", "finite", std::string("\"") + t + "\""});
  }
}

TEST_F(Cli, SeriesEntryWithAnOverlongFileName) {
  // found by fuzz_grid: std::filesystem throws (ENAMETOOLONG) on a 300-character name, which
  // must be a bad-input error naming the series, not an internal error (exit 1)
  put(dir_ / "long.pvd", "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\">\n<Collection>\n"
                         "<DataSet timestep=\"0\" file=\"" + std::string(300, 'g') + ".vti\"/>\n"
                         "</Collection>\n</VTKFile>\n");
  expect_error(run_scene(grid_scene("long.pvd")), 3, {"long.pvd"});
}

TEST_F(Cli, GridPieceOutsideItsExtentIsOneClearLine) {
  // found by fuzz_grid (F3, docs/stability.md): a <Piece> extent outside the WholeExtent.
  // the header check refuses it before VTK's reader, which would print ERR lines of its own
  // and leave only a grid of 0 x 0 x 0 to report
  std::string g =
      vti("0.1 0.1 0.1 0.1 0.1 0.1 0.1 0.1", "0.05 0.05 0.05 0.05 0.05 0.05 0.05 0.05");
  g = replace(g, "<Piece Extent=\"0 1 0 1 0 1\">", "<Piece Extent=\"0 1 0 7 0 1\">");
  put(dir_ / "piece.vti", g);
  const Result r = run_scene(grid_scene("piece.vti"));
  expect_error(r, 3, {"piece.vti", "Extent: the piece's extent differs from WholeExtent"});
  EXPECT_EQ(r.err.find("ERR|"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("0 x 0 x 0"), std::string::npos) << r.err;
}

TEST_F(Cli, GridValuesOutOfRange) {
  // a grid's flow within the ranges of a scene's uniform flow: U of 1e30 m/s blew every body out
  // of the grid in the first step (exit 0, all "exited")
  const std::string k = "0.1 0.1 0.1 0.1 0.1 0.1 0.1 0.1";
  const std::string eps = "0.05 0.05 0.05 0.05 0.05 0.05 0.05 0.05";
  put(dir_ / "fastU.vti", replace(vti(k, eps), "1 0 0 1 0 0 1 0 0", "1 0 0 1 0 0 1e30 0 0"));
  expect_error(run_scene(grid_scene("fastU.vti")), 3, {"fastU.vti", "U", "point 2", "[-1e5, 1e5] m/s"});
  put(dir_ / "bigk.vti", vti("0.1 0.1 0.1 1e30 0.1 0.1 0.1 0.1", eps));
  expect_error(run_scene(grid_scene("bigk.vti")), 3, {"bigk.vti", "k", "point 3", "[0, 1e8]"});
  put(dir_ / "bige.vti", vti(k, "0.05 1e30 0.05 0.05 0.05 0.05 0.05 0.05"));
  expect_error(run_scene(grid_scene("bige.vti")), 3, {"bige.vti", "epsilon", "point 1", "[0, 1e12]"});
}

// ---- meshes ----

std::string mesh_scene(const std::string& file) {
  return replace(base_scene(), "\"type\": \"sphere\", \"radius\": 0.003",
                 "\"type\": \"mesh\", \"file\": \"" + file + "\", \"scale\": 0.01");
}

TEST_F(Cli, OpenInvertedAndZeroVolumeMeshes) {
  const std::string data = std::string(LRIGID_SOURCE_DIR) + "/tests/data/meshes/";
  fs::copy_file(data + "open.obj", dir_ / "open.obj");
  fs::copy_file(data + "inverted.obj", dir_ / "inverted.obj");
  fs::copy_file(data + "tetra.obj", dir_ / "tetra.obj");
  // a tetrahedron squashed flat: closed and consistently oriented, zero volume
  put(dir_ / "flat.obj",
      "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0.2 0.2 0\nf 1 3 2\nf 1 2 4\nf 2 3 4\nf 3 1 4\n");
  put(dir_ / "garbage.stl", "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 zz\n");
  expect_error(run_scene(mesh_scene("open.obj")), 3, {"open.obj", "bodies[0].shape"});
  expect_error(run_scene(mesh_scene("inverted.obj")), 3, {"inverted.obj", "bodies[0].shape"});
  expect_error(run_scene(mesh_scene("flat.obj")), 3, {"flat.obj", "bodies[0].shape"});
  expect_error(run_scene(mesh_scene("garbage.stl")), 3, {"garbage.stl"});
  expect_error(run_scene(mesh_scene("absent.obj")), 3, {"absent.obj"});
  // and the good mesh runs: the failures above come from the defects
  const Result ok = run_scene(mesh_scene("tetra.obj"));
  EXPECT_EQ(ok.code, 0) << ok.err;
}

// A relative "field" or mesh "file" is looked for in the scene's folder: when it is not there, the
// message says which folder that was (absolute), whatever the working directory; an absolute
// name is reported as it is
TEST_F(Cli, MissingRelativeFilesNameTheFolderTheyWereLookedFor) {
  fs::create_directory(dir_ / "shots");
  const std::string folder = (dir_ / "shots").lexically_normal().string();
  put(dir_ / "shots" / "grid.json", grid_scene("grids/wind.vti"));
  expect_error(run({"run", "shots/grid.json", "--quiet"}), 3,
               {"fluid.field", "shots/grids/wind.vti",
                "(\"grids/wind.vti\" is relative to the scene's folder, " + folder + ")"});
  put(dir_ / "shots" / "mesh.json", mesh_scene("leaves/leaf.obj"));
  expect_error(run({"run", "shots/mesh.json", "--quiet"}), 3,
               {"bodies[0].shape.file", "leaf.obj",
                "(\"leaves/leaf.obj\" is relative to the scene's folder, " + folder + ")"});
  // an absolute name: no folder added
  const std::string abs = (dir_ / "nowhere.vti").string();
  const Result r = run_scene(grid_scene(abs));
  expect_error(r, 3, {"file not found: " + abs});
  EXPECT_EQ(r.err.find("relative to the scene's folder"), std::string::npos) << r.err;
}

TEST_F(Cli, SelfIntersectingMeshRefused) {
  // two overlapping tetrahedra: closed, consistently oriented, positive volume, and their faces
  // cross; the run went on with a wrong added mass (exit 0)
  put(dir_ / "two.obj",
      "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nv 0.2 0.2 0.2\nv 1.2 0.2 0.2\nv 0.2 1.2 0.2\n"
      "v 0.2 0.2 1.2\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\nf 5 7 6\nf 5 6 8\nf 5 8 7\nf 6 7 8\n");
  expect_error(run_scene(mesh_scene("two.obj")), 3,
               {"scene.json", "bodies[0].shape.file", "two.obj", "intersects itself", "faces"});
}

TEST_F(Cli, MeshOfMorePanelsThanTheSolverTakesNamesTheFile) {
  // a closed sphere of 10200 triangles: more than the dense solve's 10000 panels. Exit 5 said
  // "boundary element method: 10200 panels exceed ..." without the scene, key or mesh
  std::ostringstream obj;
  const int rings = 52, sectors = 100;
  obj << "v 0 0 1\n";
  for (int i = 1; i < rings; ++i)
    for (int j = 0; j < sectors; ++j) {
      const double th = M_PI * i / rings, ph = 2 * M_PI * j / sectors;
      obj << "v " << std::sin(th) * std::cos(ph) << " " << std::sin(th) * std::sin(ph) << " "
          << std::cos(th) << "\n";
    }
  obj << "v 0 0 -1\n";
  const auto at = [&](int i, int j) { return 2 + (i - 1) * sectors + j % sectors; };  // 1-based
  const int bottom = 2 + (rings - 1) * sectors;
  for (int j = 0; j < sectors; ++j) obj << "f 1 " << at(1, j) << " " << at(1, j + 1) << "\n";
  for (int i = 1; i < rings - 1; ++i)
    for (int j = 0; j < sectors; ++j)
      obj << "f " << at(i, j) << " " << at(i + 1, j) << " " << at(i + 1, j + 1) << "\nf "
          << at(i, j) << " " << at(i + 1, j + 1) << " " << at(i, j + 1) << "\n";
  for (int j = 0; j < sectors; ++j)
    obj << "f " << bottom << " " << at(rings - 1, j + 1) << " " << at(rings - 1, j) << "\n";
  put(dir_ / "fine.obj", obj.str());
  expect_error(run_scene(mesh_scene("fine.obj")), 5,
               {"scene.json", "bodies[0].shape.file", "fine.obj", "10200 panels"});
}

TEST_F(Cli, MeshNameTooLongForTheFileSystem) {
  // std::filesystem threw (ENAMETOOLONG) past the mesh reader: exit 1 "filesystem error"
  expect_error(run_scene(mesh_scene(std::string(5000, 'm') + ".obj")), 3,
               {"scene.json", "bodies[0].shape.file", "mmmm", "cannot be read"});
}

TEST_F(Cli, MeshScaleOutOfRange) {
  // the scaled mesh keeps to the shapes' lengths: 1e300 and 1e-300 were "face 0 has zero area"
  const std::string data = std::string(LRIGID_SOURCE_DIR) + "/tests/data/meshes/";
  fs::copy_file(data + "tetra.obj", dir_ / "tetra.obj");
  for (const char* scale : {"1e300", "1e-300", "1e7"}) {
    SCOPED_TRACE(scale);
    expect_error(run_scene(replace(mesh_scene("tetra.obj"), "\"scale\": 0.01",
                                   std::string("\"scale\": ") + scale)),
                 3, {"scene.json", "bodies[0].shape.scale", "tetra.obj", "[1e-9, 1e6] m"});
  }
  fs::create_directory(dir_ / "dir.obj");
  expect_error(run_scene(mesh_scene("dir.obj")), 3, {"dir.obj", "is a directory"});
}

// ---- output and resources ----

TEST_F(Cli, OutputDirectoryThatCannotBeWritten) {
  put(dir_ / "blocker", "a file where the output directory's parent should be");
  const Result r = run({"run", "scene.json", "--quiet", "-o", "blocker/out"});
  (void)r;  // scene.json does not exist yet; write it and run again
  put(dir_ / "scene.json", base_scene());
  expect_error(run({"run", "scene.json", "--quiet", "-o", "blocker/out"}), 4, {"blocker"});
  expect_error(run({"run", "scene.json", "--quiet", "-o", "/proc/lrigid_cannot_write_here"}), 4,
               {"/proc/lrigid_cannot_write_here"});
}

TEST_F(Cli, TooManyBodiesForTheParser) {
  expect_error(run_scene(replace(base_scene(), "\"count\": 2", "\"count\": 2000000000")), 3,
               {"scene.json", "bodies[0].count", "1e8"});
}

TEST_F(Cli, MoreBodiesThanMemorySaysHowMuch) {
  // lrigid run estimates 216 bytes per body and refuses to start when that exceeds 80 % of the
  // memory it may use: the physical memory or, lower here on any machine, the address-space
  // limit this test sets (4 GiB; 3e7 bodies need 6 GiB)
  const Limits four_gib{RLIM_INFINITY, rlim_t(4) << 30, false};
  put(dir_ / "scene.json", replace(base_scene(), "\"count\": 2", "\"count\": 30000000"));
  expect_error(run({"run", "scene.json", "--quiet"}, four_gib), 5,
               {"scene.json", "bodies", "30000000 bodies need about 6.0 GiB",
                "the address-space limit (ulimit -v) is 4.0 GiB"});
  // the same limit with few bodies runs: the refusal comes from the count
  put(dir_ / "scene.json", base_scene());
  const Result ok = run({"run", "scene.json", "--quiet"}, four_gib);
  EXPECT_EQ(ok.code, 0) << ok.err;
}

// ---- a finish that fails late ----

// a scene that writes every kind of result: csv, pvd (bodies and shapes), glb, landings
std::string all_outputs_scene() {
  std::string s = replace(base_scene(), "\"output\": { \"dir\": \"out\", \"every\": 0.01 }",
                          "\"ground\": { \"z\": 0.99 },\n  \"output\": { \"dir\": \"out\", "
                          "\"every\": 0.01, \"formats\": [\"csv\", \"pvd\", \"glb\"] }");
  return replace(s, "\"duration\": 0.05", "\"duration\": 0.12");
}

const char* const kResultNames[] = {"trajectories.csv", "bodies.pvd", "shapes.pvd",
                                    "animation.glb",    "landings.csv", "summary.json",
                                    "bodies",           "shapes"};

class LateFailure : public Cli {
 protected:
  // after a failed finish: none of the results under its final name (what the test put
  // there itself excepted), and no temporaries left behind
  void expect_nothing_final(const std::string& except = "") {
    for (const char* n : kResultNames) {
      if (n != except) {
        EXPECT_FALSE(fs::exists(dir_ / "out" / n)) << n << " appeared";
      }
    }
    for (const auto& e : fs::recursive_directory_iterator(dir_ / "out"))
      EXPECT_EQ(e.path().string().find(".tmp"), std::string::npos) << "left over: " << e.path();
  }
};

TEST_F(LateFailure, AllResultsAppearTogether) {
  put(dir_ / "scene.json", all_outputs_scene());
  const Result r = run({"run", "scene.json", "--quiet"});
  ASSERT_EQ(r.code, 0) << r.err;
  for (const char* n : kResultNames) EXPECT_TRUE(fs::exists(dir_ / "out" / n)) << n;
  EXPECT_GT(fs::file_size(dir_ / "out" / "landings.csv"), 20u) << "the bodies landed";
}

TEST_F(LateFailure, APathTakenLeavesNoResult) {
  // each result's final path taken by something of the other kind: a non-empty folder where a
  // file goes, a file where a folder goes. The run fails with exit 4 naming the path, and
  // none of the other results appears
  put(dir_ / "scene.json", all_outputs_scene());
  for (const char* n : kResultNames) {
    SCOPED_TRACE(n);
    fs::remove_all(dir_ / "out");
    fs::create_directories(dir_ / "out");
    const bool folder = std::string(n) == "bodies" || std::string(n) == "shapes";
    if (folder) {
      put(dir_ / "out" / n, "mine");
    } else {
      fs::create_directories(dir_ / "out" / n);
      put(dir_ / "out" / n / "keep.txt", "mine");
    }
    const Result r = run({"run", "scene.json", "--quiet"});
    EXPECT_EQ(r.code, 4) << r.err;
    EXPECT_NE(r.err.find(std::string("out/") + n), std::string::npos) << r.err;
    expect_nothing_final(n);
    // and what was there is untouched
    EXPECT_EQ(slurp(folder ? dir_ / "out" / n : dir_ / "out" / n / "keep.txt"), "mine");
  }
}

TEST_F(LateFailure, AnEarlierRunIsReplacedWholeOrKept) {
  // a second run into the same folder whose finish fails keeps the first run's results
  put(dir_ / "scene.json", all_outputs_scene());
  ASSERT_EQ(run({"run", "scene.json", "--quiet"}).code, 0);
  const std::string summary = slurp(dir_ / "out" / "summary.json");
  const std::string csv = slurp(dir_ / "out" / "trajectories.csv");
  // the second run differs (another seed) and cannot write its animation
  fs::permissions(dir_ / "out", fs::perms::all, fs::perm_options::add);
  fs::remove(dir_ / "out" / "animation.glb");
  fs::create_directories(dir_ / "out" / "animation.glb" / "x");
  const Result r = run({"run", "scene.json", "--quiet", "--seed", "9"});
  EXPECT_EQ(r.code, 4) << r.err;
  EXPECT_EQ(slurp(dir_ / "out" / "summary.json"), summary);
  EXPECT_EQ(slurp(dir_ / "out" / "trajectories.csv"), csv);
}

TEST_F(LateFailure, AFileSizeLimitLeavesNoResult) {
  // ulimit -f below each result's size in turn (measured on a good run): every write, during
  // the run or at its finish, fails in turn; each such run exits 4 and leaves nothing
  put(dir_ / "scene.json", all_outputs_scene());
  ASSERT_EQ(run({"run", "scene.json", "--quiet"}).code, 0);
  std::vector<std::pair<std::string, uintmax_t>> sizes;
  uintmax_t largest_frame = 0;
  for (const auto& e : fs::recursive_directory_iterator(dir_ / "out"))
    if (e.is_regular_file()) {
      if (e.path().parent_path() == dir_ / "out")
        sizes.emplace_back(e.path().filename().string(), e.file_size());
      else
        largest_frame = std::max<uintmax_t>(largest_frame, e.file_size());
    }
  sizes.emplace_back("largest .vtp frame", largest_frame);
  ASSERT_EQ(sizes.size(), 8u);  // with lrigid-manifest.json
  for (const auto& [name, size] : sizes) {
    SCOPED_TRACE(name + " of " + std::to_string(size) + " bytes");
    fs::remove_all(dir_ / "out");
    const Limits lim{rlim_t(size * 9 / 10), RLIM_INFINITY, false};
    const Result r = run({"run", "scene.json", "--quiet"}, lim);
    EXPECT_EQ(r.code, 4) << r.err;
    if (fs::exists(dir_ / "out")) expect_nothing_final();
  }
}

TEST_F(LateFailure, AFolderMadeReadOnlyMidRunLeavesNoResult) {
  // the output folder becomes read-only while the run goes on (as root, the run is started as
  // nobody so that the permission applies): its frames still go to the temporary folders it
  // made, but nothing can be moved into place at the finish
  std::string s = replace(base_scene(), "\"count\": 2", "\"count\": 4000");
  s = replace(s, "\"duration\": 0.05", "\"duration\": 3");
  s = replace(s, "\"every\": 0.01", "\"every\": 0.5");
  put(dir_ / "scene.json", s);
  fs::permissions(dir_, fs::perms::all);
  fs::permissions(dir_ / "scene.json", fs::perms::all);
  const pid_t pid = start({"run", "scene.json", "--quiet", "--threads", "1"},
                          Limits{RLIM_INFINITY, RLIM_INFINITY, true});
  ASSERT_TRUE(wait_until_writing()) << "the run never started writing";
  const auto read_only = fs::perms::owner_read | fs::perms::owner_exec | fs::perms::group_read |
                         fs::perms::group_exec | fs::perms::others_read | fs::perms::others_exec;
  fs::permissions(dir_ / "out", read_only);
  if (getuid() != 0) {
    ASSERT_NE(::access((dir_ / "out").c_str(), W_OK), 0);
  }
  const Result r = wait_for(pid);
  fs::permissions(dir_ / "out", fs::perms::all);
  EXPECT_EQ(r.code, 4) << r.err;
  EXPECT_NE(r.err.find("out/"), std::string::npos) << r.err;
  for (const char* n : kResultNames) EXPECT_FALSE(fs::exists(dir_ / "out" / n)) << n;
}

// ---- interrupted runs ----

class Interrupted : public Cli, public ::testing::WithParamInterface<int> {};

TEST_P(Interrupted, LeavesNothingFinalLooking) {
  // long enough to be caught mid-run: 10^4 bodies for 10^5 steps
  std::string s = replace(base_scene(), "\"count\": 2", "\"count\": 10000");
  s = replace(s, "\"duration\": 0.05", "\"duration\": 100");
  put(dir_ / "scene.json", s);
  const pid_t pid = start({"run", "scene.json", "--threads", "1"});
  // wait until the run is writing (its temporary trajectories file exists), then interrupt
  EXPECT_TRUE(wait_until_writing()) << "the run never started writing";
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  kill(pid, GetParam());
  const Result r = wait_for(pid);
  EXPECT_NE(r.code, 0) << r.err;
  expect_no_results();
  // and the signal handler (runtime/app/signals.cpp) removed the temporary files too
  std::vector<std::string> left;
  if (fs::exists(dir_ / "out"))
    for (const auto& e : fs::directory_iterator(dir_ / "out"))
      left.push_back(e.path().filename().string());
  for (const auto& n : left) ADD_FAILURE() << "left over after the signal: " << n;
  EXPECT_EQ(r.code, 128 + GetParam()) << "dies of the signal it got";
}

INSTANTIATE_TEST_SUITE_P(Signals, Interrupted, ::testing::Values(SIGINT, SIGTERM),
                         [](const auto& info) {
                           return std::string(info.param == SIGINT ? "SIGINT" : "SIGTERM");
                         });

}  // namespace
