// bodies.usda of a run, parsed back by a small reader of the USD text format: its syntax
// (balanced brackets outside strings, the header, each prim's specifier, type and name), the
// layer's metadata, and the PointInstancer's arrays against trajectories.csv at every time code,
// within the printed digits: positions, orientations (quath, real part first), velocities,
// angular velocities (deg/s), ids, protoIndices, invisibleIds; the prototypes' meshes.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <map>
#include <cctype>
#include <cstdlib>
#include <sstream>

#include "io/usd_writer.h"
#include "support/dcc_run.h"
#include "support/temp_dir.h"

namespace lrigid {
namespace {

// the numbers of a value, in order ("[(1, 2), (3, 4)]" -> 1 2 3 4)
std::vector<double> numbers(const std::string& v) {
  std::vector<double> out;
  for (size_t i = 0; i < v.size();) {
    const bool sign = (v[i] == '-' || v[i] == '+') && i + 1 < v.size() && std::isdigit(v[i + 1]);
    if (!std::isdigit(static_cast<unsigned char>(v[i])) && !sign) {
      ++i;
      continue;
    }
    char* end = nullptr;
    out.push_back(std::strtod(v.c_str() + i, &end));
    i = size_t(end - v.c_str());
  }
  return out;
}

// a layer read back: attributes by their prim path and name, each a default value and/or time
// samples (the text of each value), the layer's metadata, the prims' types
struct UsdLayer {
  std::map<std::string, std::string> meta;
  std::map<std::string, std::string> values;                     // "path.attr" -> text
  std::map<std::string, std::map<double, std::string>> samples;  // "path.attr" -> samples
  std::map<std::string, std::string> prims;                      // path -> type
};

std::string trimmed(const std::string& s) {
  const size_t a = s.find_first_not_of(' ');
  return a == std::string::npos ? "" : s.substr(a);
}

bool starts(const std::string& s, const std::string& p) { return s.rfind(p, 0) == 0; }

UsdLayer parse_usda(const std::string& text) {
  UsdLayer l;
  std::istringstream in(text);
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "#usda 1.0");
  std::vector<std::string> path;
  std::string pending;  // a prim whose "{" comes next
  bool in_meta = false;
  std::string samples_of;
  auto here = [&] {
    std::string p;
    for (const auto& s : path) p += "/" + s;
    return p;
  };
  while (std::getline(in, line)) {
    const std::string t = trimmed(line);
    if (line == "(") {
      in_meta = true;
      continue;
    }
    const size_t eq = t.find(" = ");
    if (in_meta) {
      if (line == ")") in_meta = false;
      else if (eq != std::string::npos) l.meta[t.substr(0, eq)] = t.substr(eq + 3);
      continue;
    }
    if (!samples_of.empty()) {
      const size_t colon = t.find(": ");
      if (t == "}") samples_of.clear();
      else if (colon != std::string::npos && t.back() == ',')
        l.samples[samples_of][std::stod(t.substr(0, colon))] =
            t.substr(colon + 2, t.size() - colon - 3);
      else ADD_FAILURE() << "in time samples: " << t.substr(0, 80);
      continue;
    }
    if (starts(t, "def ")) {
      // def Type "name" or def Type "name" (
      const size_t q1 = t.find('"'), q2 = t.find('"', q1 + 1);
      EXPECT_NE(q2, std::string::npos) << t;
      const std::string type = t.substr(4, q1 - 5);
      pending = t.substr(q1 + 1, q2 - q1 - 1);
      EXPECT_EQ(pending.find_first_not_of(
                    "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_"),
                std::string::npos)
          << "prim name " << pending;
      EXPECT_TRUE(q2 + 1 == t.size() || t.substr(q2 + 1) == " (") << t;
      l.prims[here() + "/" + pending] = type;
    } else if (t == "{") {
      path.push_back(pending);
    } else if (t == "}") {
      if (path.empty()) {
        ADD_FAILURE() << "unbalanced }";
        break;
      }
      path.pop_back();
    } else if (eq != std::string::npos) {
      // [uniform] type name[.timeSamples] = value, or rel name = target
      std::string lhs = t.substr(0, eq);
      if (starts(lhs, "uniform ")) lhs = lhs.substr(8);
      const size_t sp = lhs.find(' ');
      if (sp == std::string::npos) continue;  // metadata inside a prim's ( )
      std::string name = lhs.substr(sp + 1);
      const size_t ts = name.find(".timeSamples");
      if (ts != std::string::npos) {
        samples_of = here() + "." + name.substr(0, ts);
        EXPECT_EQ(t.substr(eq + 3), "{");
      } else {
        l.values[here() + "." + name] = t.substr(eq + 3);
      }
    }
  }
  EXPECT_TRUE(path.empty()) << "unclosed prim " << (path.empty() ? "" : path.back());
  return l;
}

// brackets, parentheses and braces balanced outside strings, in order
void expect_balanced(const std::string& text) {
  std::string stack;
  bool quoted = false;
  for (char c : text) {
    if (c == '"') quoted = !quoted;
    if (quoted) continue;
    if (c == '(' || c == '[' || c == '{') stack += c;
    if (c == ')' || c == ']' || c == '}') {
      ASSERT_FALSE(stack.empty()) << "a closing " << c << " with nothing open";
      const char open = c == ')' ? '(' : c == ']' ? '[' : '{';
      ASSERT_EQ(stack.back(), open) << "closes " << stack.back() << " with " << c;
      stack.pop_back();
    }
  }
  EXPECT_TRUE(stack.empty());
  EXPECT_FALSE(quoted);
}

struct UsdCache : test::TempDirTest {};

TEST_F(UsdCache, PointInstancerIsTheTrajectoriesAtEveryTimeCode) {
  test::run_dcc_scene(dir.string(), R"(["csv", "usd"])");
  const auto rows = test::read_trajectories((dir / "trajectories.csv").string());
  std::ifstream f(dir / "bodies.usda");
  std::stringstream ss;
  ss << f.rdbuf();
  const std::string text = ss.str();
  expect_balanced(text);
  const UsdLayer l = parse_usda(text);
  EXPECT_EQ(l.meta.at("upAxis"), "\"Z\"");
  EXPECT_EQ(l.meta.at("metersPerUnit"), "1");
  EXPECT_EQ(l.meta.at("defaultPrim"), "\"lrigid\"");
  EXPECT_EQ(std::stod(l.meta.at("timeCodesPerSecond")), 20.0);  // every 0.05 s
  EXPECT_EQ(std::stod(l.meta.at("startTimeCode")), 0.0);
  EXPECT_EQ(std::stod(l.meta.at("endTimeCode")), 4.0);
  const std::string pi = "/lrigid/bodies";
  EXPECT_EQ(l.prims.at(pi), "PointInstancer");
  EXPECT_EQ(numbers(l.values.at(pi + ".ids")), (std::vector<double>{0, 1, 2, 3, 4}));
  EXPECT_EQ(numbers(l.values.at(pi + ".protoIndices")), (std::vector<double>{0, 0, 1, 2, 2}));
  EXPECT_EQ(l.values.at(pi + ".prototypes"),
            "[</lrigid/bodies/Prototypes/leaf_0>, </lrigid/bodies/Prototypes/leaf_1>, "
            "</lrigid/bodies/Prototypes/pebble>]");
  const size_t nb = 5, nf = rows.size() / nb;
  ASSERT_EQ(nf, 5u);
  for (const char* a : {"positions", "orientations", "velocities", "angularVelocities",
                        "invisibleIds"})
    ASSERT_EQ(l.samples.at(pi + "." + a).size(), nf) << a;
  for (size_t fr = 0; fr < nf; ++fr) {
    const double code = rows[fr * nb].t * 20;
    auto at = [&](const char* a) { return numbers(l.samples.at(pi + "." + a).at(std::round(code))); };
    const auto x = at("positions"), q = at("orientations"), v = at("velocities"),
               w = at("angularVelocities");
    ASSERT_EQ(x.size(), 3 * nb);
    ASSERT_EQ(q.size(), 4 * nb);
    EXPECT_TRUE(at("invisibleIds").empty());
    for (size_t b = 0; b < nb; ++b) {
      const test::TrajectoryRow& r = rows[fr * nb + b];
      EXPECT_TRUE(test::near(Vec3(x[3 * b], x[3 * b + 1], x[3 * b + 2]), r.x, 1e-8));
      // real part first
      const Quat g(q[4 * b], q[4 * b + 1], q[4 * b + 2], q[4 * b + 3]);
      EXPECT_NEAR(std::abs(g.coeffs().dot(r.q.coeffs())), 1.0, 1e-8);
      EXPECT_TRUE(test::near(Vec3(v[3 * b], v[3 * b + 1], v[3 * b + 2]), r.v, 1e-8));
      EXPECT_TRUE(test::near(Vec3(w[3 * b], w[3 * b + 1], w[3 * b + 2]), r.w * 180 / M_PI,
                             1e-6 * (1 + r.w.norm())));
    }
  }
  // the prototypes: a mesh per type, faceVarying normals and (for the leaves) st
  for (const char* t : {"leaf_0", "leaf_1", "pebble"}) {
    const std::string p = pi + "/Prototypes/" + t;
    EXPECT_EQ(l.prims.at(p), "Mesh");
    const size_t corners = numbers(l.values.at(p + ".faceVertexIndices")).size();
    EXPECT_EQ(numbers(l.values.at(p + ".faceVertexCounts")).size() * 3, corners);
    EXPECT_EQ(numbers(l.values.at(p + ".normals")).size(), 3 * corners);
    EXPECT_EQ(l.values.count(p + ".primvars:st"), std::string(t) == "pebble" ? 0u : 1u);
    if (std::string(t) != "pebble") {
      EXPECT_EQ(numbers(l.values.at(p + ".primvars:st")).size(), 2 * corners);
    }
    EXPECT_EQ(l.values.at(p + ".material:binding"),
              std::string("</lrigid/Materials/") + (std::string(t) == "pebble" ? "pebble" : "leaf") + ">");
  }
  EXPECT_EQ(l.prims.at("/lrigid/Materials/leaf"), "Material");
  EXPECT_EQ(l.prims.at("/lrigid/Materials/pebble/Surface"), "Shader");
}

TEST(UsdIdentifier, MakesPrimNamesOfLabels) {
  EXPECT_EQ(usd_identifier("leaf.3"), "leaf_3");
  EXPECT_EQ(usd_identifier("3d leaf"), "_3d_leaf");
  EXPECT_EQ(usd_identifiers({"a.1", "a_1", "b"}), (std::vector<std::string>{"a_1", "a_1_2", "b"}));
}

}  // namespace
}  // namespace lrigid
