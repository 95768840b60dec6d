// A scene as the user described it (parsed and validated by io/scene_json). Plain data, SI units.
// compile_model() (compile/compile_model.h) turns it into the constant Model the step runs on.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "body/shape.h"
#include "fluid/field.h"
#include "model/effects.h"

namespace lrigid {

enum class Integrator { Euler, RK4, Splitting, Strang };
// The scheme of the shipped scenes and of a Scene or Model built in code: strang
// reaches each error of docs/accuracy.md's study for less CPU time than splitting, on every
// scene kind measured; splitting (first order) stays fully supported.
constexpr Integrator kDefaultIntegrator = Integrator::Strang;
enum class TurbulenceModel { Body, Seen };
// arithmetic of the batched step (integrate/rigid_batch.h); the scalar step is double
enum class Precision { Double, Float };

// How bodies meet the ground, the grid's solids and the grid's outer boundary (scene keys
// ground.contact, walls.contact, outside; docs/scene-format.md, docs/contacts.md), applied by
// contact/pass.h after each step.
enum class ContactMode { Collide, Stop };
enum class OutsideMode { Remove, Stop };
const char* contact_mode_name(ContactMode m);
const char* outside_mode_name(OutsideMode m);

// A body type's contact material (key "contact", per body type and as the scene's default).
struct ContactSpec {
  double restitution = 0.3;  // e in [0, 1]: normal speed after / before an impact, -
  double friction = 0.5;     // mu >= 0: Coulomb friction coefficient, -
  // mu_r >= 0: rolling resistance coefficient: the torque against rolling is at most
  // mu_r r N (r the contact point's distance to the centre of mass, N the normal force), -
  double rolling_resistance = 0;
};

const char* integrator_name(Integrator i);
// The scheme named `name` ("euler", "rk4", "splitting", "strang"); false for another name.
bool integrator_from_name(const std::string& name, Integrator* out);
// The scheme names as a list for messages: "euler, rk4, splitting or strang"
constexpr const char* kIntegratorNames = "euler, rk4, splitting or strang";
const char* turbulence_model_name(TurbulenceModel m);
const char* drift_name(Drift d);

struct BodySpec {
  std::string name;
  Shape shape;
  int panels = 0;                         // BEM panels for box/mesh (0 = default)
  double density = 0;                     // kg/m^3
  Vec3 mass_offset = Vec3::Zero();        // centre of mass minus volume centroid, shape axes, m
  int count = 1;
  bool spawn_in_box = false;
  Vec3 position = Vec3::Zero();           // centre of mass, world, m (when !spawn_in_box)
  Vec3 box_lo = Vec3::Zero(), box_hi = Vec3::Zero();  // spawn box corners, world, m
  // spawn on the surface of the grid's solids (key "spawn", fluid/solid_surface.h): its sites
  // with the fluid point in [box_lo, box_hi] (the whole grid without a box), `spawn_offset`
  // into the fluid
  bool spawn_on_solids = false;
  bool spawn_surface_box = false;         // a box limits the sites
  double spawn_offset = 0;                // m
  bool random_orientation = false;
  Quat orientation = Quat::Identity();    // body -> world
  Vec3 velocity = Vec3::Zero();           // world, m/s
  Vec3 angular_velocity = Vec3::Zero();   // world, rad/s
  // art direction (docs/effects.md): per-body spin magnitude drawn uniformly from
  // [spin_min, spin_max] about a uniformly random axis, added to angular_velocity, rad/s
  double spin_min = 0, spin_max = 0;
  // per-body size and density factors drawn from [lo, hi]; bodies are spread over `variants`
  // body types (quantized draws) so the model stays constant per type
  double size_min = 1, size_max = 1;       // -
  double density_min = 1, density_max = 1; // -
  int variants = 1;
  // contact material; a key the body does not give comes from the scene's "contact"
  ContactSpec contact;
  bool restitution_given = false, friction_given = false, rolling_given = false;
  // release over time (key "release", model/release.h): by rate (bodies per second from
  // release_start) or at the listed times (the count split in bursts); neither: all at t = 0
  double release_rate = 0;                // 1/s; 0: not by rate
  double release_start = 0;               // s
  std::vector<double> release_times;      // s, increasing
  bool released_over_time() const { return release_rate > 0 || !release_times.empty(); }
};

struct OutputSpec {
  std::string dir = "results";            // resolved against the working directory
  double every = 0.1;                     // s between written states
  bool csv = true;
  bool pvd = true;
  bool glb = false;                       // animation.glb (glTF 2.0, docs/outputs.md)
  bool glb_instanced = false;             // animation_instanced.glb (EXT_mesh_gpu_instancing)
  bool houdini = false;                   // houdini_points.csv (Houdini's attribute names)
  bool usd = false;                       // bodies.usda (a USD PointInstancer)
  double checkpoint_every = 300;          // s of wall time between checkpoints; 0: none
};

struct Scene {
  std::string file;                       // the scene file, for messages
  double fluid_density = 1000;            // kg/m^3
  double kinematic_viscosity = 1e-6;      // m^2/s
  bool uniform_field = true;
  std::string field_path;                 // absolute path of .vti/.pvd (when !uniform_field)
  TimeMode time_mode = TimeMode::Loop;
  Vec3 uniform_U = Vec3::Zero();          // m/s
  double uniform_k = 0, uniform_epsilon = 0;
  Vec3 gravity = Vec3(0, 0, -9.81);       // m/s^2
  bool effects_auto = false;
  EffectSet effects;
  Integrator integrator = kDefaultIntegrator;
  bool batched = true;                    // integrator.batched: the batched steps
  Precision precision = Precision::Double;  // integrator.precision
  double dt = 1e-3;                       // s
  double duration = 1;                    // s
  uint64_t seed = 1;
  std::vector<BodySpec> bodies;
  bool has_ground = false;
  double ground_z = 0;                    // m
  // contacts (docs/contacts.md)
  ContactSpec contact;                    // defaults of the body types' "contact"
  ContactMode ground_contact = ContactMode::Collide;
  ContactMode walls_contact = ContactMode::Collide;
  OutsideMode outside = OutsideMode::Remove;
  // body_contact "collide": bodies collide with each other (contact/bodies.h); "off" (the
  // default): they pass through each other
  bool body_contact = false;
  TurbulenceModel turbulence_model = TurbulenceModel::Seen;
  Drift drift = Drift::Stationary;
  bool crossing_trajectories = true;      // seen model: Csanady's correction (docs/physics/langevin.md)
  // art direction: scales of the mean flow U and of the turbulent velocity (sqrt k) the bodies
  // see; 1 is the physical field (docs/effects.md)
  double mean_flow_scale = 1;             // -
  double turbulence_scale = 1;            // -
  OutputSpec output;
};

}  // namespace lrigid
