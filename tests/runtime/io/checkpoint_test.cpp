// Checkpoints (io/checkpoint.h) keep what a resumed run needs to go on bitwise: here the
// sleeping bodies' gust watches (contact/sleep.h), which decide the step a sleeper wakes at.
#include "io/checkpoint.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "io/durable.h"
#include "util/error.h"

namespace lrigid {
namespace {

State bodies(size_t n, bool watches) {
  State st;
  st.x.assign(n, Vec3::Zero());
  st.q.assign(n, Quat::Identity());
  st.v.assign(n, Vec3::Zero());
  st.w.assign(n, Vec3::Zero());
  st.u_seen.assign(n, Vec3::Zero());
  st.type.assign(n, 0);
  st.status.assign(n, BodyStatus::Moving);
  st.t_stop.assign(n, 0);
  st.reason.assign(n, "");
  st.history_offset.assign(n, State::kNoHistory);
  st.contact.assign(n, ContactState::Flying);
  st.rest_steps.assign(n, 0);
  st.impacts.assign(n, 0);
  st.t_touch.assign(n, 0);
  st.x_touch.assign(n, Vec3::Zero());
  st.hidden.assign(n, 0);
  if (watches) st.watch.assign(n, GustWatch{});
  return st;
}

// The running build's fingerprint is the build-id the linker wrote into it, as readelf reads it
// from the file
TEST(Checkpoint, TheChecksumIsFnv1a64) {
  // the published test vectors of FNV-1a 64 (offset basis 14695981039346656037), fed whole and
  // in pieces
  auto fnv = [](const std::string& s) {
    Fnv64 f;
    f.add(s.data(), s.size());
    return f.h;
  };
  EXPECT_EQ(fnv(""), 0xcbf29ce484222325ull);
  EXPECT_EQ(fnv("a"), 0xaf63dc4c8601ec8cull);
  EXPECT_EQ(fnv("foobar"), 0x85944171f73967e8ull);
  Fnv64 pieces;
  pieces.add("foo", 3);
  pieces.add("bar", 3);
  EXPECT_EQ(pieces.h, fnv("foobar"));
}

TEST(Checkpoint, TheBuildFingerprintIsTheLinkersBuildId) {
  std::string readelf;
  FILE* p = popen("readelf -n /proc/$PPID/exe 2>/dev/null", "r");
  ASSERT_NE(p, nullptr);
  char line[512];
  while (std::fgets(line, sizeof line, p)) readelf += line;
  pclose(p);
  const size_t at = readelf.find("Build ID: ");
  ASSERT_NE(at, std::string::npos) << "readelf found no build-id:\n" << readelf;
  std::string id = readelf.substr(at + 10);
  id = id.substr(0, id.find_first_of(" \n"));
  ASSERT_GE(id.size(), 16u);
  EXPECT_EQ(build_fingerprint(), "gnu-build-id:" + id);
  EXPECT_EQ(build_fingerprint(), build_fingerprint());
}

TEST(Checkpoint, KeepsTheSleepersGustWatches) {
  const std::string path = ::testing::TempDir() + "/watch.ckpt";
  const CheckpointId id{"build", "scene", 1, "scene.json"};
  const auto none_out = [](BinaryOut&) {};
  const auto none_in = [](BinaryIn&) {};
  State st = bodies(3, true);
  st.status[1] = BodyStatus::Sleeping;
  st.t_stop[1] = 2.468;
  GustWatch& w = st.watch[1];
  w.u = Vec3(0.1, -0.2, 0.3);
  w.ua = -0.25;
  w.gust = 0.7;
  w.start = 1200;
  w.step = 1234;
  w.wake = 5678;
  w.valid = 1;
  write_checkpoint(path, id, 0, st, RunStats{}, none_out);
  State back = bodies(3, true);
  RunStats stats;
  read_checkpoint(path, id, 0, &back, &stats, none_in);
  ASSERT_EQ(back.watch.size(), 3u);
  EXPECT_EQ(back.status[1], BodyStatus::Sleeping);
  EXPECT_EQ(back.watch[1].u, w.u);
  EXPECT_EQ(back.watch[1].gust, 0.7);
  EXPECT_EQ(back.watch[1].ua, -0.25);
  EXPECT_EQ(back.watch[1].start, 1200u);
  EXPECT_EQ(back.watch[1].step, 1234u);
  EXPECT_EQ(back.watch[1].wake, 5678u);
  EXPECT_EQ(back.watch[1].valid, 1);
  EXPECT_EQ(back.watch[0].valid, 0);
  EXPECT_EQ(back.watch[0].wake, GustWatch::kNever);

  // a run without contacts keeps no watches, and its checkpoint reads back without any
  write_checkpoint(path, id, 0, bodies(3, false), RunStats{}, none_out);
  State plain = bodies(3, true);
  read_checkpoint(path, id, 0, &plain, &stats, none_in);
  EXPECT_TRUE(plain.watch.empty());
  std::remove(path.c_str());
}

// The contact impulses between bodies (State::pair_impulses, the next step's warm start) go
// through a checkpoint bitwise; ones that name a body the run has not, or out of order, or not
// pushing, are refused: a resumed run would start from impulses no run left
TEST(Checkpoint, KeepsTheContactImpulsesBetweenBodies) {
  const std::string path = ::testing::TempDir() + "/impulses.ckpt";
  const CheckpointId id{"build", "scene", 1, "scene.json"};
  const auto none_out = [](BinaryOut&) {};
  const auto none_in = [](BinaryIn&) {};
  auto impulse = [](uint32_t a, uint32_t b, double jn) {
    PairImpulse p;
    p.a = a, p.b = b, p.jn = jn;
    for (int e = 0; e < 3; ++e) p.r[e] = 0.01 * (e + 1) + jn, p.jt[e] = -0.1 * jn * (e + 1);
    return p;
  };
  State st = bodies(3, true);
  st.pair_impulses = {impulse(0, 1, 0.25), impulse(0, 1, 0.5), impulse(0, PairImpulse::kSurface, 1.5),
                      impulse(1, 2, 1e-300)};
  write_checkpoint(path, id, 0, st, RunStats{}, none_out);
  State back = bodies(3, true);
  RunStats stats;
  read_checkpoint(path, id, 0, &back, &stats, none_in);
  ASSERT_EQ(back.pair_impulses.size(), 4u);
  for (size_t k = 0; k < 4; ++k)
    EXPECT_EQ(std::memcmp(&back.pair_impulses[k], &st.pair_impulses[k], sizeof(PairImpulse)), 0)
        << k;
  auto refused = [&](const State& bad) {
    write_checkpoint(path, id, 0, bad, RunStats{}, none_out);
    State r = bodies(3, true);
    try {
      read_checkpoint(path, id, 0, &r, &stats, none_in);
    } catch (const Error& e) {
      EXPECT_EQ(e.code(), ExitCode::BadInput);
      return std::string(e.what());
    }
    return std::string();
  };
  State bad = st;
  bad.pair_impulses[3].b = 3;  // a body the run has not
  EXPECT_NE(refused(bad).find("contact impulse 3"), std::string::npos) << refused(bad);
  bad = st;
  std::swap(bad.pair_impulses[2], bad.pair_impulses[3]);  // out of order
  EXPECT_NE(refused(bad).find("contact impulse 3"), std::string::npos) << refused(bad);
  bad = st;
  bad.pair_impulses[1].b = 0;  // a body with itself
  EXPECT_NE(refused(bad).find("contact impulse 1"), std::string::npos) << refused(bad);
  bad = st;
  bad.pair_impulses[0].jn = 0;  // not pushing
  EXPECT_NE(refused(bad).find("contact impulse 0"), std::string::npos) << refused(bad);
  bad = st;
  bad.pair_impulses[2].jt[1] = std::nan("");
  EXPECT_NE(refused(bad).find("contact impulse 2"), std::string::npos) << refused(bad);
  std::remove(path.c_str());
}

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

void put(const std::string& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
}

// read_checkpoint's error message, or "" when it reads the file
std::string read_error(const std::string& path) {
  const CheckpointId id{"build", "scene", 1, "scene.json"};
  State back = bodies(3, true);
  RunStats stats;
  try {
    read_checkpoint(path, id, 0, &back, &stats, [](BinaryIn& in) {
      std::string extra;
      in.str(&extra);
    });
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ExitCode::BadInput) << e.what();
    return e.what();
  }
  return "";
}

// A checkpoint ends in a checksum of everything before it. One flipped bit anywhere
// (the header, the bodies' state, the writer's part, the checksum itself) and any cut is
// refused with exit 3, the bodies' data included (it would resume into other results).
TEST(Checkpoint, AnyFlippedBitOrCutIsRefused) {
  const std::string path = ::testing::TempDir() + "/flip.ckpt";
  const CheckpointId id{"build", "scene", 1, "scene.json"};
  State st = bodies(3, true);
  st.x[1] = Vec3(0.25, -1.5, 3.0);
  st.v[2] = Vec3(1, 2, 3);
  write_checkpoint(path, id, 0, st, RunStats{}, [](BinaryOut& out) { out.str("the writer"); });
  ASSERT_EQ(read_error(path), "");
  const std::string good = slurp(path);
  ASSERT_GT(good.size(), 200u);
  size_t refused = 0, tried = 0;
  for (size_t at = 0; at < good.size(); at += 7) {
    std::string bad = good;
    bad[at] ^= char(1 << (at % 8));
    put(path, bad);
    const std::string err = read_error(path);
    ++tried;
    if (!err.empty()) ++refused;
    else ADD_FAILURE() << "a bit flipped at byte " << at << " of " << good.size() << " was read";
  }
  EXPECT_EQ(refused, tried);
  for (const size_t cut : {size_t(1), size_t(8), good.size() / 2, good.size() - 9}) {
    put(path, good.substr(0, good.size() - cut));
    EXPECT_NE(read_error(path), "") << "cut by " << cut << " bytes";
  }
  put(path, good + "x");
  EXPECT_NE(read_error(path), "") << "a byte appended";
  // the body data: the message says checksum
  std::string bad = good;
  bad[good.size() / 2] ^= 0x10;
  put(path, bad);
  EXPECT_NE(read_error(path).find("checksum mismatch"), std::string::npos) << read_error(path);
  std::remove(path.c_str());
}

// A length written wrong under a checksum that matches (what no flipped bit gives, but a
// checksum proves nothing about a writer's mistakes): refused with exit 3, before anything the
// size of the length is allocated, whichever array it is
TEST(Checkpoint, ALengthBeyondTheFileIsRefusedWithoutAllocatingIt) {
  const std::string path = ::testing::TempDir() + "/length.ckpt";
  const CheckpointId id{"build", "scene", 1, "scene.json"};
  write_checkpoint(path, id, 0, bodies(3, true), RunStats{},
                   [](BinaryOut& out) { out.str("the writer"); });
  const std::string good = slurp(path);
  // the arrays' lengths: the build's (after the magic), the positions' (after the header)
  const size_t build_length = 8;
  const size_t x_length = 8 + 8 + id.build.size() + 8 + id.scene.size() + 4 + 4 + 8 + 8;
  for (const size_t at : {build_length, x_length}) {
    for (const uint64_t n : {uint64_t(1) << 36, uint64_t(good.size())}) {
      std::string bad = good;
      std::memcpy(&bad[at], &n, sizeof n);
      Fnv64 sum;
      sum.add(bad.data(), bad.size() - 8);
      std::memcpy(&bad[bad.size() - 8], &sum.h, 8);
      put(path, bad);
      const std::string err = read_error(path);
      EXPECT_NE(err.find("corrupt checkpoint (an array of " + std::to_string(n)), std::string::npos)
          << "length " << n << " at byte " << at << ": " << err;
    }
  }
  std::remove(path.c_str());
}

// A checkpoint of the format before checksums (LRIGCKP2) is refused, saying why: it cannot be
// verified (docs/cli.md, "Checkpoints and --resume")
TEST(Checkpoint, AnUncheckedOlderFormatIsRefusedSayingWhy) {
  const std::string path = ::testing::TempDir() + "/old.ckpt";
  put(path, std::string("LRIGCKP2") + std::string(200, '\0'));
  const std::string err = read_error(path);
  EXPECT_NE(err.find("format 2"), std::string::npos) << err;
  EXPECT_NE(err.find("no checksum"), std::string::npos) << err;
  std::remove(path.c_str());
}

// A checkpoint file that is not there says "missing", not "cannot be read"
TEST(Checkpoint, AMissingFileSaysMissing) {
  const std::string path = ::testing::TempDir() + "/nowhere/rank0.step40.bin";
  const std::string err = read_error(path);
  EXPECT_NE(err.find("missing"), std::string::npos) << err;
  EXPECT_EQ(err.find("cannot be read"), std::string::npos) << err;
}

}  // namespace
}  // namespace lrigid
