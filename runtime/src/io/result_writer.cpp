#include "io/result_writer.h"

#include <unistd.h>
#include <vtkCellArray.h>
#include <vtkDoubleArray.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkUnsignedCharArray.h>
#include <vtkXMLPolyDataWriter.h>

#include <cinttypes>
#include <filesystem>
#include <iomanip>
#include <sstream>

#include "io/atomic_file.h"
#include "util/error.h"

namespace lrigid {

namespace fs = std::filesystem;

ResultWriter::ResultWriter(const std::string& dir, const Model& model, const OutputSpec& spec)
    : dir_(dir), model_(model), spec_(spec), tag_(".tmp" + std::to_string(::getpid())) {
  ensure_writable_directory(dir_);
  if (spec_.csv) {
    csv_tmp_ = (fs::path(dir_) / ("trajectories.csv" + tag_)).string();
    csv_ = std::fopen(csv_tmp_.c_str(), "w");
    if (!csv_) throw Error(ExitCode::Output, where(csv_tmp_, "", "cannot open for writing"));
    std::fputs("body,type,t,x,y,z,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz\n", csv_);
  }
  if (spec_.pvd) {
    vtp_tmp_dir_ = (fs::path(dir_) / ("bodies" + tag_)).string();
    std::error_code ec;
    fs::create_directories(vtp_tmp_dir_, ec);
    if (ec) throw Error(ExitCode::Output, where(vtp_tmp_dir_, "", "cannot create: " + ec.message()));
  }
}

ResultWriter::~ResultWriter() {
  if (!finished_) cleanup();
}

void ResultWriter::cleanup() {
  if (csv_) std::fclose(csv_);
  csv_ = nullptr;
  std::error_code ec;
  if (!csv_tmp_.empty()) fs::remove(csv_tmp_, ec);
  if (!vtp_tmp_dir_.empty()) fs::remove_all(vtp_tmp_dir_, ec);
}

void ResultWriter::write_frame(const State& st) {
  if (csv_) {
    for (size_t i = 0; i < st.size(); ++i) {
      const Mat3 R = st.q[i].toRotationMatrix();
      const Vec3 v = R * st.v[i], w = R * st.w[i];
      const Quat& q = st.q[i];
      std::fprintf(csv_,
                   "%zu,%s,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g\n",
                   i, model_.types[st.type[i]].name.c_str(), st.t, st.x[i].x(), st.x[i].y(),
                   st.x[i].z(), q.w(), q.x(), q.y(), q.z(), v.x(), v.y(), v.z(), w.x(), w.y(),
                   w.z());
    }
    if (std::ferror(csv_)) throw Error(ExitCode::Output, where(csv_tmp_, "", "write failed (disk full?)"));
  }
  if (spec_.pvd) {
    std::ostringstream name;
    name << "bodies_" << std::setw(6) << std::setfill('0') << frames_.size() << ".vtp";
    write_vtp(st, (fs::path(vtp_tmp_dir_) / name.str()).string());
    frames_.emplace_back(st.t, name.str());
  }
}

void ResultWriter::write_vtp(const State& st, const std::string& path) const {
  const vtkIdType n = static_cast<vtkIdType>(st.size());
  vtkNew<vtkPoints> pts;
  pts->SetDataTypeToDouble();
  pts->SetNumberOfPoints(n);
  vtkNew<vtkCellArray> verts;
  vtkNew<vtkDoubleArray> orient, vel, angvel;
  orient->SetName("orientation");  // quaternion w, x, y, z (body -> world)
  orient->SetNumberOfComponents(4);
  orient->SetNumberOfTuples(n);
  vel->SetName("velocity");
  vel->SetNumberOfComponents(3);
  vel->SetNumberOfTuples(n);
  angvel->SetName("angular_velocity");
  angvel->SetNumberOfComponents(3);
  angvel->SetNumberOfTuples(n);
  vtkNew<vtkIntArray> id, type;
  id->SetName("body");
  id->SetNumberOfTuples(n);
  type->SetName("type");
  type->SetNumberOfTuples(n);
  vtkNew<vtkUnsignedCharArray> status;
  status->SetName("status");  // 0 moving, 1 landed, 2 exited, 3 failed
  status->SetNumberOfTuples(n);
  for (vtkIdType i = 0; i < n; ++i) {
    const Mat3 R = st.q[i].toRotationMatrix();
    const Vec3 v = R * st.v[i], w = R * st.w[i];
    pts->SetPoint(i, st.x[i].data());
    verts->InsertNextCell(1, &i);
    const double q[4] = {st.q[i].w(), st.q[i].x(), st.q[i].y(), st.q[i].z()};
    orient->SetTuple(i, q);
    vel->SetTuple(i, v.data());
    angvel->SetTuple(i, w.data());
    id->SetValue(i, static_cast<int>(i));
    type->SetValue(i, st.type[i]);
    status->SetValue(i, static_cast<unsigned char>(st.status[i]));
  }
  vtkNew<vtkPolyData> poly;
  poly->SetPoints(pts);
  poly->SetVerts(verts);
  for (vtkDataArray* a : {static_cast<vtkDataArray*>(orient.Get()), static_cast<vtkDataArray*>(vel.Get()),
                          static_cast<vtkDataArray*>(angvel.Get()), static_cast<vtkDataArray*>(id.Get()),
                          static_cast<vtkDataArray*>(type.Get()), static_cast<vtkDataArray*>(status.Get())})
    poly->GetPointData()->AddArray(a);
  vtkNew<vtkXMLPolyDataWriter> w;
  w->SetFileName(path.c_str());
  w->SetInputData(poly);
  w->SetDataModeToAppended();
  w->SetCompressorTypeToZLib();
  if (w->Write() != 1) throw Error(ExitCode::Output, where(path, "", "cannot write .vtp frame"));
}

void ResultWriter::finish(const State& st, const RunStats& stats, const nlohmann::json& extra) {
  using nlohmann::json;
  // landings
  if (model_.has_ground) {
    write_file_atomically((fs::path(dir_) / "landings.csv").string(), [&](std::ostream& o) {
      o << "body,type,t,x,y,z\n" << std::setprecision(9);
      for (size_t i = 0; i < st.size(); ++i)
        if (st.status[i] == BodyStatus::Landed)
          o << i << ',' << model_.types[st.type[i]].name << ',' << st.t_stop[i] << ','
            << st.x[i].x() << ',' << st.x[i].y() << ',' << st.x[i].z() << '\n';
    });
  }
  if (csv_) {
    const bool bad = std::fclose(csv_) != 0;
    csv_ = nullptr;
    if (bad) throw Error(ExitCode::Output, where(csv_tmp_, "", "write failed (disk full?)"));
    fs::rename(csv_tmp_, fs::path(dir_) / "trajectories.csv");
    csv_tmp_.clear();
  }
  if (spec_.pvd) {
    const fs::path final_dir = fs::path(dir_) / "bodies";
    std::error_code ec;
    fs::remove_all(final_dir, ec);
    fs::rename(vtp_tmp_dir_, final_dir, ec);
    if (ec) throw Error(ExitCode::Output, where(final_dir.string(), "", "cannot move into place: " + ec.message()));
    vtp_tmp_dir_.clear();
    write_file_atomically((fs::path(dir_) / "bodies.pvd").string(), [&](std::ostream& o) {
      o << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n  <Collection>\n"
        << std::setprecision(12);
      for (const auto& f : frames_)
        o << "    <DataSet timestep=\"" << f.first << "\" group=\"\" part=\"0\" file=\"bodies/"
          << f.second << "\"/>\n";
      o << "  </Collection>\n</VTKFile>\n";
    });
  }
  json s;
  s["bodies"] = st.size();
  s["body_steps"] = stats.body_steps;
  s["steps"] = stats.steps;
  s["wall_seconds"] = stats.wall_seconds;
  s["body_steps_per_second"] =
      stats.wall_seconds > 0 ? double(stats.body_steps) / stats.wall_seconds : 0.0;
  s["effects"] = effect_names(model_.union_effects());
  json types = json::array();
  for (const BodyType& t : model_.types)
    types.push_back({{"name", t.name},
                     {"count", t.count},
                     {"mass", t.mass},
                     {"volume", t.volume},
                     {"effects", effect_names(t.effects)},
                     {"added_mass_method", t.added_mass_method},
                     {"added_mass_panels", t.added_mass_panels}});
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
  s.update(extra);
  write_file_atomically((fs::path(dir_) / "summary.json").string(),
                        [&](std::ostream& o) { o << s.dump(2) << '\n'; });
  finished_ = true;
}

}  // namespace lrigid
