// lrigid's side of the box pile (bench/peers/pile.md, run by run_pile.sh): the measures of
// pile_common.h (deepest overlaps, kinetic energy, height) at every output time of an lrigid
// run's trajectories.csv, reported in the peers' JSON with the run's own rate.
//   pile_measure --trajectories FILE --body-steps B --seconds T [--size LX LY LZ]
//                [--density RHO] [--dt DT] [--steps S] [--params JSON] --poses FILE
// --body-steps and --seconds: summary.json's body_steps and wall_seconds (integration only, no
// output; one thread).
#include "pile_common.h"

int main(int argc, char** argv) {
  const char* prog = argv[0];
  std::string trajectories, params = "{}";
  double body_steps = -1, seconds = -1;
  try {
    pile::Params p = pile::parse_flags(argc, argv, [&](int i) {
      const std::string f = argv[i];
      if (f != "--trajectories" && f != "--body-steps" && f != "--seconds" && f != "--params") return 0;
      if (i + 1 >= argc) pile::usage_error(prog, f + ": needs a value");
      if (f == "--trajectories") trajectories = argv[i + 1];
      else if (f == "--params") params = argv[i + 1];
      else if (f == "--body-steps") body_steps = pile::parse_number(prog, "--body-steps", argv[i + 1]);
      else seconds = pile::parse_number(prog, "--seconds", argv[i + 1]);
      return 2;
    });
    if (trajectories.empty() || !(body_steps > 0) || !(seconds > 0))
      pile::usage_error(prog, "need --trajectories FILE, --body-steps > 0 and --seconds > 0");
    const size_t n = pile::read_poses(p.poses, p.n).size();

    std::ifstream in(trajectories);
    if (!in) throw std::runtime_error(trajectories + ": cannot open");
    std::string line;
    std::getline(in, line);
    if (line.rfind("body,type,t,x,y,z,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz", 0) != 0)
      throw std::runtime_error(trajectories + ": not an lrigid trajectories.csv");
    pile::Run r;
    std::vector<pile::Body> frame(n);
    std::vector<char> seen(n, 0);
    double t_frame = -1;
    auto flush = [&] {
      for (size_t i = 0; i < n; ++i)
        if (!seen[i]) throw std::runtime_error(trajectories + ": body " + std::to_string(i) +
                                               " missing at t = " + std::to_string(t_frame));
      r.samples.push_back(pile::measure(p, frame, t_frame));
      r.window_rates.push_back(0);  // lrigid reports its rate for the whole run only
      std::fill(seen.begin(), seen.end(), 0);
    };
    while (std::getline(in, line)) {
      std::vector<std::string> c;
      std::istringstream s(line);
      std::string cell;
      while (std::getline(s, cell, ',')) c.push_back(cell);
      if (c.size() < 16) throw std::runtime_error(trajectories + ": short row: " + line);
      const long body = std::strtol(c[0].c_str(), nullptr, 10);
      const double t = std::strtod(c[2].c_str(), nullptr);
      if (body < 0 || size_t(body) >= n) throw std::runtime_error(trajectories + ": body out of range");
      if (t != t_frame) {
        if (t_frame >= 0) flush();
        t_frame = t;
      }
      auto num = [&](int k) { return std::strtod(c[size_t(k)].c_str(), nullptr); };
      pile::Body& b = frame[size_t(body)];
      b.x = {num(3), num(4), num(5)};
      b.q = {num(6), num(7), num(8), num(9)};
      b.v = {num(10), num(11), num(12)};
      b.w = {num(13), num(14), num(15)};
      seen[size_t(body)] = 1;
    }
    if (t_frame < 0) throw std::runtime_error(trajectories + ": no rows");
    flush();
    r.window_rates.pop_back();  // one rate per interval between samples
    r.body_steps = (long long)body_steps;
    r.step_cpu = seconds;
    pile::report("lrigid", "", p, n, r, params);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "pile_measure: %s\n", e.what());
    return 1;
  }
  return 0;
}
