#include "io/result_writer.h"

#include <unistd.h>

#include <algorithm>
#include <charconv>
#include <chrono>
#include <cinttypes>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <filesystem>
#include <iomanip>
#include <sstream>

#include "body/solidify.h"
#include "contact/bodies.h"
#include "body/tessellate.h"
#include "effects/registry.h"
#include "io/atomic_file.h"
#include "io/results_dir.h"
#include "integrate/simulation.h"
#include "io/checkpoint.h"
#include "io/dcc_cache.h"
#include "io/mesh_io.h"
#include "util/error.h"

namespace lrigid {

Vec3 body_velocity(const Model& m, const State& st, size_t i, const Mat3& R) {
  Vec3 v = R * st.v[i];
  if (m.turbulence_model == TurbulenceModel::Body &&
      m.types[st.type[i]].effects.has(Effect::Turbulence))
    v += st.u_seen[i];
  return v;
}


namespace fs = std::filesystem;

TriangleMesh body_surface(const BodyType& type, int target_faces) {
  TriangleMesh m = tessellate(type.shape, target_faces);
  for (Vec3& v : m.vertices) v -= type.com;
  return m;
}

int shape_faces_for(size_t bodies) {
  // about 24,000 triangles a frame in all (a few hundred kB compressed), 20 to 320 per body
  const size_t per_body = bodies > 0 ? 24000 / bodies : 320;
  return int(std::clamp<size_t>(per_body, 20, 320));
}

namespace {

// the frames so far, inside the temporary folders (docs/outputs.md, "During the run")
constexpr const char* kPartialBodies = "bodies.partial.pvd";
constexpr const char* kPartialShapes = "shapes.partial.pvd";

// <name>_NNNNNN.vtp
std::string frame_name(const char* stem, size_t i) {
  std::ostringstream name;
  name << stem << "_" << std::setw(6) << std::setfill('0') << i << ".vtp";
  return name.str();
}

void make_dir(const std::string& d) {
  std::error_code ec;
  fs::create_directories(d, ec);
  if (ec) throw Error(ExitCode::Output, where(d, "", "cannot create: " + ec.message()));
}

// a ParaView collection of `frames`, each file named `prefix` + its name; a partial one (the
// frames so far of a run that goes on, or was interrupted) says so in a comment, and is not
// fsync'ed (a view of the run, rewritten at every checkpoint and on resume)
void write_pvd(const fs::path& path, const std::string& prefix,
               const std::vector<std::pair<double, std::string>>& frames, bool partial = false) {
  write_file_atomically(path.string(), [&](std::ostream& o) {
    o << "<?xml version=\"1.0\"?>\n";
    if (partial)
      o << "<!-- PARTIAL: the frames written so far by a run that is still going on or was "
           "interrupted; not a result (results appear only with summary.json) -->\n";
    o << "<VTKFile type=\"Collection\" version=\"0.1\">\n  <Collection>\n"
      << std::setprecision(12);
    for (const auto& f : frames)
      o << "    <DataSet timestep=\"" << f.first << "\" group=\"\" part=\"0\" file=\"" << prefix
        << f.second << "\"/>\n";
    o << "  </Collection>\n</VTKFile>\n";
  }, !partial);
}

}  // namespace

ResultWriter::ResultWriter(const std::string& dir, const Model& model, const OutputSpec& spec,
                           const std::string& resume_tag, bool force)
    : dir_(dir), model_(model), spec_(spec), tag_(".tmp" + std::to_string(::getpid())),
      force_(force) {
  ensure_writable_directory(dir_);
  // the names this run writes must be free or lrigid's own (io/results_dir.h): refused now,
  // before the run, not after it
  check_may_write(dir_, planned(), force_);
  // a resumed run goes on with the interrupted one's temporaries, under their names (renaming
  // them would leave the checkpoint pointing at nothing if this run were killed before its
  // first checkpoint)
  if (!resume_tag.empty()) {
    tag_ = resume_tag;
    // the output so far belongs to the checkpoint: whatever happens, this writer removes none
    // of it (a resume that fails its checks leaves everything for the next attempt; the
    // interrupted finish's leftovers go in restore, once the checks have passed)
    keep_ = true;
  }
  auto take_over = [&](const std::string& name) {
    const fs::path p = fs::path(dir_) / (name + tag_);
    std::error_code ec;
    if (!resume_tag.empty() && !fs::exists(p, ec))
      fail_input(p.string(), "", "missing: the interrupted run's output so far is gone");
  };
  if (spec_.csv) {
    take_over("trajectories.csv");
    csv_tmp_ = (fs::path(dir_) / ("trajectories.csv" + tag_)).string();
    csv_ = std::fopen(csv_tmp_.c_str(), resume_tag.empty() ? "w" : "r+");
    if (!csv_) throw Error(ExitCode::Output, where(csv_tmp_, "", "cannot open for writing"));
    if (resume_tag.empty()) std::fputs("body,type,t,x,y,z,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz,state\n", csv_);
  }
  if (spec_.pvd) {
    take_over("bodies");
    take_over("shapes");
    vtp_tmp_dir_ = (fs::path(dir_) / ("bodies" + tag_)).string();
    make_dir(vtp_tmp_dir_);
    shapes_tmp_dir_ = (fs::path(dir_) / ("shapes" + tag_)).string();
    make_dir(shapes_tmp_dir_);
    const int faces = shape_faces_for(model_.body_count);
    std::vector<TriangleMesh> surfaces;
    for (const BodyType& t : model_.types) surfaces.push_back(series_surface(t, faces));
    vtp_ = std::make_unique<FramesThread>(model_, std::move(surfaces));
  }
  if (keeps_frames()) {
    // the caches for DCC tools keep every frame in memory until the end (x and q, 56 bytes a
    // sample; 48 more with the velocities)
    const double frames = std::floor(model_.duration / spec_.every + 1e-9) + 2;
    const double sample = sizeof(Vec3) + sizeof(Quat) + (keeps_velocities() ? 2 * sizeof(Vec3) : 0);
    const double need = frames * double(model_.body_count) * sample;
    const double have = double(sysconf(_SC_PHYS_PAGES)) * double(sysconf(_SC_PAGE_SIZE));
    if (need > 0.5 * have) {
      char buf[280];
      std::snprintf(buf, sizeof buf,
                    "the caches for DCC tools (\"glb\", \"glb_instanced\", \"houdini\", \"usd\") "
                    "would keep %.1f GiB of frames in memory (%.1f GiB here); drop them and bake "
                    "afterwards with lrigid export-gltf, or raise output.every",
                    need / (1 << 30), have / (1 << 30));
      throw Error(ExitCode::Resource, where(model_.scene_file, "output.formats", buf));
    }
    for (const BodyType& t : model_.types)
      gltf_.types.push_back({t.name, body_surface(t, 320), t.spec, t.variant});
  }
}

bool ResultWriter::keeps_frames() const {
  for (const DccFormat& d : kDccFormats)
    if (spec_.*d.enabled) return true;
  return false;
}

bool ResultWriter::keeps_velocities() const {
  for (const DccFormat& d : kDccFormats)
    if (spec_.*d.enabled && d.velocities) return true;
  return false;
}

std::vector<ResultItem> ResultWriter::planned() const {
  std::vector<ResultItem> v;
  if (model_.has_ground) v.push_back({"landings.csv", false, ""});
  if (spec_.csv) v.push_back({"trajectories.csv", false, ""});
  if (spec_.pvd) {
    v.push_back({"bodies", true, ""});
    v.push_back({"bodies.pvd", false, ""});
    v.push_back({"shapes", true, ""});
    v.push_back({"shapes.pvd", false, ""});
  }
  for (const DccFormat& d : kDccFormats)
    if (spec_.*d.enabled) v.push_back({d.file, false, ""});
  v.push_back({"summary.json", false, ""});
  return v;
}

void ResultWriter::remove_stale_temporaries() const {
  // A run killed while finishing leaves the final files it had begun under the interrupted run's
  // tag (landings.csv.tmp42, animation.glb.tmp42.tmp42, ...). This run writes them all again, so
  // they go; the output so far (the trajectories, the frame folders) stays: it goes on from it.
  const std::string keep[] = {"trajectories.csv" + tag_, "bodies" + tag_, "shapes" + tag_};
  std::error_code ec;
  for (const fs::directory_entry& e : fs::directory_iterator(dir_, ec)) {
    const std::string name = e.path().filename().string();
    const size_t at = name.find(tag_);
    if (at == std::string::npos || std::find(std::begin(keep), std::end(keep), name) != std::end(keep))
      continue;
    const size_t after = at + tag_.size();
    if (after == name.size() || name[after] == '.') fs::remove_all(e.path(), ec);
  }
  // inside the frame folders: the partial series' own temporaries (bodies.partial.pvd.tmp42,
  // io/atomic_file.h) of a run killed while rewriting them
  for (const char* folder : {"bodies", "shapes"}) {
    const fs::path d = fs::path(dir_) / (folder + tag_);
    for (const fs::directory_entry& e : fs::directory_iterator(d, ec)) {
      const std::string name = e.path().filename().string();
      const size_t at = name.rfind(".tmp");
      if (at != std::string::npos && at + 4 < name.size() &&
          name.find_first_not_of("0123456789", at + 4) == std::string::npos)
        fs::remove(e.path(), ec);
    }
  }
}

ResultWriter::~ResultWriter() {
  vtp_.reset();  // the frame being written, if any, before its folder can go
  if (finished_) return;
  if (keep_) {
    // a checkpoint refers to the temporaries: keep them for lrigid run --resume
    if (csv_) std::fclose(csv_);
    csv_ = nullptr;
    return;
  }
  cleanup();
}

void ResultWriter::save(BinaryOut& out) {
  if (vtp_) vtp_->wait(), write_partial_pvds();  // the checkpoint counts the last frame
  // the output so far durable and checksummed before the checkpoint that counts it: a power
  // loss then leaves a checkpoint whose files are all there, and a resume that finds them
  // otherwise refuses
  uint64_t csv_bytes = 0;
  if (csv_) {
    if (std::fflush(csv_) != 0 || std::ferror(csv_) || ::fsync(fileno(csv_)) != 0)
      throw Error(ExitCode::Output, where(csv_tmp_, "", "write failed (disk full?)"));
    const long pos = std::ftell(csv_);
    if (pos < 0) throw Error(ExitCode::Output, where(csv_tmp_, "", "cannot tell its length"));
    csv_bytes = uint64_t(pos);
    if (!checksum_range(csv_tmp_, csv_summed_, csv_bytes, &csv_sum_))
      throw Error(ExitCode::Output, where(csv_tmp_, "", "cannot be read back"));
    csv_summed_ = csv_bytes;
  }
  if (spec_.pvd) {
    for (size_t i = frame_sums_.size(); i < frames_.size(); ++i) {
      FrameSum fs_{};
      const std::string b = (fs::path(vtp_tmp_dir_) / frame_name("bodies", i)).string();
      const std::string sh = (fs::path(shapes_tmp_dir_) / frame_name("shapes", i)).string();
      std::error_code ec;
      fs_.bodies_bytes = fs::file_size(b, ec);
      fs_.shapes_bytes = fs::file_size(sh, ec);
      Fnv64 fb, fsh;
      if (!checksum_range(b, 0, fs_.bodies_bytes, &fb))
        throw Error(ExitCode::Output, where(b, "", "cannot be read back"));
      if (!checksum_range(sh, 0, fs_.shapes_bytes, &fsh))
        throw Error(ExitCode::Output, where(sh, "", "cannot be read back"));
      fs_.bodies_sum = fb.h;
      fs_.shapes_sum = fsh.h;
      sync_path(b);
      sync_path(sh);
      frame_sums_.push_back(fs_);
    }
    sync_path(vtp_tmp_dir_);
    sync_path(shapes_tmp_dir_);
  }
  sync_path(dir_);
  out.str(tag_);
  out.pod(csv_bytes);
  out.pod(csv_sum_.h);
  out.pod(uint64_t(frames_.size()));
  for (const auto& f : frames_) {
    out.pod(f.first);
    out.str(f.second);
  }
  out.vec(frame_sums_);
  out.vec(gltf_.body_type);
  out.vec(gltf_.times);
  out.vec(gltf_.x);
  out.vec(gltf_.q);
  out.vec(gltf_.hidden);
  out.vec(gltf_.state);
  out.vec(gltf_.v);
  out.vec(gltf_.w);
}

void ResultWriter::restore(BinaryIn& in) {
  std::string old_tag;
  in.str(&old_tag);
  // the temporaries the checkpoint counts are the ones latest.json names
  if (old_tag != tag_)
    fail_input(in.file(), "",
               "counts the temporaries *" + old_tag + ", latest.json names *" + tag_ +
                   ": the two are not of one run");
  uint64_t csv_bytes = 0, csv_sum = 0, nframes = 0;
  in.pod(&csv_bytes);
  in.pod(&csv_sum);
  in.pod(&nframes);
  if (nframes > (uint64_t(1) << 32)) fail_input(in.file(), "", "corrupt checkpoint (frames)");
  frames_.resize(nframes);
  for (auto& f : frames_) {
    in.pod(&f.first);
    in.str(&f.second);
  }
  in.vec(&frame_sums_);
  if (spec_.pvd && frame_sums_.size() != frames_.size())
    fail_input(in.file(), "", "corrupt checkpoint (frame checksums)");
  in.vec(&gltf_.body_type);
  in.vec(&gltf_.times);
  in.vec(&gltf_.x);
  in.vec(&gltf_.q);
  in.vec(&gltf_.hidden);
  in.vec(&gltf_.state);
  in.vec(&gltf_.v);
  in.vec(&gltf_.w);
  // the output so far as the checkpoint counted it, before anything is changed
  const std::string again =
      ": the output so far differs from what the checkpoint counted (cut short, changed or "
      "lost), so the run cannot go on from it; nothing was removed. Put the file back as it "
      "was, or start the run afresh (remove " + dir_ + "/checkpoint first)";
  if (csv_) {
    Fnv64 f;
    std::error_code ec;
    const uintmax_t have = fs::file_size(csv_tmp_, ec);
    if (ec || have < csv_bytes)
      fail_input(csv_tmp_, "",
                 std::to_string(ec ? 0 : have) + " bytes where the checkpoint counts " +
                     std::to_string(csv_bytes) + again);
    if (!checksum_range(csv_tmp_, 0, csv_bytes, &f) || f.h != csv_sum)
      fail_input(csv_tmp_, "", "checksum of its first " + std::to_string(csv_bytes) +
                                   " bytes " + f.hex() + ", the checkpoint's " +
                                   Fnv64{csv_sum}.hex() + again);
    csv_sum_ = f;
    csv_summed_ = csv_bytes;
  }
  for (size_t i = 0; spec_.pvd && i < frames_.size(); ++i) {
    const FrameSum& want = frame_sums_[i];
    const std::pair<std::string, std::pair<uint64_t, uint64_t>> files[] = {
        {(fs::path(vtp_tmp_dir_) / frame_name("bodies", i)).string(),
         {want.bodies_bytes, want.bodies_sum}},
        {(fs::path(shapes_tmp_dir_) / frame_name("shapes", i)).string(),
         {want.shapes_bytes, want.shapes_sum}}};
    for (const auto& [path, sum] : files) {
      std::error_code ec;
      const uintmax_t have = fs::file_size(path, ec);
      if (ec) fail_input(path, "", "missing" + again);
      Fnv64 f;
      if (have != sum.first || !checksum_range(path, 0, have, &f) || f.h != sum.second)
        fail_input(path, "", std::to_string(have) + " bytes with checksum " + f.hex() +
                                 ", the checkpoint's " + std::to_string(sum.first) +
                                 " bytes with " + Fnv64{sum.second}.hex() + again);
    }
  }
}

void ResultWriter::go_on() {
  remove_stale_temporaries();
  if (csv_) {
    // lines written after the checkpoint are written again
    if (std::fflush(csv_) != 0 || ::ftruncate(fileno(csv_), off_t(csv_summed_)) != 0 ||
        std::fseek(csv_, 0, SEEK_END) != 0)
      throw Error(ExitCode::Output, where(csv_tmp_, "", "cannot cut back to the checkpoint"));
  }
  if (spec_.pvd) write_partial_pvds();
}

void ResultWriter::write_partial_pvds() const {
  write_pvd(fs::path(vtp_tmp_dir_) / kPartialBodies, "", frames_, true);
  auto shape_frames = frames_;
  for (size_t i = 0; i < shape_frames.size(); ++i) shape_frames[i].second = frame_name("shapes", i);
  write_pvd(fs::path(shapes_tmp_dir_) / kPartialShapes, "", shape_frames, true);
}

void ResultWriter::cleanup() {
  if (csv_) std::fclose(csv_);
  csv_ = nullptr;
  std::error_code ec;
  if (!csv_tmp_.empty()) fs::remove(csv_tmp_, ec);
  if (!vtp_tmp_dir_.empty()) fs::remove_all(vtp_tmp_dir_, ec);
  if (!shapes_tmp_dir_.empty()) fs::remove_all(shapes_tmp_dir_, ec);
  for (const ResultItem& p : staged_) fs::remove_all(fs::path(dir_) / p.tmp, ec);
  staged_.clear();
}

void ResultWriter::write_frame(const State& st) {
  if (csv_) {
    // the frame's rows built in memory with std::to_chars (append_number: the same digits as
    // printf's %.9g, a few times faster), then one write
    csv_line_.clear();
    for (size_t i = 0; i < st.size(); ++i) {
      // a body waiting for its release has no row (read_results: a frame lists the bodies
      // released by then)
      if (st.status[i] == BodyStatus::Unreleased) continue;
      const Mat3 R = st.q[i].toRotationMatrix();
      const Vec3 v = body_velocity(model_, st, i, R), w = R * st.w[i];
      const Quat& q = st.q[i];
      char b[24];
      csv_line_.append(b, std::to_chars(b, b + sizeof b, i).ptr);
      csv_line_ += ',';
      csv_line_ += model_.types[st.type[i]].name;
      for (const double x : {st.t, st.x[i].x(), st.x[i].y(), st.x[i].z(), q.w(), q.x(), q.y(),
                             q.z(), v.x(), v.y(), v.z(), w.x(), w.y(), w.z()}) {
        csv_line_ += ',';
        append_number(&csv_line_, x);
      }
      csv_line_ += ',';
      csv_line_ += st.state_name(i);
      csv_line_ += '\n';
    }
    if (std::fwrite(csv_line_.data(), 1, csv_line_.size(), csv_) != csv_line_.size() ||
        std::ferror(csv_))
      throw Error(ExitCode::Output, where(csv_tmp_, "", "write failed (disk full?)"));
  }
  if (spec_.pvd) {
    const size_t i = frames_.size();
    // the frames written so far, openable while the run goes on (the one before this one was
    // being written on the frames' thread: wait for it first); rewritten at most every half
    // second of wall time, as the list grows with the run (and at every checkpoint)
    vtp_->wait();
    const auto now = std::chrono::steady_clock::now();
    if (frames_.empty() || now - partial_written_ >= std::chrono::milliseconds(500)) {
      write_partial_pvds();
      partial_written_ = now;
    }
    vtp_->write(st, (fs::path(vtp_tmp_dir_) / frame_name("bodies", i)).string(),
                (fs::path(shapes_tmp_dir_) / frame_name("shapes", i)).string());
    frames_.emplace_back(st.t, frame_name("bodies", i));
  }
  if (keeps_frames()) {
    if (gltf_.body_type.empty())
      for (size_t i = 0; i < st.size(); ++i) gltf_.body_type.push_back(st.type[i]);
    gltf_.times.push_back(st.t);
    gltf_.x.insert(gltf_.x.end(), st.x.begin(), st.x.end());
    gltf_.q.insert(gltf_.q.end(), st.q.begin(), st.q.end());
    gltf_.hidden.insert(gltf_.hidden.end(), st.hidden.begin(), st.hidden.end());
    gltf_.hidden.resize(gltf_.x.size(), 0);
    for (size_t i = 0; i < st.size(); ++i) gltf_.state.push_back(st.state_code(i));
    if (keeps_velocities())
      for (size_t i = 0; i < st.size(); ++i) {
        const Mat3 R = st.q[i].toRotationMatrix();
        gltf_.v.push_back(body_velocity(model_, st, i, R));
        gltf_.w.push_back(R * st.w[i]);
      }
  }
}

void ResultWriter::finish(const State& st, const RunStats& stats, const nlohmann::json& extra) {
  using nlohmann::json;
  // Every file is first written completely under a temporary name; only then are they all
  // renamed into place, summary.json last (commit_staged). A failure anywhere before that
  // leaves no final-looking file; a failing rename puts back what was there before.
  if (vtp_) vtp_->wait();
  const fs::path d(dir_);
  auto staged = [&](const std::string& name, bool is_dir = false) {
    const std::string tmp = (d / (name + tag_)).string();
    staged_.push_back({name, is_dir, name + tag_});
    return tmp;
  };
  if (model_.has_ground) {
    write_file_atomically(staged("landings.csv"), [&](std::ostream& o) {
      o << "body,type,t,x,y,z\n" << std::setprecision(9);
      // each body's first touchdown: where it landed (ground.contact "stop") or first touched
      // the ground (contact/pass.h), so the landing statistics keep their meaning
      for (size_t i = 0; i < st.size(); ++i) {
        if (st.status[i] == BodyStatus::Landed)
          o << i << ',' << model_.types[st.type[i]].name << ',' << st.t_stop[i] << ','
            << st.x[i].x() << ',' << st.x[i].y() << ',' << st.x[i].z() << '\n';
        else if (i < st.t_touch.size() && !std::isnan(st.t_touch[i]))
          o << i << ',' << model_.types[st.type[i]].name << ',' << st.t_touch[i] << ','
            << st.x_touch[i].x() << ',' << st.x_touch[i].y() << ',' << st.x_touch[i].z() << '\n';
      }
    });
  }
  if (csv_) {
    const bool bad = std::fflush(csv_) != 0 || std::ferror(csv_) || std::fclose(csv_) != 0;
    csv_ = nullptr;
    if (bad) throw Error(ExitCode::Output, where(csv_tmp_, "", "write failed (disk full?)"));
    staged_.push_back({"trajectories.csv", false, "trajectories.csv" + tag_});
    csv_tmp_.clear();
  }
  if (spec_.pvd) {
    std::error_code ec;
    fs::remove(fs::path(vtp_tmp_dir_) / kPartialBodies, ec);
    fs::remove(fs::path(shapes_tmp_dir_) / kPartialShapes, ec);
    staged_.push_back({"bodies", true, "bodies" + tag_});
    vtp_tmp_dir_.clear();
    write_pvd(staged("bodies.pvd"), "bodies/", frames_);
    staged_.push_back({"shapes", true, "shapes" + tag_});
    shapes_tmp_dir_.clear();
    auto shape_frames = frames_;
    for (size_t i = 0; i < shape_frames.size(); ++i)
      shape_frames[i].second = frame_name("shapes", i);
    write_pvd(staged("shapes.pvd"), "shapes/", shape_frames);
  }
  for (const DccFormat& d : kDccFormats)
    if (spec_.*d.enabled) d.write(staged(d.file), gltf_);
  json s;
  s["bodies"] = st.size();
  s["body_steps"] = stats.body_steps;
  s["steps"] = stats.steps;
  s["wall_seconds"] = stats.wall_seconds;
  s["body_steps_per_second"] =
      stats.wall_seconds > 0 ? double(stats.body_steps) / stats.wall_seconds : 0.0;
  s["effects"] = effect_names(model_.union_effects());
  json types = json::array();
  for (const BodyType& t : model_.types) {
    std::string why_not_batched;
    const StepKind kind = step_kind(model_, t, &why_not_batched);
    types.push_back(
        {{"name", t.name},
         {"entry", t.spec},
         {"variant", t.variant},
         {"count", t.count},
         {"mass", t.mass},
         {"volume", t.volume},
         {"effects", effect_names(t.effects)},
         // which step it took (integrate/simulation.h) and, for the scalar one, why not batched
         {"step", step_kind_name(kind)},
         {"not_batched_because", why_not_batched},
         {"added_mass_method", t.added_mass_method},
         {"added_mass_panels", t.added_mass_panels},
         {"first_body", t.first_body},
         // enough to rebuild the surface (lrigid export-gltf, lrigid render)
         {"shape",
          {{"type", shape_type_name(t.shape.type)},
           {"half_extents",
            {t.shape.half_extents.x(), t.shape.half_extents.y(), t.shape.half_extents.z()}},
           {"source", t.shape.source}}},
         {"com", {t.com.x(), t.com.y(), t.com.z()}}});
    if (t.shape.type == ShapeType::Mesh) {
      types.back()["shape"]["scale"] = t.shape.scale;
      types.back()["shape"]["thickness"] = t.shape.thickness;
    }
  }
  s["body_types"] = types;
  s["integrator"] = integrator_name(model_.integrator);
  s["dt"] = model_.dt;
  s["duration"] = model_.duration;
  s["seed"] = model_.seed;
  s["turbulence"] = {{"model", turbulence_model_name(model_.turbulence_model)},
                     {"drift", drift_name(model_.drift)}};
  s["landed"] = stats.landed;
  s["exited"] = stats.exited;
  s["failed"] = stats.failed;
  // contacts (docs/contacts.md): each body's state at the end, the contact events (touches
  // after flying) and the first touchdowns on the ground, bodies removed at the grid's edge
  {
    json states = json::object();
    for (const char* name : kStateNames) states[name] = 0;
    uint64_t events = 0;
    size_t touched = 0, hidden = 0, released = 0;
    for (size_t i = 0; i < st.size(); ++i) {
      states[st.state_name(i)] = states[st.state_name(i)].get<size_t>() + 1;
      if (i < st.impacts.size()) events += st.impacts[i];
      if (i < st.t_touch.size()) touched += !std::isnan(st.t_touch[i]);
      if (i < st.hidden.size()) hidden += st.hidden[i] && st.status[i] == BodyStatus::Exited;
      released += st.status[i] != BodyStatus::Unreleased;
    }
    s["states"] = states;
    // bodies released by the end (bodies[i].release; all of them without it)
    s["released"] = released;
    s["contacts"] = {{"ground", model_.has_ground ? contact_mode_name(model_.ground_contact)
                                                  : "none"},
                     {"walls", contact_mode_name(model_.walls_contact)},
                     {"walls_active", model_.walls_collide()},
                     {"outside", outside_mode_name(model_.outside)},
                     {"events", events},
                     {"touched_ground", touched},
                     {"removed", hidden}};
    // contacts between bodies: the mode, the touching pairs summed over the steps, the sleeping
    // bodies a contact woke, and the deepest overlap of two bodies at the end (m)
    json bc = {{"mode", model_.body_contact ? "collide" : "off"},
               {"pair_steps", stats.pair_steps},
               {"woken", stats.pair_wakes}};
    if (model_.body_contact) bc["deepest_overlap_end"] = deepest_pair_overlap(model_, st);
    s["body_contact"] = bc;
  }
  json stopped = json::array();
  for (size_t i = 0; i < st.size() && stopped.size() < 1000; ++i)
    if (st.status[i] == BodyStatus::Exited || st.status[i] == BodyStatus::Failed)
      stopped.push_back({{"body", i},
                         {"status", body_status_name(st.status[i])},
                         {"t", st.t_stop[i]},
                         {"reason", st.reason[i]}});
  s["stopped"] = stopped;
  s["version"] = LRIGID_VERSION;
  s["scene"] = model_.scene_file;
  s["output_every"] = spec_.every;
  json outputs = json::array();
  if (spec_.csv) outputs.push_back("trajectories.csv");
  if (spec_.pvd) outputs.insert(outputs.end(), {"bodies.pvd", "shapes.pvd"});
  for (const DccFormat& d : kDccFormats)
    if (spec_.*d.enabled) outputs.push_back(d.file);
  s["outputs"] = outputs;
  s["field"] = nullptr;  // the grid (.vti/.pvd) the run sampled; cmd_run fills it in
  s["ground_z"] = model_.has_ground ? json(model_.ground_z) : json(nullptr);
  s.update(extra);
  write_file_atomically(staged("summary.json"), [&](std::ostream& o) { o << s.dump(2) << '\n'; });
  // summary.json is the last one
  commit_results(dir_, staged_, force_, checkpoint_dir_);
  staged_.clear();
  finished_ = true;
}

namespace {

Shape shape_from_summary(const nlohmann::json& j, const std::string& file, const std::string& key) {
  try {
    const std::string type = j.at("type").get<std::string>();
    const auto h = j.at("half_extents");
    const Vec3 he(h.at(0).get<double>(), h.at(1).get<double>(), h.at(2).get<double>());
    if (type == "sphere") return Shape::sphere(he.x());
    if (type == "ellipsoid") return Shape::ellipsoid(he.x(), he.y(), he.z());
    if (type == "box") return Shape::box(2 * he.x(), 2 * he.y(), 2 * he.z());
    if (type == "mesh") {
      const std::string src = j.at("source").get<std::string>();
      auto mesh = std::make_shared<TriangleMesh>(read_mesh(src));
      // the scale the run applied (its scene's, times a variant's); results without it: from
      // the extents
      double scale = j.value("scale", 0.0);
      if (!(scale > 0)) {
        Vec3 lo = Vec3::Constant(1e300), hi = Vec3::Constant(-1e300);
        for (const Vec3& v : mesh->vertices) lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
        const double half = 0.5 * (hi - lo).maxCoeff();
        scale = half > 0 ? he.maxCoeff() / half : 1.0;
      }
      for (Vec3& v : mesh->vertices) v *= scale;
      // a single-sided surface: the thin body the run simulated (body/solidify.h)
      const double thickness = j.value("thickness", 0.0);
      if (thickness > 0) *mesh = solidify_surface(*mesh, thickness, src);
      return Shape::from_mesh(std::move(mesh), src);
    }
    fail_input(file, key + ".type", "unknown shape type \"" + type + "\"");
  } catch (const nlohmann::json::exception& e) {
    fail_input(file, key, std::string("malformed shape: ") + e.what());
  }
}

}  // namespace

Results read_results(const std::string& dir, int target_faces) {
  // a finish that a kill interrupted while moving the results into place is completed first
  complete_interrupted_finish(dir);
  Results r;
  const std::string sum_path = (fs::path(dir) / "summary.json").string();
  {
    std::ifstream in(sum_path);
    if (!in) fail_input(sum_path, "", fs::exists(sum_path) ? "cannot be read" : "file not found");
    try {
      r.summary = nlohmann::json::parse(in);
    } catch (const nlohmann::json::exception& e) {
      fail_input(sum_path, "", std::string("not valid JSON: ") + e.what());
    }
  }
  GltfAnimation& a = r.frames;
  std::vector<std::string> names;
  try {
    const auto& types = r.summary.at("body_types");
    for (size_t i = 0; i < types.size(); ++i) {
      const std::string key = "body_types[" + std::to_string(i) + "]";
      const auto& t = types[i];
      if (!t.contains("shape"))
        fail_input(sum_path, key + ".shape",
                   "missing (results written before lrigid recorded shapes)");
      BodyType bt;
      bt.name = t.at("name").get<std::string>();
      bt.shape = shape_from_summary(t.at("shape"), sum_path, key + ".shape");
      const auto& c = t.at("com");
      bt.com = Vec3(c.at(0).get<double>(), c.at(1).get<double>(), c.at(2).get<double>());
      a.types.push_back({bt.name, body_surface(bt, target_faces), t.value("entry", i),
                         t.value("variant", 0)});
      names.push_back(bt.name);
      for (size_t k = 0; k < t.at("count").get<size_t>(); ++k) a.body_type.push_back(int(i));
    }
  } catch (const nlohmann::json::exception& e) {
    fail_input(sum_path, "body_types", e.what());
  }
  const size_t nb = a.body_type.size();
  const std::string csv = (fs::path(dir) / "trajectories.csv").string();
  std::ifstream in(csv);
  if (!in)
    fail_input(
        csv, "",
        fs::exists(csv) ? "cannot be read" : "file not found (needs \"csv\" in output.formats)");
  std::string line;
  std::getline(in, line);
  if (line.rfind("body,type,t,x,y,z,qw,qx,qy,qz", 0) != 0)
    fail_input(csv, "line 1", "unexpected header \"" + line + "\"");
  // the state column (newer runs): bodies removed at the grid's edge ("outside": "remove") are
  // hidden from their exit on; a body exited otherwise (stopped at a solid) stays visible
  const bool has_velocities =
      line.rfind("body,type,t,x,y,z,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz", 0) == 0;
  const bool has_state = line.size() >= 6 && line.compare(line.size() - 6, 6, ",state") == 0;
  std::vector<uint8_t> removed(nb, 0);
  if (has_state && r.summary.contains("contacts") &&
      r.summary["contacts"].value("outside", "") == "remove") {
    std::fill(removed.begin(), removed.end(), 1);
    if (r.summary.contains("stopped"))
      for (const auto& e : r.summary["stopped"])
        if (e.value("reason", "") != "left the grid" && e.value("body", nb) < nb)
          removed[e.value("body", nb)] = 0;
  }
  // Rows go frame by frame, bodies in increasing order (a body number not above the one before
  // starts a frame). A frame lists every body released by then (bodies[i].release), so a body is
  // missing only from the frames before its first row: there it is unreleased and hidden, at its
  // first recorded pose.
  const uint8_t unreleased = uint8_t(state_code_from_name("unreleased"));
  std::vector<uint8_t> has_row;  // (nframe * nbody)
  size_t line_no = 1;
  long prev_body = -1;
  while (std::getline(in, line)) {
    ++line_no;
    if (line.empty()) continue;
    const std::string at = "line " + std::to_string(line_no);
    const char* p = line.c_str();
    char* end = nullptr;
    const unsigned long body = std::strtoul(p, &end, 10);
    if (end == p || *end != ',') fail_input(csv, at, "malformed row \"" + line + "\"");
    if (body >= nb)
      fail_input(csv, at, "body " + std::to_string(body) + " of " + std::to_string(nb) +
                              " bodies (summary.json)");
    p = std::strchr(end + 1, ',');  // skip the type name
    if (!p) fail_input(csv, at, "malformed row \"" + line + "\"");
    double v[14] = {};
    for (int i = 0; i < (has_velocities ? 14 : 8); ++i) {
      double& x = v[i];
      x = std::strtod(p + 1, &end);
      if (end == p + 1 || (*end != ',' && *end != '\0'))
        fail_input(csv, at, "malformed number in \"" + line + "\"");
      p = end;
    }
    if (long(body) <= prev_body || a.times.empty()) {
      // a new frame: every body waiting until its row says otherwise
      a.times.push_back(v[0]);
      a.x.resize(a.x.size() + nb, Vec3::Zero());
      a.q.resize(a.q.size() + nb, Quat::Identity());
      has_row.resize(has_row.size() + nb, 0);
      if (has_velocities) {
        a.v.resize(a.v.size() + nb, Vec3::Zero());
        a.w.resize(a.w.size() + nb, Vec3::Zero());
      }
      if (has_state) {
        a.state.resize(a.state.size() + nb, unreleased);
        a.hidden.resize(a.hidden.size() + nb, 1);
      }
    } else if (v[0] != a.times.back()) {
      fail_input(csv, at, "t = " + std::to_string(v[0]) + " in the frame of t = " +
                              std::to_string(a.times.back()) + " (rows go frame by frame)");
    }
    prev_body = long(body);
    const size_t k = (a.times.size() - 1) * nb + body;
    has_row[k] = 1;
    a.x[k] = Vec3(v[1], v[2], v[3]);
    a.q[k] = Quat(v[4], v[5], v[6], v[7]);  // Eigen order w, x, y, z
    if (has_velocities) {
      a.v[k] = Vec3(v[8], v[9], v[10]);
      a.w[k] = Vec3(v[11], v[12], v[13]);
    }
    if (has_state) {
      const size_t c = line.rfind(',');
      const int code = state_code_from_name(line.substr(c + 1));
      if (code < 0) fail_input(csv, at, "unknown state \"" + line.substr(c + 1) + "\"");
      a.state[k] = uint8_t(code);
      a.hidden[k] = removed[body] && line.compare(c + 1, std::string::npos, "exited") == 0;
    }
  }
  if (nb == 0 || a.times.empty()) fail_input(csv, "", "no rows");
  const size_t nf = a.times.size();
  size_t released = 0;  // bodies with rows
  for (size_t b = 0; b < nb; ++b) {
    size_t first = 0;
    while (first < nf && !has_row[first * nb + b]) ++first;
    if (first > 0 && !has_state)
      fail_input(csv, "", "body " + std::to_string(b) + " has no row before " +
                              (first == nf ? std::string("the end")
                                           : "t = " + std::to_string(a.times[first])));
    if (first == nf) continue;  // never released in the run
    ++released;
    for (size_t f = first; f < nf; ++f)
      if (!has_row[f * nb + b])
        fail_input(csv, "", "body " + std::to_string(b) + " has no row at t = " +
                                std::to_string(a.times[f]) + " after its first one");
    for (size_t f = 0; f < first; ++f) {
      a.x[f * nb + b] = a.x[first * nb + b];
      a.q[f * nb + b] = a.q[first * nb + b];
    }
  }
  if (released != r.summary.value("released", nb))
    fail_input(csv, "", std::to_string(released) + " bodies have rows where summary.json says " +
                            std::to_string(r.summary.value("released", nb)) + " were released");
  return r;
}

}  // namespace lrigid
