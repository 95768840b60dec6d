// Bullet peer of the box pile (bench/peers/pile.md, run by run_pile.sh): the pile's boxes from
// the poses file dropped onto the ground z = 0 under gravity in a btDiscreteDynamicsWorld
// (btDbvtBroadphase, btSequentialImpulseConstraintSolver, one thread), stepped at a fixed dt with
// no substeps. Prints one JSON object (pile_common.h): body-steps per CPU second of the stepping,
// the pile's deepest overlaps, kinetic energy and height.
//   pile_bullet --poses FILE [--n N] [--size LX LY LZ] [--density RHO] [--friction MU]
//               [--restitution E] [--gravity G] [--dt DT] [--steps S] [--sample-every T]
//               [--margin M] [--iterations K] [--erp ERP] [--split-impulse 0|1]
//               [--split-threshold D] [--sleep 0|1] [--breaking-threshold D]
#include <btBulletDynamicsCommon.h>

#include <memory>

#include "pile_common.h"

int main(int argc, char** argv) {
  // Bullet's settings (defaults: see pile.md for why)
  double margin = 0.0005;   // m, btBoxShape's collision margin (inside its half extents)
  int iterations = 10;      // sequential impulse sweeps per step (Bullet's default)
  double erp = 0.2;         // contacts' error reduction (m_erp2, Bullet's default)
  int split = 1;            // split impulse: position correction without added velocity
  double split_threshold = -0.04;  // m: deeper contacts than this are corrected by split impulse
  int sleep = 1;            // Bullet's deactivation of resting bodies (its default thresholds)
  double breaking = 0.002;  // m, gContactBreakingThreshold: contacts kept (and made) this far apart
  const char* prog = argv[0];
  pile::Params p;
  try {
    p = pile::parse_flags(argc, argv, [&](int i) {
      const std::string f = argv[i];
      const bool ours = f == "--margin" || f == "--iterations" || f == "--erp" ||
                        f == "--split-impulse" || f == "--split-threshold" || f == "--sleep" ||
                        f == "--breaking-threshold";
      if (!ours) return 0;
      if (i + 1 >= argc) pile::usage_error(prog, f + ": needs a value");
      const char* v = argv[i + 1];
      if (f == "--margin") margin = pile::parse_number(prog, "--margin", v);
      else if (f == "--iterations") iterations = int(pile::parse_number(prog, "--iterations", v));
      else if (f == "--erp") erp = pile::parse_number(prog, "--erp", v);
      else if (f == "--split-impulse") split = int(pile::parse_number(prog, "--split-impulse", v));
      else if (f == "--split-threshold") split_threshold = pile::parse_number(prog, "--split-threshold", v);
      else if (f == "--breaking-threshold") breaking = pile::parse_number(prog, f.c_str(), v);
      else sleep = int(pile::parse_number(prog, "--sleep", v));
      return 2;
    });
    if (!(breaking > 0) || !(margin >= 0) || iterations < 1 || !(erp >= 0 && erp <= 1) || (split != 0 && split != 1) ||
        (sleep != 0 && sleep != 1))
      pile::usage_error(prog, "need --breaking-threshold > 0, --margin >= 0, --iterations >= 1, --erp in [0, 1], "
                              "--split-impulse 0|1, --sleep 0|1");
    std::vector<pile::Body> init = pile::read_poses(p.poses, p.n);
    const size_t n = init.size();

    gContactBreakingThreshold = btScalar(breaking);
    btDefaultCollisionConfiguration config;
    // several contact points of a box on the plane at once (a box lying flat rests on 4)
    config.setPlaneConvexMultipointIterations();
    btCollisionDispatcher dispatcher(&config);
    btDbvtBroadphase broadphase;
    btSequentialImpulseConstraintSolver solver;
    btDiscreteDynamicsWorld world(&dispatcher, &broadphase, &solver, &config);
    world.setGravity(btVector3(0, 0, btScalar(-p.gravity)));
    btContactSolverInfo& si = world.getSolverInfo();
    si.m_numIterations = iterations;
    si.m_erp2 = btScalar(erp);
    si.m_splitImpulse = split;
    si.m_splitImpulsePenetrationThreshold = btScalar(split_threshold);

    btStaticPlaneShape ground_shape(btVector3(0, 0, 1), 0);
    btRigidBody ground(btRigidBody::btRigidBodyConstructionInfo(0, nullptr, &ground_shape));
    ground.setFriction(btScalar(p.friction));
    ground.setRestitution(btScalar(p.restitution));
    world.addRigidBody(&ground);

    btBoxShape box(btVector3(btScalar(p.size[0] / 2), btScalar(p.size[1] / 2), btScalar(p.size[2] / 2)));
    box.setMargin(btScalar(margin));
    const btScalar mass = btScalar(p.mass());
    btVector3 inertia;
    box.calculateLocalInertia(mass, inertia);
    std::vector<std::unique_ptr<btRigidBody>> bodies;
    bodies.reserve(n);
    for (const pile::Body& b : init) {
      btRigidBody::btRigidBodyConstructionInfo info(mass, nullptr, &box, inertia);
      info.m_friction = btScalar(p.friction);
      info.m_restitution = btScalar(p.restitution);
      info.m_startWorldTransform = btTransform(
          btQuaternion(btScalar(b.q[1]), btScalar(b.q[2]), btScalar(b.q[3]), btScalar(b.q[0])),
          btVector3(btScalar(b.x[0]), btScalar(b.x[1]), btScalar(b.x[2])));
      bodies.push_back(std::make_unique<btRigidBody>(info));
      if (!sleep) bodies.back()->setActivationState(DISABLE_DEACTIVATION);
      world.addRigidBody(bodies.back().get());
    }

    auto get = [&](std::vector<pile::Body>& st) {
      for (size_t i = 0; i < n; ++i) {
        const btTransform& tr = bodies[i]->getWorldTransform();
        const btQuaternion q = tr.getRotation();
        const btVector3& x = tr.getOrigin();
        const btVector3& v = bodies[i]->getLinearVelocity();
        const btVector3& w = bodies[i]->getAngularVelocity();
        st[i].x = {x.x(), x.y(), x.z()};
        st[i].q = {q.w(), q.x(), q.y(), q.z()};
        st[i].v = {v.x(), v.y(), v.z()};
        st[i].w = {w.x(), w.y(), w.z()};
      }
    };
    // fixed step: maxSubSteps = 0 steps exactly dt, no interpolation
    auto step = [&] { world.stepSimulation(btScalar(p.dt), 0); };
    const pile::Run r = pile::run(p, n, step, get);
    int asleep = 0;
    for (const auto& b : bodies) asleep += b->getActivationState() == ISLAND_SLEEPING;

    char params[800];
    std::snprintf(params, sizeof params,
                  "{\"precision\": \"%s\", \"broadphase\": \"btDbvtBroadphase\", "
                  "\"solver\": \"btSequentialImpulseConstraintSolver\", \"iterations\": %d, "
                  "\"margin_m\": %g, \"contact_breaking_threshold_m\": %g, \"erp2\": %g, "
                  "\"split_impulse\": %d, \"split_impulse_threshold_m\": %g, "
                  "\"box_box\": \"btBoxBoxDetector\", \"plane_multipoint\": true, \"deactivation\": %s, \"asleep_at_end\": %d, "
                  "\"friction\": %g, \"restitution\": %g}",
                  sizeof(btScalar) == 8 ? "double" : "float", iterations, margin,
                  double(gContactBreakingThreshold), erp, split, split_threshold,
                  sleep ? "true" : "false", asleep, p.friction, p.restitution);
    pile::report("bullet", std::to_string(btGetVersion()), p, n, r, params);
    for (auto& b : bodies) world.removeRigidBody(b.get());
    world.removeRigidBody(&ground);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "pile_bullet: %s\n", e.what());
    return 1;
  }
  return 0;
}
