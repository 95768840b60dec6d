#include "io/houdini_writer.h"

#include "io/atomic_file.h"
#include "io/dcc_cache.h"
#include "model/state.h"

namespace lrigid {

void write_houdini_csv(const std::string& path, const GltfAnimation& a) {
  check_animation(path, a, true);
  const size_t nb = a.bodies();
  const std::vector<Quat> q = continuous_orientations(a);
  write_file_atomically(path, [&](std::ostream& o) {
    o << kHoudiniHeader << '\n';
    std::string row;
    for (size_t f = 0; f < a.times.size(); ++f) {
      row.clear();
      for (size_t b = 0; b < nb; ++b) {
        if (a.hidden_at(f, b)) continue;
        const size_t k = f * nb + b;
        const GltfBodyType& t = a.types[size_t(a.body_type[b])];
        row += std::to_string(f + 1);
        row += ',';
        append_number(&row, a.times[f]);
        row += ',' + std::to_string(b) + ',' + t.name + ',' + std::to_string(t.variant) + ',';
        row += a.state.empty() ? "" : kStateNames[a.state[k]];
        const Vec3 &x = a.x[k], &v = a.v[k], &w = a.w[k];
        for (const double c : {x.x(), x.y(), x.z(), q[k].x(), q[k].y(), q[k].z(), q[k].w(), v.x(),
                               v.y(), v.z(), w.x(), w.y(), w.z()}) {
          row += ',';
          append_number(&row, c);
        }
        row += '\n';
      }
      o.write(row.data(), std::streamsize(row.size()));
    }
  });
}

}  // namespace lrigid
