// What the batched steps share (integrate/batch_lanes.h): the block driver drive_block and the
// lane stages. The driver hands a lane the loops leave to the scalar step, which then takes it
// to the bit, and stops lanes as the scalar loop stops bodies; a block ends where its bodies end
// stepped one by one (spheres on the isotropic M, plates on the diagonal one, double and float); the sample stage is the
// field's sample, the normals are the scalar step's, the OU update is the identity without seen
// turbulence, and an outcome names a lane's first non-finite part before its leaving the fluid.
// (The header has internal linkage: this file compiles its own copy of what it calls.)
#include "integrate/batch_lanes.h"

#include <gtest/gtest.h>

#include <cstring>
#include <limits>
#include <numeric>
#include <random>
#include <string>
#include <vector>

#include "effects/mean_flow.h"
#include "integrate/rigid_batch.h"
#include "integrate/simulation.h"
#include "support/batch_compare.h"
#include "support/fixture.h"

namespace lrigid {
namespace {

constexpr double kNu = 1.5e-5;

// A block's lanes as whole BodyStates, for a step written here (the driver's interface: load,
// store, rest, velocity(), w and q; the positions also in Samples::x, where the sample stage
// reads them)
struct BodyLanes : Samples<double> {
  BodyState b[kBatch];
  double v[3][kBatch] = {}, w[3][kBatch] = {}, q[4][kBatch] = {};
  void load(int j, const BodyState& s) {
    b[j] = s;
    b[j].history = nullptr;
    for (int a = 0; a < 3; ++a) x[a][j] = s.x[a], v[a][j] = s.v[a], w[a][j] = s.w[a];
    q[0][j] = s.q.w(), q[1][j] = s.q.x(), q[2][j] = s.q.y(), q[3][j] = s.q.z();
  }
  void store(int j, BodyState* s) const { *s = b[j]; }
  void rest(int j) {
    b[j].v.setZero();
    b[j].w.setZero();
    for (int a = 0; a < 3; ++a) v[a][j] = w[a][j] = 0;
  }
  double (*velocity())[kBatch] { return v; }
};

// Body i of two States bitwise the same (a NaN left in place compares equal), with the same
// status, stop time and reason.
::testing::AssertionResult same_body(const State& a, const State& b, size_t i) {
  auto bits = [](const auto& x, const auto& y) {
    return std::memcmp(&x, &y, sizeof(x)) == 0;
  };
  if (a.status[i] != b.status[i] || a.reason[i] != b.reason[i] ||
      !bits(a.t_stop[i], b.t_stop[i]))
    return ::testing::AssertionFailure()
           << "body " << i << ": " << body_status_name(a.status[i]) << " at " << a.t_stop[i]
           << " (" << a.reason[i] << ") against " << body_status_name(b.status[i]) << " at "
           << b.t_stop[i] << " (" << b.reason[i] << ")";
  if (!bits(a.x[i], b.x[i]) || !bits(a.q[i], b.q[i]) || !bits(a.v[i], b.v[i]) ||
      !bits(a.w[i], b.w[i]) || !bits(a.u_seen[i], b.u_seen[i]))
    return ::testing::AssertionFailure()
           << "body " << i << " at " << a.x[i].transpose() << " against " << b.x[i].transpose();
  return ::testing::AssertionSuccess();
}

// glass beads in the sheared wind grid (support/batch_compare.h), no ground: they leave the
// grid through its floor and hit its block
Scene bead_scene(int count) {
  Scene s = test::sphere_scene(2.5e-4, 2500, 1.2, kNu, count);
  s.effects = test::effects({Effect::Gravity, Effect::Buoyancy, Effect::Drag, Effect::AddedMass,
                             Effect::MeanFlow, Effect::Turbulence});
  batch_test::release_in_wind_grid(&s, 7);
  return s;
}

// The driver with a step written here: the even lanes step themselves (step_body, committed as
// the loops commit a lane), the odd ones report kScalar, what the loops leave to the scalar
// step. Every lane must end bitwise where the scalar loop (simulate, "batched": false) ends its
// body, with the same status, stop time and reason (bodies leave the grid, two fail on a
// non-finite state), and the driver counts the handed steps and the steps taken as the loop
// does.
TEST(BatchLanes, ALaneTheLoopsLeaveIsTheScalarStepsToTheBit) {
  const int count = 20;  // lanes past 20 repeat body 0 and stay idle
  Scene s = bead_scene(count);
  s.has_ground = false;
  Model m = test::compile(s, batch_test::wind_grid(kNu));
  m.batched = false;
  // (no contacts: the step written here does not keep the start of the step a contact needs)
  ASSERT_FALSE(m.contacts());
  State start = initial_state(m, s);
  // a handed lane and one that steps itself fail
  start.v[3].x() = std::numeric_limits<double>::quiet_NaN();
  start.w[4].y() = std::numeric_limits<double>::quiet_NaN();
  const uint64_t last = static_cast<uint64_t>(std::llround(m.duration / m.dt));

  State scalar = start;
  const RunStats loop = simulate(m, &scalar, RunOptions{});

  const BodyType& type = m.types[0];
  FieldConsts fc;
  set_field_consts(m, type, &fc);
  uint64_t handed = 0;
  auto step = [&](auto, BodyLanes* lanes, uint64_t k, int* outcome, int* landed) {
    const double t = static_cast<double>(k) * m.dt;
    for (int j = 0; j < lanes->width; ++j) {
      outcome[j] = kOk;
      landed[j] = 0;
      if (!lanes->live[j]) continue;
      if (j % 2 == 1) {
        outcome[j] = kScalar;
        ++handed;
        continue;
      }
      BodyState b = lanes->b[j];
      std::string reason;
      const StepOutcome out = step_body(m, type, lanes->body[j], k, t, &b, &reason);
      if (out == StepOutcome::Ok) {
        lanes->load(j, b);
      } else if (out == StepOutcome::Exited) {
        outcome[j] = kOutside;
      } else {
        int part = 0;
        while (part < 4 && reason != std::string("non-finite ") + kNonFiniteName[part]) ++part;
        outcome[j] = kNonFinite + part;
      }
    }
  };
  std::vector<uint32_t> body(count);
  std::iota(body.begin(), body.end(), 0u);
  State block = start;
  const BlockStats stats = drive_block<double, BodyLanes>(m, type, fc, false, &block, body.data(),
                                                          count, 0, last, step);
  for (size_t i = 0; i < size_t(count); ++i) EXPECT_TRUE(same_body(block, scalar, i));
  EXPECT_EQ(stats.body_steps, loop.body_steps);
  EXPECT_EQ(stats.scalar_steps, handed);
  // the scene takes each path: bodies still moving, leaving the grid, failing; odd and even
  EXPECT_GT(batch_test::count(scalar, BodyStatus::Moving), 0u);
  EXPECT_GT(batch_test::count(scalar, BodyStatus::Exited), 1u);
  EXPECT_EQ(batch_test::count(scalar, BodyStatus::Failed), 2u);
  EXPECT_NE(scalar.reason[3].find("non-finite"), std::string::npos) << scalar.reason[3];
  EXPECT_NE(scalar.reason[4].find("non-finite"), std::string::npos) << scalar.reason[4];
  bool exited[2] = {false, false};
  for (size_t i = 0; i < size_t(count); ++i)
    exited[i % 2] = exited[i % 2] || scalar.status[i] == BodyStatus::Exited;
  EXPECT_TRUE(exited[0] && exited[1]) << "lanes that step themselves and handed lanes leave";
}

// The scene's 32 bodies in one block, and each body alone in a block of its own (lane 0, the
// others idle): the same final states to the bit, the same stops, the same counts. A lane's
// arithmetic does not depend on its place in the block nor on how many lanes the block steps.
void expect_block_is_one_by_one(const Scene& s, const FluidField& field, Precision p,
                                BlockStats (*advance)(const Model&, const BodyType&, State*,
                                                      const uint32_t*, int, uint64_t, uint64_t,
                                                      StretchSweep*)) {
  Model m = test::compile(s, field);
  m.precision = p;
  ASSERT_NE(step_kind(m, m.types[0], nullptr), StepKind::Scalar);
  const State start = initial_state(m, s);
  ASSERT_EQ(start.size(), size_t(kBatch));
  const uint64_t last = static_cast<uint64_t>(std::llround(m.duration / m.dt));
  std::vector<uint32_t> body(kBatch);
  std::iota(body.begin(), body.end(), 0u);
  State block = start, alone = start;
  const BlockStats all = advance(m, m.types[0], &block, body.data(), kBatch, 0, last, nullptr);
  BlockStats sum;
  for (int j = 0; j < kBatch; ++j) {
    const BlockStats one = advance(m, m.types[0], &alone, &body[j], 1, 0, last, nullptr);
    sum.body_steps += one.body_steps;
    sum.scalar_steps += one.scalar_steps;
    sum.newton_steps += one.newton_steps;
  }
  for (size_t i = 0; i < size_t(kBatch); ++i) EXPECT_TRUE(same_body(block, alone, i));
  EXPECT_EQ(all.body_steps, sum.body_steps);
  EXPECT_EQ(all.scalar_steps, sum.scalar_steps);
  EXPECT_EQ(all.newton_steps, sum.newton_steps);
  EXPECT_GT(all.body_steps, 0u);
}

TEST(BatchLanes, ABlockEndsWhereItsBodiesEndSteppedOneByOne) {
  const FluidField field = batch_test::wind_grid(kNu);
  // beads, landing on the way (strang)
  Scene beads = bead_scene(kBatch);
  beads.integrator = Integrator::Strang;
  // tissue squares spinning fast at a coarse step: stiff drag (Newton in the loops) and free
  // flows the loops hand to the scalar step (splitting)
  Scene tissue = bead_scene(kBatch);
  tissue.bodies[0].shape = Shape::box(0.03, 0.03, 5e-5);
  tissue.bodies[0].density = 200;
  tissue.effects.add(Effect::Lift);
  tissue.integrator = Integrator::Splitting;
  tissue.dt = 0.02;
  tissue.duration = 0.1;
  tissue.bodies[0].angular_velocity = Vec3(40, -25, 10);
  for (const Precision p : {Precision::Double, Precision::Float}) {
    SCOPED_TRACE(p == Precision::Double ? "double" : "float");
    {
      SCOPED_TRACE("beads");
      expect_block_is_one_by_one(beads, field, p, advance_rigid_block);
    }
    {
      SCOPED_TRACE("tissue");
      expect_block_is_one_by_one(tissue, field, p, advance_rigid_block);
    }
  }
  // the scenes take those paths
  const Model mb = test::compile(beads, field);
  State sb = initial_state(mb, beads);
  simulate(mb, &sb, RunOptions{});
  EXPECT_GT(batch_test::count(sb, BodyStatus::Landed), 0u);
  EXPECT_GT(batch_test::count(sb, BodyStatus::Moving), 0u);
  const Model mt = test::compile(tissue, field);
  State st = initial_state(mt, tissue);
  const RunStats stats = simulate(mt, &st, RunOptions{});
  EXPECT_GT(stats.scalar_handoffs, 0u) << "the scene hands lanes to the scalar step";
  EXPECT_GT(stats.newton_steps, 0u) << "the loops run Newton themselves";
}

// The sample stage (sample_lanes) at a block's positions, in the steady grid and in the gusting
// series (frames blended at the sample's time), with the art scales: inside where the field's
// sample is, and there the same U, grad U, its material derivative, the Langevin coefficients
// and grad sigma^2 as the field's sample (effects/evaluate.h sample_fluid).
TEST(BatchLanes, TheSampleOfTheLanesIsTheFieldsSample) {
  for (const bool gusty : {false, true}) {
    SCOPED_TRACE(gusty ? "gusting series" : "steady grid");
    Scene s = bead_scene(1);
    s.mean_flow_scale = 1.3;
    s.turbulence_scale = 0.8;
    const Model m =
        test::compile(s, gusty ? batch_test::gusty_wind_grid(kNu) : batch_test::wind_grid(kNu));
    FieldConsts fc;
    set_field_consts(m, m.types[0], &fc);
    ASSERT_TRUE(fc.grid);
    std::mt19937_64 gen(3);
    // the grid's box is [-6, 6] x [-4, 4] x [-0.5, 5.5], its solid block |x|, |y| <= 1, z <= 2
    std::uniform_real_distribution<double> ux(-6.5, 6.5), uy(-4.5, 4.5), uz(-1.0, 6.0);
    const double t = 0.42;
    int inside = 0;
    for (int round = 0; round < 8; ++round) {
      Samples<double> lanes{};
      if (gusty) lanes.frames = m.field.frames_at(t);
      for (int j = 0; j < kBatch; ++j) {
        lanes.x[0][j] = ux(gen), lanes.x[1][j] = uy(gen), lanes.x[2][j] = uz(gen);
        if (j == 0) lanes.x[0][j] = 0.5, lanes.x[1][j] = 0.5, lanes.x[2][j] = 1.0;  // in the block
      }
      sample_lanes(fc, lanes.x, &lanes);
      for (int j = 0; j < kBatch; ++j) {
        const Vec3 x(lanes.x[0][j], lanes.x[1][j], lanes.x[2][j]);
        FluidSample fs;
        const bool in = sample_fluid(m, x, t, true, &fs);
        ASSERT_EQ(lanes.inside[j] != 0, in) << x.transpose();
        if (!in) continue;
        ++inside;
        const double tol = 1e-12;
        for (int a = 0; a < 3; ++a) {
          EXPECT_NEAR(lanes.U[a][j], fs.U[a], tol * (1 + fs.U.norm())) << x.transpose();
          EXPECT_NEAR(lanes.gs[a][j], fs.grad_sigma2[a], tol * (1 + fs.grad_sigma2.norm()));
          const Vec3 acc = mean_flow_acceleration(fs);
          EXPECT_NEAR(lanes.acc[a][j], acc[a], tol * (1 + acc.norm())) << x.transpose();
          for (int b = 0; b < 3; ++b)
            EXPECT_NEAR(lanes.gU[a * 3 + b][j], fs.grad_U(a, b), tol * (1 + fs.grad_U.norm()));
        }
        EXPECT_NEAR(lanes.alpha[j], fs.alpha, tol * fs.alpha);
        EXPECT_NEAR(lanes.beta[j], fs.beta, tol * fs.beta);
        EXPECT_NEAR(lanes.sigma2[j], fs.sigma2, tol * fs.sigma2);
      }
    }
    EXPECT_GT(inside, 8 * kBatch / 4);
    EXPECT_LT(inside, 8 * kBatch);
  }
}

// The normals of a lane are its body's at that step, as the scalar step draws them
// (NormalStream keyed by seed, body and step): the Strang half steps' (n_c +- n_{6+c}) / sqrt 2,
// or the whole step's n_c; none without the seen turbulence.
TEST(BatchLanes, EachLanesNormalsAreTheScalarStepsForItsBodyAndStep) {
  FieldConsts fc;
  fc.turb = true;
  fc.tu = 1;
  fc.seed = 0x0123456789abcdefULL;
  Samples<double> lanes{};
  for (int j = 0; j < kBatch; ++j) lanes.body[j] = 1000u * uint32_t(j) + 7u;
  for (const uint64_t step : {uint64_t(0), uint64_t(1), uint64_t(123456789012)}) {
    alignas(64) double z1[3][kBatch], z2[3][kBatch], whole[3][kBatch], unused[3][kBatch];
    lane_normals(fc, lanes, step, z1, z2);
    lane_normals<double, true>(fc, lanes, step, whole, unused);
    for (int j = 0; j < kBatch; ++j) {
      double n[12];
      NormalStream(fc.seed, lanes.body[j], step).normals(n);
      for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(z1[c][j], (n[c] + n[6 + c]) * M_SQRT1_2, 1e-14) << "lane " << j;
        EXPECT_NEAR(z2[c][j], (n[c] - n[6 + c]) * M_SQRT1_2, 1e-14) << "lane " << j;
        EXPECT_NEAR(whole[c][j], n[c], 1e-14) << "lane " << j;
      }
    }
  }
  fc.turb = false;
  fc.tu = 0;
  alignas(64) double z1[3][kBatch], z2[3][kBatch];
  lane_normals(fc, lanes, 5, z1, z2);
  for (int c = 0; c < 3; ++c)
    for (int j = 0; j < kBatch; ++j) {
      EXPECT_EQ(z1[c][j], 0.0);
      EXPECT_EQ(z2[c][j], 0.0);
    }
}

// The OU update of a lane's seen fluctuation: us <- decay us + h (1/2 grad sigma^2 + us (V .
// grad sigma^2) / (2 sigma^2)) + noise z with Thomson's drift, without it the same less the
// drift; along a crossing-trajectory drift direction the along pair (decay_a, noise_a) in place
// of (decay, noise); without the seen turbulence (factor 0) the identity, exactly, whatever the
// coefficients.
TEST(BatchLanes, TheOUUpdateOfALaneIsThomsonsAndTheIdentityWithoutSeenTurbulence) {
  Samples<double> lanes{};
  alignas(64) double z[3][kBatch] = {};
  const int j = 5;
  lanes.sigma2[j] = 0.04;
  const double gs[3] = {0.01, -0.02, 0.03}, V[3] = {1.5, -0.5, 0.25}, z0[3] = {0.7, -1.2, 0.4};
  for (int a = 0; a < 3; ++a) lanes.gs[a][j] = gs[a], z[a][j] = z0[a];
  const double decay = 0.9, noise = 0.05, h = 0.01, u0[3] = {0.1, 0.2, -0.3};
  const double proj = (V[0] * gs[0] + V[1] * gs[1] + V[2] * gs[2]) / (2 * 0.04);
  const double none[3] = {0, 0, 0}, down[3] = {0, 0, -1};
  for (const double wm : {1.0, 0.0}) {
    double us[3] = {u0[0], u0[1], u0[2]};
    lane_ou_update(1.0, wm, decay, noise, decay, noise, none, h, lanes, z, j, V, us);
    for (int a = 0; a < 3; ++a)
      EXPECT_NEAR(us[a], decay * u0[a] + wm * h * (0.5 * gs[a] + u0[a] * proj) + noise * z0[a],
                  1e-15);
    // a drift along -z: z takes 0.8 and 0.07
    double ud[3] = {u0[0], u0[1], u0[2]};
    lane_ou_update(1.0, wm, decay, noise, 0.8, 0.07, down, h, lanes, z, j, V, ud);
    for (int a = 0; a < 3; ++a)
      EXPECT_NEAR(ud[a],
                  (a == 2 ? 0.8 : decay) * u0[a] + wm * h * (0.5 * gs[a] + u0[a] * proj) +
                      (a == 2 ? 0.07 : noise) * z0[a],
                  1e-15);
  }
  double us[3] = {u0[0], u0[1], u0[2]};
  lane_ou_update(0.0, 1.0, decay, noise, 0.8, 0.07, down, h, lanes, z, j, V, us);
  for (int a = 0; a < 3; ++a) EXPECT_EQ(us[a], u0[a]);
}

// A lane's outcome: a non-finite part fails it, named as step_body names the first (position,
// orientation, velocity, angular velocity, seen turbulent velocity), before its sample's being
// outside exits it (a NaN position samples as outside); a lane handed to the scalar step is that
// step's whatever its state.
TEST(BatchLanes, AnOutcomeNamesTheFirstNonFinitePartBeforeLeavingTheFluid) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  double part[5][4] = {{1, 2, 3, 0}, {1, 0, 0, 0}, {0.1, 0.2, 0.3, 0}, {1, -1, 2, 0},
                       {0.01, 0, 0, 0}};
  auto outcome = [&](bool inside, bool scalar) {
    return decode_outcome(
        outcome_bits(part[0], part[1], part[2], part[3], part[4], inside, scalar));
  };
  EXPECT_EQ(outcome(true, false), kOk);
  EXPECT_EQ(outcome(false, false), kOutside);
  EXPECT_EQ(outcome(true, true), kScalar);
  for (int first = 4; first >= 0; --first) {
    part[first][first == 1 ? 3 : 1] = nan;  // (the last component of the orientation)
    EXPECT_EQ(outcome(false, false), kNonFinite + first) << kNonFiniteName[first];
    EXPECT_EQ(outcome(true, false), kNonFinite + first);
    EXPECT_EQ(outcome(false, true), kScalar);
  }
}

// A block steps its lanes up to the last live one rounded up to whole 512-bit vectors: 8
// doubles, 16 floats.
TEST(BatchLanes, ABlockStepsWholeVectorsUpToItsLastLiveLane) {
  for (int hi = 0; hi <= kBatch; ++hi) {
    EXPECT_EQ(lane_width<double>(hi), (hi + 7) / 8 * 8) << hi;
    EXPECT_EQ(lane_width<float>(hi), (hi + 15) / 16 * 16) << hi;
  }
}

}  // namespace
}  // namespace lrigid
