// Writes a run's results into a directory (docs/outputs.md):
//   trajectories.csv   body,type,t,x,y,z,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz (SI, world frame)
//   bodies.pvd + bodies/bodies_NNNNNN.vtp   ParaView time series of body points with arrays
//   landings.csv       body,type,t,x,y,z of bodies that reached the ground (scenes with ground)
//   summary.json       counts, timing, effects, stopped bodies and why
// Nothing appears under its final name until the run completed: files are written under
// temporary names and renamed at finish(); a writer destroyed before finish() removes them.
#pragma once
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "integrate/simulation.h"
#include "model/state.h"
#include "nlohmann/json.hpp"

namespace lrigid {

class ResultWriter {
 public:
  ResultWriter(const std::string& dir, const Model& model, const OutputSpec& spec);
  ~ResultWriter();
  ResultWriter(const ResultWriter&) = delete;
  ResultWriter& operator=(const ResultWriter&) = delete;

  void write_frame(const State& state);
  // Moves everything into place; `extra` is merged into summary.json.
  void finish(const State& state, const RunStats& stats, const nlohmann::json& extra);

  const std::string& dir() const { return dir_; }

 private:
  void write_vtp(const State& state, const std::string& path) const;
  void cleanup();

  std::string dir_;
  const Model& model_;
  OutputSpec spec_;
  std::string tag_;
  std::FILE* csv_ = nullptr;
  std::string csv_tmp_;
  std::string vtp_tmp_dir_;
  std::vector<std::pair<double, std::string>> frames_;
  bool finished_ = false;
};

}  // namespace lrigid
