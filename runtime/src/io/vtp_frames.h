// The frames of the ParaView series (docs/outputs.md), written cheaply: a frame of
// the default scene must cost no more than simulating the steps between two frames
// (docs/performance.md, "Output cost").
//   BodiesFrames: bodies_NNNNNN.vtp, one point per body with orientation, velocity,
//                 angular_velocity, body, type, status
//   ShapesFrames: shapes_NNNNNN.vtp, each body's surface placed at (x, q), cells with body,
//                 type, status
// The topology and the arrays that do not change during a run (connectivity, body, type) are
// built at the first frame and kept; a frame only fills the positions (and orientations,
// velocities, status) into the kept arrays, then VTK's XML writer writes them as raw binary
// appended data (no base64, 32-bit ids), compressed with LZ4 by default: no per-body string
// formatting anywhere. Errors: lrigid::Error(ExitCode::Output) naming the path.
#pragma once
#include <future>
#include <memory>
#include <string>
#include <vector>

#include "body/tessellate.h"
#include "model/model.h"
#include "model/state.h"

namespace lrigid {

enum class VtpCompression { None, LZ4, ZLib };

// The surface the shapes series draws for a body type, in its body frame: a box as its 12
// triangles (its exact surface: a finer tessellation of flat faces draws the same picture and
// costs more to write), any other shape as body_surface(type, target_faces) (result_writer.h).
TriangleMesh series_surface(const BodyType& type, int target_faces);

class BodiesFrames {
 public:
  BodiesFrames(const Model& model, VtpCompression c = VtpCompression::LZ4);
  ~BodiesFrames();
  void write(const State& state, const std::string& path);

 private:
  struct Impl;
  std::unique_ptr<Impl> p_;
};

class ShapesFrames {
 public:
  // surfaces: one per body type, in the body frame (result_writer.h body_surface)
  ShapesFrames(std::vector<TriangleMesh> surfaces, VtpCompression c = VtpCompression::LZ4);
  ~ShapesFrames();
  void write(const State& state, const std::string& path);

 private:
  struct Impl;
  std::unique_ptr<Impl> p_;
};

// Both series on a thread of their own, one frame at a time: write() copies what a
// frame needs (t, positions, orientations, velocities, seen turbulence, types, status) and
// returns while the frame is written, so the simulation goes on meanwhile; the next write()
// and wait() first wait for the frame before and rethrow its error. Destroying it waits too.
class FramesThread {
 public:
  FramesThread(const Model& model, std::vector<TriangleMesh> surfaces,
               VtpCompression c = VtpCompression::LZ4);
  ~FramesThread();
  void write(const State& state, std::string bodies_path, std::string shapes_path);
  void wait();

 private:
  BodiesFrames bodies_;
  ShapesFrames shapes_;
  State copy_;
  std::future<void> pending_;
};

}  // namespace lrigid
