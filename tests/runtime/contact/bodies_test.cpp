// Contacts between bodies (contact/bodies.h, island.h) against closed forms: two spheres head-on
// and off-centre with restitution e, Newton's cradle, a stack of boxes standing, a block sliding
// on a block, a heap of spheres on the ground; the same results for any thread count; the
// speculative stretches of several steps (integrate/simulation.cpp) give the lockstep's results to
// the bit (bodies far apart in a wind, a heap, sleeping bodies woken by a falling one).
#include "contact/bodies.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "compile/compile_model.h"
#include "contact/island.h"
#include "contact/pair_geometry.h"
#include "integrate/simulation.h"
#include "support/batch_compare.h"
#include "support/contact_scenes.h"
#include "support/fixture.h"

namespace lrigid {
namespace {

using test::kG;

BodySpec body(const std::string& name, const Shape& shape, double density, const Vec3& x,
              const Vec3& v, double e, double mu) {
  BodySpec b;
  b.name = name;
  b.shape = shape;
  b.density = density;
  b.position = x;
  b.velocity = v;
  b.contact.restitution = e;
  b.contact.friction = mu;
  return b;
}

BodySpec sphere_body(const std::string& name, double r, double density, const Vec3& x,
                     const Vec3& v, double e, double mu) {
  return body(name, Shape::sphere(r), density, x, v, e, mu);
}

// bodies in still air under the given gravity, no fluid forces, body contacts on
Scene pair_scene(std::vector<BodySpec> bodies, const Vec3& g, double dt, double duration) {
  Scene s = test::sphere_scene(0.01, 1000, 1.2, 1.5e-5);
  s.bodies = std::move(bodies);
  s.effects = test::effects({Effect::Gravity});
  s.gravity = g;
  s.dt = dt;
  s.duration = duration;
  s.body_contact = true;
  return s;
}

State run(const Model& m, const Scene& s, int threads = 1) {
  State st = initial_state(m, s);
  RunOptions o;
  o.threads = threads;
  simulate(m, &st, o);
  return st;
}

TEST(BodyContact, PairMaterialIsBox2dsMixingRule) {
  ContactParams a, b;
  a.restitution = 0.2, a.friction = 0.9, a.rolling_resistance = 0.01;
  b.restitution = 0.5, b.friction = 0.4, b.rolling_resistance = 0.05;
  const PairMaterial m = pair_material(a, b);
  EXPECT_DOUBLE_EQ(m.restitution, 0.5);
  EXPECT_DOUBLE_EQ(m.friction, std::sqrt(0.9 * 0.4));
  EXPECT_DOUBLE_EQ(m.rolling, 0.05);
}

// Head-on: u1' = (m1 u1 + m2 u2 - m2 e (u1 - u2)) / (m1 + m2), and the same for u2'.
TEST(BodyContact, TwoSpheresHeadOnLeaveWithNewtonsRestitution) {
  for (const double e : {0.0, 0.5, 1.0}) {
    for (const double rho2 : {1000.0, 3000.0}) {
      const double r = 0.01, u1 = 1.0, u2 = -0.5;
      Scene s = pair_scene({sphere_body("a", r, 1000, Vec3(-0.03, 0, 0), Vec3(u1, 0, 0), e, 0.3),
                            sphere_body("b", r, rho2, Vec3(0.03, 0, 0), Vec3(u2, 0, 0), e, 0.3)},
                           Vec3::Zero(), 1e-4, 0.05);
      const Model m = test::compile(s);
      const State st = run(m, s);
      const double m1 = m.types[0].mass, m2 = m.types[1].mass;
      const double a = (m1 * u1 + m2 * u2 - m2 * e * (u1 - u2)) / (m1 + m2);
      const double b = (m1 * u1 + m2 * u2 + m1 * e * (u1 - u2)) / (m1 + m2);
      EXPECT_NEAR(st.v[0].x(), a, 0.01 * std::abs(u1 - u2)) << "e " << e << " rho2 " << rho2;
      EXPECT_NEAR(st.v[1].x(), b, 0.01 * std::abs(u1 - u2)) << "e " << e << " rho2 " << rho2;
      // momentum exactly, no spin, no sideways motion
      EXPECT_NEAR(m1 * st.v[0].x() + m2 * st.v[1].x(), m1 * u1 + m2 * u2, 1e-9);
      EXPECT_LT(st.w[0].norm() + st.w[1].norm(), 1e-9);
      EXPECT_LT(std::abs(st.v[0].y()) + std::abs(st.v[0].z()), 1e-9);
      // they never sank into each other by more than one step's travel; flying apart (or
      // together at e = 0), nothing touches them: they are flying, not resting
      EXPECT_LT(deepest_pair_overlap(m, st), 1e-9);
      if (e > 0) {
        EXPECT_EQ(st.contact[0], ContactState::Flying) << "e " << e;
        EXPECT_EQ(st.contact[1], ContactState::Flying) << "e " << e;
      }
    }
  }
}

// Off-centre, frictionless: along the line of centres at contact the head-on rule, across it the
// velocities are unchanged. Sphere a moves along x towards b, which sits off its line by `off` in
// y; the contact normal from b to a is n = (-sqrt(4r^2 - off^2), -off, 0) / 2r.
TEST(BodyContact, OffCentreFrictionlessSpheresExchangeTheNormalPartOnly) {
  for (const double e : {0.3, 1.0}) {
    const double r = 0.01, off = 0.01, u = 1.0;
    Scene s = pair_scene({sphere_body("a", r, 1000, Vec3(-0.03, 0, 0), Vec3(u, 0, 0), e, 0.0),
                          sphere_body("b", r, 1000, Vec3(0.0, off, 0), Vec3::Zero(), e, 0.0)},
                         Vec3::Zero(), 1e-4, 0.05);
    const Model m = test::compile(s);
    const State st = run(m, s);
    const Vec3 n = Vec3(-std::sqrt(4 * r * r - off * off), -off, 0) / (2 * r);  // b towards a
    const Vec3 ua(u, 0, 0);
    const double un = ua.dot(n);  // < 0: approaching
    const Vec3 va = ua - (1 + e) / 2 * un * n, vb = (1 + e) / 2 * un * n;
    const Vec3 ga = st.q[0] * st.v[0], gb = st.q[1] * st.v[1];
    EXPECT_NEAR((ga - va).norm(), 0, 0.01 * u) << "e " << e << ": " << ga.transpose();
    EXPECT_NEAR((gb - vb).norm(), 0, 0.01 * u) << "e " << e << ": " << gb.transpose();
  }
}

// Newton's cradle: three equal spheres 1 mm apart in a row (the sequential-collision
// idealization), e = 1, no friction: the first one's momentum passes to the last.
TEST(BodyContact, NewtonsCradlePassesTheMomentumToTheLast) {
  const double r = 0.01, u = 0.5, gap = 0.001;
  Scene s = pair_scene(
      {sphere_body("a", r, 1000, Vec3(-(2 * r + gap), 0, 0), Vec3(u, 0, 0), 1, 0),
       sphere_body("b", r, 1000, Vec3(0, 0, 0), Vec3::Zero(), 1, 0),
       sphere_body("c", r, 1000, Vec3(2 * r + gap, 0, 0), Vec3::Zero(), 1, 0)},
      Vec3::Zero(), 1e-4, 0.05);
  const Model m = test::compile(s);
  const State st = run(m, s);
  EXPECT_NEAR(st.v[0].x(), 0, 0.01 * u);
  EXPECT_NEAR(st.v[1].x(), 0, 0.01 * u);
  EXPECT_NEAR(st.v[2].x(), u, 0.01 * u);
}

// 60 spheres dropped into a heap on the ground: no overlap deeper than 1 mm at any output, at
// rest at the end; the same run on 1 and 2 threads gives the same state bitwise.
TEST(BodyContact, AHeapOfSpheresRestsWithoutOverlapAndAnyThreadCountGivesTheSameRun) {
  BodySpec b = sphere_body("ball", 0.01, 1000, Vec3::Zero(), Vec3::Zero(), 0.2, 0.5);
  // gravel-like rolling resistance: with less, a ball resting on two others rolls them apart (the
  // wedge pushes each with 0.29 of its weight, the resistance holds mu_r times 1.5 of it)
  b.contact.rolling_resistance = 0.3;
  b.count = 60;
  b.spawn_in_box = true;
  b.box_lo = Vec3(-0.03, -0.03, 0.02);
  b.box_hi = Vec3(0.03, 0.03, 0.3);
  Scene s = pair_scene({b}, Vec3(0, 0, -kG), 1e-3, 3.0);
  s.has_ground = true;
  s.ground_z = 0;
  s.ground_contact = ContactMode::Collide;
  const Model m = test::compile(s);
  State st = initial_state(m, s);
  // in layers of 3 x 3, 2 mm apart, each layer shifted so that they fall onto each other
  for (size_t i = 0; i < st.size(); ++i) {
    const double layer = double(i / 9), shift = 0.005 * (i / 9 % 2 == 0 ? 1 : -1);
    st.x[i] = Vec3(-0.022 + 0.022 * double(i % 3) + shift, -0.022 + 0.022 * double(i / 3 % 3),
                   0.011 + 0.025 * layer);
  }
  State st2 = st;
  double worst = 0;
  RunOptions o;
  o.every = 0.05;
  o.threads = 1;
  o.on_output = [&](const State& x) { worst = std::max(worst, deepest_pair_overlap(m, x)); };
  simulate(m, &st, o);
  EXPECT_LT(worst, 1e-3);
  size_t still = 0;
  std::string moving;
  for (size_t i = 0; i < st.size(); ++i) {
    const bool s_i = st.status[i] == BodyStatus::Sleeping || st.contact[i] == ContactState::Resting;
    still += s_i;
    if (!s_i)
      moving += " " + std::to_string(i) + ": z " + std::to_string(st.x[i].z()) + " v " +
                std::to_string(st.v[i].norm()) + " w " + std::to_string(st.w[i].norm()) + ";";
  }
  EXPECT_EQ(still, st.size()) << "not at rest:" << moving;
  double zmax = 0;
  for (size_t i = 0; i < st.size(); ++i) zmax = std::max(zmax, st.x[i].z());
  EXPECT_GT(zmax, 0.02) << "a heap, not one layer";
  // the first 0.5 s again on 1 and 2 threads
  State st1 = st2;
  Scene s2 = s;
  s2.duration = 0.5;
  const Model m2 = test::compile(s2);
  RunOptions o1;
  o1.threads = 1;
  simulate(m2, &st1, o1);
  RunOptions o2;
  o2.threads = 2;
  simulate(m2, &st2, o2);
  for (size_t i = 0; i < st.size(); ++i) {
    EXPECT_EQ(st1.x[i], st2.x[i]) << i;
    EXPECT_EQ(st1.v[i], st2.v[i]) << i;
  }
}

BodySpec box_body(const std::string& name, const Vec3& size, double density, const Vec3& x,
                  const Vec3& v, double e, double mu) {
  return body(name, Shape::box(size.x(), size.y(), size.z()), density, x, v, e, mu);
}

// Five boxes stacked on the ground stand: after 10 s no box has moved by 0.1 mm.
TEST(BodyContact, AStackOfFiveBoxesStands) {
  std::vector<BodySpec> boxes;
  for (int k = 0; k < 5; ++k)
    boxes.push_back(box_body("box" + std::to_string(k), Vec3(0.04, 0.03, 0.02), 1000,
                             Vec3(0, 0, 0.01 + 0.02 * k), Vec3::Zero(), 0.0, 0.5));
  Scene s = pair_scene(boxes, Vec3(0, 0, -kG), 1e-3, 10.0);
  s.has_ground = true;
  s.ground_z = 0;
  s.ground_contact = ContactMode::Collide;
  const Model m = test::compile(s);
  State st = initial_state(m, s);
  const std::vector<Vec3> x0 = st.x;
  double worst = 0;
  RunOptions o;
  o.every = 0.1;
  o.on_output = [&](const State& x) {
    for (size_t i = 0; i < x.size(); ++i) worst = std::max(worst, (x.x[i] - x0[i]).norm());
  };
  simulate(m, &st, o);
  EXPECT_LT(worst, 1e-4);
  for (size_t i = 0; i < st.size(); ++i) EXPECT_EQ(st.status[i], BodyStatus::Sleeping) << i;
}

// A block sliding on a heavier block that the ground holds: it decelerates at mu g and stops
// after v0^2 / (2 mu g); the lower block stays where it is.
TEST(BodyContact, ABlockSlidingOnABlockStopsAfterV0SquaredOverTwoMuG) {
  const double mu = 0.4, v0 = 0.5;
  Scene s = pair_scene(
      {box_body("base", Vec3(0.12, 0.1, 0.02), 5000, Vec3(0, 0, 0.01), Vec3::Zero(), 0, mu),
       box_body("slider", Vec3(0.04, 0.04, 0.02), 1000, Vec3(-0.03, 0, 0.03), Vec3(v0, 0, 0), 0,
                mu)},
      Vec3(0, 0, -kG), 1e-3, 0.5);
  s.has_ground = true;
  s.ground_z = 0;
  s.ground_contact = ContactMode::Collide;
  const Model m = test::compile(s);
  State st = initial_state(m, s);
  simulate(m, &st, RunOptions{});
  const double d = v0 * v0 / (2 * mu * kG);
  EXPECT_NEAR(st.x[1].x() - (-0.03), d, 0.02 * d);
  EXPECT_NEAR(st.x[1].z(), 0.03, 1e-4);
  EXPECT_LT((st.x[0] - Vec3(0, 0, 0.01)).norm(), 1e-4);
}

// A box on the slope of a heavy wedge lying on the ground (bodies that never sleep here): below
// the friction angle atan(mu) = 26.6 deg static friction holds it with no creep; above it, it
// slides down.
TEST(BodyContact, ABoxOnAWedgeHoldsBelowTheFrictionAngleWithoutCreep) {
  const double mu = 0.5, L = 0.4, W = 0.2, hz = 0.01;
  for (const double deg : {20.0, 25.0, 29.0}) {
    SCOPED_TRACE(std::to_string(deg) + " deg");
    const double a = deg * M_PI / 180, H = L * std::tan(a);
    auto mesh = std::make_shared<TriangleMesh>();
    mesh->vertices = {Vec3(-L / 2, -W / 2, 0), Vec3(L / 2, -W / 2, 0), Vec3(L / 2, -W / 2, H),
                      Vec3(-L / 2, W / 2, 0),  Vec3(L / 2, W / 2, 0),  Vec3(L / 2, W / 2, H)};
    mesh->faces = {{0, 1, 2}, {3, 5, 4}, {0, 3, 4}, {0, 4, 1},
                   {1, 4, 5}, {1, 5, 2}, {2, 5, 3}, {2, 3, 0}};
    // the wedge's centre of mass (its triangle's centroid) a little above the ground; the box on
    // the slope's middle, 0.3 mm above it
    const Vec3 wedge_com(L / 6, 0, H / 3 + 2e-4);
    const Vec3 n(-std::sin(a), 0, std::cos(a));
    const Vec3 box_x = Vec3(0, 0, L / 2 * std::tan(a) + 2e-4) + n * (hz + 3e-4);
    BodySpec wedge =
        body("wedge", Shape::from_mesh(mesh, "wedge"), 3000, wedge_com, Vec3::Zero(), 0, mu);
    wedge.panels = 200;  // (its added mass takes no part: gravity alone)
    BodySpec box = box_body("box", Vec3(0.04, 0.03, 2 * hz), 1000, box_x, Vec3::Zero(), 0, mu);
    box.panels = 200;
    box.orientation = Quat(Eigen::AngleAxisd(-a, Vec3::UnitY()));
    Scene s = pair_scene({wedge, box}, Vec3(0, 0, -kG), 2e-3, 2);
    s.has_ground = true;
    s.ground_z = 0;
    s.ground_contact = ContactMode::Collide;
    Model m = test::compile(s);
    m.sleep_time = 1e9;  // (resting, never asleep: the solver holds it, step after step)
    State st = initial_state(m, s);
    RunOptions o;
    o.threads = 1;
    o.every = 0.5;
    std::vector<Vec3> at;  // the box's centre at each output
    o.on_output = [&](const State& x) { at.push_back(x.x[1]); };
    simulate(m, &st, o);
    ASSERT_EQ(at.size(), 5u);
    const Vec3 down(-std::cos(a), 0, -std::sin(a));
    if (std::tan(a) < mu) {
      // settled by 0.5 s; then no motion along the slope
      EXPECT_LT(std::abs((at[4] - at[1]).dot(down)), 1e-6) << (at[4] - at[1]).transpose();
      EXPECT_EQ(st.status[1], BodyStatus::Moving);
      EXPECT_EQ(st.contact[1], ContactState::Resting);
    } else {
      EXPECT_GT((at[2] - at[0]).dot(down), 0.05) << "it slides";
    }
  }
}

TEST(BodyContact, IslandPointsNeverPullAndEnergyDoesNotGrow) {
  // two spheres touching with random velocities and a random normal: after island_resolve the
  // normal velocity is >= its target and the kinetic energy is not larger
  Mat6 Minv = Mat6::Zero();
  Minv.diagonal() << 1, 1, 1, 2.5, 2.5, 2.5;
  uint64_t seed = 7;
  auto rnd = [&]() {
    seed = seed * 6364136223846793005ULL + 1442695040888963407ULL;
    return double(seed >> 11) / double(1ULL << 53) * 2 - 1;
  };
  for (int c = 0; c < 500; ++c) {
    IslandBody b[2];
    world_inverse_mass(Minv, Mat3::Identity(), b[0].W);
    world_inverse_mass(Minv, Mat3::Identity(), b[1].W);
    for (int a = 0; a < 3; ++a)
      b[0].v[a] = rnd(), b[0].w[a] = rnd(), b[1].v[a] = rnd(), b[1].w[a] = rnd();
    Vec3 n(rnd(), rnd(), rnd());
    n.normalize();
    IslandPoint p;
    p.a = 0, p.b = 1;
    for (int a = 0; a < 3; ++a) p.n[a] = n[a], p.ra[a] = -0.5 * n[a], p.rb[a] = 0.5 * n[a];
    p.depth = 0;
    p.restitution = 0.5 * (rnd() + 1);
    p.friction = rnd() + 1;
    p.rest_speed = 0.01;
    auto energy = [&]() {
      double E = 0;
      for (const IslandBody& x : b)
        E += 0.5 * (dot3(x.v, x.v) + dot3(x.w, x.w) / 2.5);
      return E;
    };
    const double E0 = energy();
    double vc[3];
    island_point_velocity(b, p, vc);
    const double vn0 = dot3(vc, p.n);
    island_resolve(b, &p, 1, 48, 1e-3);
    island_point_velocity(b, p, vc);
    const double vn1 = dot3(vc, p.n);
    EXPECT_GE(p.jn, 0);
    if (vn0 < -0.01) EXPECT_NEAR(vn1, -p.restitution * vn0, 1e-6 * std::abs(vn0));
    else EXPECT_GE(vn1, -1e-9);
    EXPECT_LE(energy(), E0 * (1 + 1e-9) + 1e-12);
    EXPECT_LE(std::sqrt(dot3(p.jt, p.jt)), p.friction * p.jn * (1 + 1e-9) + 1e-15);
  }
}

// The impulses each step leaves for the next one's warm start (State::pair_impulses): on a stack
// of five boxes standing on the ground, the pair below box k carries the weight of the boxes
// above it over the step, (4 - k) m g dt, and box 0's points on the ground the weight of the four
// above it (the step's own contact pass holds box 0's), with no net tangential impulse; the
// points are sorted by their pair, each pair's bodies in order, each point pushing and within its
// friction cone.
TEST(BodyContact, EachStepLeavesTheStacksWeightsForTheNextOne) {
  std::vector<BodySpec> boxes;
  for (int k = 0; k < 5; ++k)
    boxes.push_back(box_body("box" + std::to_string(k), Vec3(0.04, 0.03, 0.02), 1000,
                             Vec3(0, 0, 0.01 + 0.02 * k), Vec3::Zero(), 0.0, 0.5));
  const double dt = 1e-3;
  Scene s = pair_scene(boxes, Vec3(0, 0, -kG), dt, 0.3);  // (asleep after 0.5 s of rest)
  s.has_ground = true;
  s.ground_z = 0;
  s.ground_contact = ContactMode::Collide;
  const Model m = test::compile(s);
  State st = run(m, s);
  const double w = 1000 * 0.04 * 0.03 * 0.02 * kG * dt;  // one box's weight over a step, N s
  std::map<std::pair<uint32_t, uint32_t>, double> load;
  std::map<std::pair<uint32_t, uint32_t>, Vec3> tang;
  for (size_t k = 0; k < st.pair_impulses.size(); ++k) {
    const PairImpulse& p = st.pair_impulses[k];
    EXPECT_GT(p.jn, 0);
    EXPECT_TRUE(p.b == PairImpulse::kSurface || p.a < p.b);
    if (k > 0) {
      const PairImpulse& q = st.pair_impulses[k - 1];
      EXPECT_TRUE(q.a < p.a || (q.a == p.a && q.b <= p.b)) << k;
    }
    load[{p.a, p.b}] += p.jn;
    tang.try_emplace({p.a, p.b}, Vec3::Zero()).first->second += Vec3(p.jt[0], p.jt[1], p.jt[2]);
    EXPECT_LE(std::sqrt(dot3(p.jt, p.jt)), 0.5 * p.jn * (1 + 1e-12));  // in the cone
  }
  ASSERT_EQ(load.size(), 5u);
  EXPECT_NEAR((load[{0, PairImpulse::kSurface}]), 4 * w, 1e-3 * w);
  for (uint32_t k = 0; k < 4; ++k) EXPECT_NEAR((load[{k, k + 1}]), (4 - k) * w, 1e-3 * w) << k;
  // (a face's points may hold friction against each other, which sums to nothing; what is left
  // is the stack's settling, a few per cent of a weight)
  for (const auto& [pair, jt] : tang) EXPECT_LT(jt.norm(), 0.05 * w) << pair.first << " " << pair.second;
}

// The warm start is state: a run continued from its state goes on as the uninterrupted run does,
// bitwise, and the same state without the last step's impulses goes on differently (a resumed run
// needs them: they are in the checkpoint)
TEST(BodyContact, TheLastStepsImpulsesAreStateARunContinuesWith) {
  std::vector<BodySpec> bs;
  for (int k = 0; k < 4; ++k)
    bs.push_back(box_body("box" + std::to_string(k), Vec3(0.04, 0.03, 0.02), 1000,
                          Vec3(0.004 * k, 0.003 * k, 0.012 + 0.025 * k), Vec3::Zero(), 0.0, 0.5));
  Scene s = pair_scene(bs, Vec3(0, 0, -kG), 1e-3, 0.4);
  s.has_ground = true;
  s.ground_z = 0;
  s.ground_contact = ContactMode::Collide;
  const Model whole = test::compile(s);
  const State uninterrupted = run(whole, s);
  Scene half = s;
  half.duration = 0.2;
  State st = run(test::compile(half), half);
  ASSERT_FALSE(st.pair_impulses.empty());
  State cold = st;
  cold.pair_impulses.clear();
  simulate(whole, &st, RunOptions{});
  simulate(whole, &cold, RunOptions{});
  bool differs = false;
  for (size_t i = 0; i < st.size(); ++i) {
    EXPECT_EQ(st.x[i], uninterrupted.x[i]) << i;
    EXPECT_EQ(st.v[i], uninterrupted.v[i]) << i;
    differs = differs || cold.x[i] != uninterrupted.x[i];
  }
  EXPECT_TRUE(differs);
}

// island_resolve from the impulses that solve its problem (a warm start at the solution) stays
// there: one sweep leaves the impulses and velocities where the cold solve put them; and a warm
// start outside the constraints (pulling, beyond the friction cone, along the normal, NaN) is
// taken within them
TEST(BodyContact, AWarmStartAtTheSolutionStaysThereAndOneOutsideIsTakenWithin) {
  Mat6 Minv = Mat6::Zero();
  Minv.diagonal() << 1, 1, 1, 2.5, 2.5, 2.5;
  IslandBody b0[2];
  world_inverse_mass(Minv, Mat3::Identity(), b0[0].W);
  world_inverse_mass(Minv, Mat3::Identity(), b0[1].W);
  const double v0[3] = {0.3, -0.2, -1.0}, w0[3] = {0.5, 0.1, -0.2};
  for (int a = 0; a < 3; ++a) b0[0].v[a] = v0[a], b0[0].w[a] = w0[a];
  IslandPoint p0;
  p0.a = 0, p0.b = 1;
  const Vec3 n = Vec3(0.2, 0.1, 1).normalized();
  for (int a = 0; a < 3; ++a) p0.n[a] = n[a], p0.ra[a] = -0.5 * n[a], p0.rb[a] = 0.5 * n[a];
  p0.friction = 0.8;
  p0.rest_speed = 0.01;
  IslandBody cold[2] = {b0[0], b0[1]};
  IslandPoint pc = p0;
  island_resolve(cold, &pc, 1, 256, 1e-3);
  ASSERT_GT(pc.jn, 0);
  IslandBody warm[2] = {b0[0], b0[1]};
  IslandPoint pw = p0;
  pw.jn = pc.jn;
  for (int a = 0; a < 3; ++a) pw.jt[a] = pc.jt[a];
  island_resolve(warm, &pw, 1, 1, 1e-3);
  EXPECT_NEAR(pw.jn, pc.jn, 1e-12);
  for (int k = 0; k < 2; ++k)
    for (int a = 0; a < 3; ++a) {
      EXPECT_NEAR(warm[k].v[a], cold[k].v[a], 1e-12);
      EXPECT_NEAR(warm[k].w[a], cold[k].w[a], 1e-12);
    }
  // outside the constraints: taken within them before any sweep (0 sweeps)
  const double jt_far[3] = {5.0, -3.0, 2.0};
  for (const double jn : {-1.0, 0.5, std::nan("")}) {
    IslandBody b[2] = {b0[0], b0[1]};
    IslandPoint p = p0;
    p.jn = jn;
    for (int a = 0; a < 3; ++a) p.jt[a] = jt_far[a];
    island_resolve(b, &p, 1, 0, 1e-3);
    const double jn_in = jn > 0 ? jn : 0.0;
    EXPECT_EQ(p.jn, jn_in);
    EXPECT_NEAR(dot3(p.jt, p.n), 0, 1e-15);
    EXPECT_LE(std::sqrt(dot3(p.jt, p.jt)), p0.friction * jn_in * (1 + 1e-12));
    // the impulse applied: jn n + jt on a, its opposite on b (unit masses: the velocity changes)
    for (int a = 0; a < 3; ++a) {
      const double J = jn_in * p.n[a] + p.jt[a];
      EXPECT_NEAR(b[0].v[a] - b0[0].v[a], J, 1e-12);
      EXPECT_NEAR(b[1].v[a] - b0[1].v[a], -J, 1e-12);
    }
  }
}

// The position correction (island_resolve's moves): a column of three bodies at rest, pressed
// into the ground and into each other by d0, d1, d2: half of each penetration is removed at once,
// the column lifted as one (body k rises by half of the penetrations below it: the ground does not
// give, the bodies above are pushed, not pulled); a point apart (depth < 0) moves nothing; the
// velocities stay zero (positions only)
TEST(BodyContact, ThePositionCorrectionLiftsAColumnPressedIntoTheGround) {
  Mat6 Minv = Mat6::Zero();
  Minv.diagonal() << 2, 2, 2, 5, 5, 5;  // 0.5 kg
  IslandBody b[4];
  for (IslandBody& x : b) world_inverse_mass(Minv, Mat3::Identity(), x.W);
  const double d[3] = {4e-4, 1e-3, 2.5e-4};
  std::vector<IslandPoint> pts;
  auto point = [&](int a, int bb, double depth, double z) {
    IslandPoint p;
    p.a = a, p.b = bb;
    p.n[2] = 1;
    p.ra[2] = -0.01, p.rb[2] = 0.01;
    p.ra[0] = p.rb[0] = z;  // off the centre line: the correction translates only
    p.depth = depth;
    p.friction = 0.5;
    p.rest_speed = 0.01;
    pts.push_back(p);
  };
  point(0, -1, d[0], 0.003);
  point(0, -1, d[0], -0.003);
  point(1, 0, d[1], 0.002);
  point(2, 1, d[2], -0.001);
  point(3, 2, -1e-4, 0.0);  // body 3 above body 2, apart
  std::vector<double> moves(3 * 4, -1.0);
  island_resolve(b, pts.data(), int(pts.size()), 256, 1e-3, 1e-3, moves.data());
  const double want[4] = {0.5 * d[0], 0.5 * (d[0] + d[1]), 0.5 * (d[0] + d[1] + d[2]), 0.0};
  for (int k = 0; k < 4; ++k) {
    EXPECT_NEAR(moves[3 * k + 2], want[k], 1e-5 * want[2]) << k;  // (the sweeps stop at 1e-6)
    EXPECT_EQ(moves[3 * k], 0.0) << k;
    EXPECT_EQ(moves[3 * k + 1], 0.0) << k;
    for (int a = 0; a < 3; ++a) {
      EXPECT_EQ(b[k].v[a], 0.0);
      EXPECT_EQ(b[k].w[a], 0.0);
    }
  }
}

// Two States bitwise the same in every part (a NaN left in place compares equal)
::testing::AssertionResult same_state(const State& a, const State& b) {
  auto bits = [](const auto& x, const auto& y) {
    return x.size() == y.size() &&
           (x.empty() || std::memcmp(x.data(), y.data(), x.size() * sizeof(x[0])) == 0);
  };
  const std::pair<const char*, bool> parts[] = {
      {"step", a.step == b.step && std::memcmp(&a.t, &b.t, sizeof a.t) == 0},
      {"x", bits(a.x, b.x)},
      {"q", bits(a.q, b.q)},
      {"v", bits(a.v, b.v)},
      {"w", bits(a.w, b.w)},
      {"u_seen", bits(a.u_seen, b.u_seen)},
      {"status", bits(a.status, b.status)},
      {"t_stop", bits(a.t_stop, b.t_stop)},
      {"reason", a.reason == b.reason},
      {"contact", bits(a.contact, b.contact)},
      {"rest_steps", bits(a.rest_steps, b.rest_steps)},
      {"impacts", bits(a.impacts, b.impacts)},
      {"t_touch", bits(a.t_touch, b.t_touch)},
      {"x_touch", bits(a.x_touch, b.x_touch)},
      {"hidden", bits(a.hidden, b.hidden)},
      {"history", bits(a.history, b.history)},
      {"pair_impulses", bits(a.pair_impulses, b.pair_impulses)},
      {"watch", a.watch.size() == b.watch.size()}};
  const char* part = nullptr;
  for (const auto& [name, same] : parts)
    if (!same && !part) part = name;
  for (size_t i = 0; !part && i < a.watch.size(); ++i) {
    const GustWatch &p = a.watch[i], &r = b.watch[i];
    if (p.u != r.u || std::memcmp(&p.ua, &r.ua, sizeof p.ua) != 0 ||
        std::memcmp(&p.gust, &r.gust, sizeof p.gust) != 0 || p.start != r.start ||
        p.step != r.step || p.wake != r.wake || p.valid != r.valid)
      part = "watch";
  }
  if (!part) return ::testing::AssertionSuccess();
  auto out = ::testing::AssertionFailure() << "the states differ in " << part;
  for (size_t i = 0; i < std::min(a.size(), b.size()); ++i)
    if (a.x[i] != b.x[i] || a.v[i] != b.v[i] || a.status[i] != b.status[i] ||
        a.contact[i] != b.contact[i]) {
      out << " (first at body " << i << ": x " << a.x[i].transpose() << " against "
          << b.x[i].transpose() << ")";
      break;
    }
  return out;
}

struct StretchRun {
  State state;
  RunStats stats;
  size_t asleep_at_outputs = 0;  // bodies asleep, summed over the outputs
};

// The run of m from `start` with stretches of `steps` steps (RunOptions::contact_stretch; 1: the
// lockstep) on `threads` threads, an output every `every` seconds.
StretchRun run_stretches(const Model& m, const State& start, uint64_t steps, int threads,
                         double every) {
  StretchRun r{start, {}, 0};
  RunOptions o;
  o.threads = threads;
  o.every = every;
  o.contact_stretch = steps;
  o.on_output = [&](const State& x) {
    for (size_t i = 0; i < x.size(); ++i)
      r.asleep_at_outputs += x.status[i] == BodyStatus::Sleeping;
  };
  r.stats = simulate(m, &r.state, o);
  return r;
}

// The speculative stretches (the default length, and 7 steps) on 1 and 2 threads end bitwise
// where the lockstep ends, with the same counts; returns the lockstep's run, and in
// *lockstep_stretches the stretches of the default length taken in lockstep from their start
// (bodies touching from step to step).
StretchRun expect_stretches_are_the_lockstep(const Model& m, const State& start, double every,
                                             uint64_t* lockstep_stretches = nullptr) {
  const StretchRun lock = run_stretches(m, start, 1, 1, every);
  struct Case {
    uint64_t steps;
    int threads;
  };
  for (const Case c : {Case{0, 1}, Case{7, 1}, Case{0, 2}}) {
    SCOPED_TRACE("stretches of " + (c.steps ? std::to_string(c.steps) : std::string("default")) +
                 " steps, " + std::to_string(c.threads) + " threads");
    const StretchRun r = run_stretches(m, start, c.steps, c.threads, every);
    EXPECT_TRUE(same_state(r.state, lock.state));
    EXPECT_EQ(r.stats.body_steps, lock.stats.body_steps);
    EXPECT_EQ(r.stats.scalar_handoffs, lock.stats.scalar_handoffs);
    EXPECT_EQ(r.stats.pair_steps, lock.stats.pair_steps);
    EXPECT_EQ(r.stats.pair_wakes, lock.stats.pair_wakes);
    EXPECT_EQ(r.stats.steps, lock.stats.steps);
    EXPECT_EQ(r.stats.landed, lock.stats.landed);
    EXPECT_EQ(r.stats.exited, lock.stats.exited);
    EXPECT_EQ(r.stats.resting, lock.stats.resting);
    EXPECT_EQ(r.asleep_at_outputs, lock.asleep_at_outputs);
    if (lockstep_stretches && c.steps == 0 && c.threads == 1)
      *lockstep_stretches = r.stats.lockstep_stretches;
  }
  return lock;
}

// Bodies far apart in the sheared wind grid, landing on its colliding ground and leaving it:
// beads (the isotropic M, whose lanes keep the world velocity), tissue squares and seed pods (the
// diagonal M), on the batched step in double and single precision and on the scalar step. No
// two touch: every stretch is kept as it was first taken.
TEST(BodyContactStretches, BodiesFarApartEndWhereTheLockstepEndsThem) {
  Scene s = test::sphere_scene(0.004, 600, 1.2, 1.5e-5, 12);
  s.effects = test::effects({Effect::Gravity, Effect::Buoyancy, Effect::Drag, Effect::AddedMass,
                             Effect::MeanFlow, Effect::Turbulence, Effect::Lift});
  BodySpec tissue = s.bodies[0];
  tissue.name = "tissue";
  tissue.shape = Shape::box(0.03, 0.03, 1e-4);
  tissue.density = 300;
  tissue.count = 12;
  BodySpec pod = s.bodies[0];
  pod.name = "pod";
  pod.shape = Shape::ellipsoid(0.004, 0.002, 0.002);
  pod.density = 400;
  pod.count = 12;
  s.bodies.push_back(tissue);
  s.bodies.push_back(pod);
  batch_test::release_in_wind_grid(&s, 11);
  for (BodySpec& b : s.bodies) {
    b.spawn_in_box = true;
    b.box_lo = Vec3(-5.5, -3.5, 0.05);
    b.box_hi = Vec3(-1.5, 3.5, 1.5);
    b.random_orientation = true;
  }
  s.ground_contact = ContactMode::Collide;
  s.body_contact = true;
  s.duration = 0.6;
  const FluidField field = batch_test::wind_grid(1.5e-5);
  struct Case {
    bool batched;
    Precision p;
    const char* name;
  };
  for (const Case c :
       {Case{true, Precision::Double, "batched double"},
        Case{true, Precision::Float, "batched float"}, Case{false, Precision::Double, "scalar"}}) {
    SCOPED_TRACE(c.name);
    Model m = test::compile(s, field);
    m.batched = c.batched;
    m.precision = c.p;
    ASSERT_EQ(step_kind(m, m.types[0], nullptr), c.batched ? StepKind::Batched : StepKind::Scalar);
    const State start = initial_state(m, s);
    uint64_t lockstep_stretches = 1;
    const StretchRun lock = expect_stretches_are_the_lockstep(m, start, 0.1, &lockstep_stretches);
    // the scene: bodies far apart, some on the ground, some leaving the grid
    EXPECT_EQ(lock.stats.pair_steps, 0u);
    EXPECT_EQ(lockstep_stretches, 0u) << "every stretch speculative";
    size_t on_ground = 0;
    for (size_t i = 0; i < lock.state.size(); ++i)
      on_ground += lock.state.status[i] == BodyStatus::Moving &&
                   lock.state.contact[i] != ContactState::Flying;
    EXPECT_GT(on_ground, 0u);
  }
}

// A heap of spheres and boxes falling onto the ground and onto each other (every stretch has
// bodies taken again in lockstep); spheres thrown at each other and three spheres in a row
// colliding in free space, with no ground (the stage marks a body flying once it touches
// nothing).
TEST(BodyContactStretches, AHeapEndsWhereTheLockstepEndsIt) {
  BodySpec ball = sphere_body("ball", 0.01, 1000, Vec3::Zero(), Vec3::Zero(), 0.2, 0.5);
  ball.contact.rolling_resistance = 0.3;
  ball.count = 30;
  ball.spawn_in_box = true;
  ball.box_lo = Vec3(-0.03, -0.03, 0.02);
  ball.box_hi = Vec3(0.03, 0.03, 0.12);
  BodySpec brick =
      box_body("brick", Vec3(0.02, 0.015, 0.01), 800, Vec3::Zero(), Vec3::Zero(), 0.1, 0.6);
  brick.count = 10;
  brick.spawn_in_box = true;
  brick.box_lo = Vec3(-0.03, -0.03, 0.12);
  brick.box_hi = Vec3(0.03, 0.03, 0.2);
  brick.random_orientation = true;
  Scene s = pair_scene({ball, brick}, Vec3(0, 0, -kG), 1e-3, 0.4);
  s.has_ground = true;
  s.ground_z = 0;
  s.ground_contact = ContactMode::Collide;
  const Model m = test::compile(s);
  uint64_t lockstep_stretches = 0;
  const StretchRun heap =
      expect_stretches_are_the_lockstep(m, initial_state(m, s), 0.05, &lockstep_stretches);
  EXPECT_GT(heap.stats.pair_steps, 1000u) << "bodies on bodies";
  // (a heap's bodies touch from step to step: stretches taken in lockstep from their start after
  // the first, speculative one)
  EXPECT_GT(lockstep_stretches, 0u);

  // spheres thrown at each other in free space: with no colliding ground the stage marks a body
  // flying once it touches nothing, which a stretch that starts just after a contact must do too
  BodySpec bead = sphere_body("bead", 0.005, 1000, Vec3::Zero(), Vec3::Zero(), 0.7, 0.3);
  bead.count = 40;
  bead.spawn_in_box = true;
  bead.box_lo = Vec3(-0.04, -0.04, -0.04);
  bead.box_hi = Vec3(0.04, 0.04, 0.04);
  Scene swarm = pair_scene({bead}, Vec3::Zero(), 5e-4, 0.25);
  const Model ms = test::compile(swarm);
  ASSERT_FALSE(ms.contacts());
  State thrown = initial_state(ms, swarm);
  for (size_t i = 0; i < thrown.size(); ++i)
    thrown.v[i] = -2.0 * thrown.x[i] + 0.1 * Vec3(std::sin(3.0 * i), std::cos(5.0 * i), 0);
  const StretchRun free = expect_stretches_are_the_lockstep(ms, thrown, 0.05);
  EXPECT_GT(free.stats.pair_steps, 100u);

  const double r = 0.01, u = 0.5, gap = 0.001;
  Scene row =
      pair_scene({sphere_body("a", r, 1000, Vec3(-(2 * r + gap), 0, 0), Vec3(u, 0, 0), 0.8, 0.2),
                  sphere_body("b", r, 1000, Vec3(0, 0, 0), Vec3::Zero(), 0.8, 0.2),
                  sphere_body("c", r, 1000, Vec3(2 * r + gap, 0, 0), Vec3::Zero(), 0.8, 0.2)},
                 Vec3::Zero(), 1e-4, 0.05);
  const Model mr = test::compile(row);
  ASSERT_FALSE(mr.contacts());
  const StretchRun cradle = expect_stretches_are_the_lockstep(mr, initial_state(mr, row), 0.01);
  EXPECT_GT(cradle.stats.pair_steps, 0u);
  EXPECT_GT(cradle.state.v[2].x(), 0.3 * u) << "the last one leaves";
}

// A stack of boxes falls asleep on the ground; a sphere released over it later falls onto it and
// wakes it (and the sleeping boxes touching the one it hits), while a second stack far away
// sleeps on.
TEST(BodyContactStretches, SleepingBodiesWokenByAFallingOneEndWhereTheLockstepEndsThem) {
  std::vector<BodySpec> bodies;
  for (const double x0 : {0.0, 0.5})
    for (int k = 0; k < 3; ++k)
      bodies.push_back(box_body("box" + std::to_string(k), Vec3(0.04, 0.03, 0.02), 1000,
                                Vec3(x0, 0, 0.01 + 0.02 * k), Vec3::Zero(), 0.0, 0.5));
  BodySpec ball =
      sphere_body("ball", 0.008, 3000, Vec3(0.005, 0.003, 0.3), Vec3(0, 0, -1), 0.3, 0.5);
  ball.release_times = {0.8};
  bodies.push_back(ball);
  Scene s = pair_scene(bodies, Vec3(0, 0, -kG), 1e-3, 1.2);
  s.has_ground = true;
  s.ground_z = 0;
  s.ground_contact = ContactMode::Collide;
  Model m = test::compile(s);
  m.sleep_time = 0.3;
  const StretchRun run = expect_stretches_are_the_lockstep(m, initial_state(m, s), 0.1);
  EXPECT_GT(run.stats.pair_wakes, 0u) << "the ball wakes the stack";
  EXPECT_GT(run.asleep_at_outputs, 0u);
  for (size_t i = 3; i < 6; ++i)
    EXPECT_EQ(run.state.status[i], BodyStatus::Sleeping) << "the far stack sleeps on: " << i;
}

// Boxes lying on the ground of the gusting wind grid (a field whose frames change at 0.3, 0.55 and
// 0.9 s) fall asleep, and wake where the flow changes (a stretch ends there; one that fell asleep
// inside the stretch is taken again in lockstep), and a bead falls onto one.
TEST(BodyContactStretches, BodiesAsleepInAChangingFlowEndWhereTheLockstepEndsThem) {
  std::vector<BodySpec> bodies;
  for (int k = 0; k < 4; ++k)
    bodies.push_back(box_body("brick" + std::to_string(k), Vec3(0.04, 0.03, 0.02), 2000,
                              Vec3(-4 + 0.041 * k, 0, 0.01), Vec3::Zero(), 0.0, 0.6));
  BodySpec bead = sphere_body("bead", 0.006, 2500, Vec3(-3.96, 0.002, 0.4), Vec3::Zero(), 0.3, 0.5);
  bead.release_times = {0.4};
  bodies.push_back(bead);
  Scene s = pair_scene(bodies, Vec3(0, 0, -kG), 2e-3, 1.2);
  s.uniform_field = false;
  s.effects = test::effects({Effect::Gravity, Effect::Buoyancy, Effect::Drag, Effect::MeanFlow});
  s.has_ground = true;
  s.ground_z = 0;
  s.ground_contact = ContactMode::Collide;
  Model m = test::compile(s, batch_test::gusty_wind_grid(1.5e-5));
  ASSERT_GE(m.field.frame_count(), 2u);
  // (asleep at 0.546 s, inside a stretch of 7 steps that the frame at 0.55 s cuts, and again
  // from 1.1 s)
  m.sleep_time = 0.545;
  const StretchRun run = expect_stretches_are_the_lockstep(m, initial_state(m, s), 0.1);
  EXPECT_GT(run.asleep_at_outputs, 0u);
  EXPECT_GT(run.stats.pair_steps, 0u);
}

}  // namespace
}  // namespace lrigid
