#include "contact/bodies.h"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <numeric>

#include "contact/island.h"
#include "contact/pair_geometry.h"
#include "contact/pass.h"
#include "contact/sleep.h"
#include "contact/solver.h"
#include "contact/touching.h"
#include "model/body_state.h"

namespace lrigid {

PairMaterial pair_material(const ContactParams& a, const ContactParams& b) {
  return {std::max(a.restitution, b.restitution), std::sqrt(a.friction * b.friction),
          std::max(a.rolling_resistance, b.rolling_resistance)};
}

namespace {

// Sweeps of the projected Gauss-Seidel over an island's points (fewer once converged,
// kContactTolerance). A stack at rest passes its weight down one body per sweep, so an island at
// rest takes up to kIslandPassesPerBody sweeps per body, at most kIslandPasses: a stack of twenty
// boxes (240) then stands within 0.27 mm over 10 s and sleeps (with at most 32 it falls over),
// and two leaves resting on each other in the wind, which converge slowly and never sleep, take
// 24 (the wind scene: 12 % faster than with 256 for every island, the same bodies asleep at the
// end);
// an island of many points takes at most kIslandSweeps point-sweeps a step, and an island in
// motion (a point moving faster than its resting speed: an
// impact, a body sliding or spinning) kIslandMinPasses: their problem is a new one every step,
// which the sweeps' friction impulses, following the slip from point to point, converge to only
// slowly (two boxes meeting while one spins on the ground: still 0.2 of the tolerance's floor
// after 64 sweeps), and the warm start carries the sweeps' work from one step to the next
// (docs/contacts.md: the 1000-box pile, 3500 points, takes 18).
constexpr int kIslandPasses = 256;
constexpr int kIslandMinPasses = 16;
constexpr int kIslandSweeps = 1 << 16;
constexpr int kIslandPassesPerBody = 12;

// The warm start (island_resolve): a point takes the impulses of the last step's point of the
// same two bodies (or the same body and a surface) nearest to it, by their offsets from the
// lower body's centre of mass in the world frame, when that one is within this fraction of the
// smaller body's reach (docs/contacts.md)
constexpr double kWarmMatch = 0.1;

// The depth a touching point keeps, which the islands' position correction does not push out
// (island_resolve): kPositionSlop, or kSlopFraction of the thinner body's smallest half extent
// when that is less (paper 0.1 mm thick: 12.5 um). Without it every resting contact, which the
// step's position update takes a little into the surface, was pushed out each step and fell
// back: the 1000-box pile kept 66 boxes faster than 1 cm/s at 3 s; with 50 um it is at rest by
// 1.5 s, every box below 1 cm/s, and its deepest overlap at the end 58 um instead of 220 um
// (docs/contacts.md).
constexpr double kPositionSlop = 5e-5;
constexpr double kSlopFraction = 0.25;
double position_slop(const BodyType& a, const BodyType& b) {
  return std::min(kPositionSlop,
                  kSlopFraction * std::min(a.half_extents.minCoeff(), b.half_extents.minCoeff()));
}

bool key_less(const PairImpulse& x, const PairImpulse& y) {
  return x.a != y.a ? x.a < y.a : x.b < y.b;
}

// The last step's points of bodies a < b (b = PairImpulse::kSurface: a's surface points), and
// which of them a point has taken already
struct WarmRange {
  const PairImpulse* first = nullptr;
  int count = 0;
  uint64_t used = 0;
  WarmRange(const std::vector<PairImpulse>& cache, uint32_t a, uint32_t b) {
    PairImpulse key;
    key.a = a, key.b = b;
    const auto r = std::equal_range(cache.begin(), cache.end(), key, key_less);
    first = cache.data() + (r.first - cache.begin());
    count = int(std::min<ptrdiff_t>(r.second - r.first, 64));
  }
  // the nearest point not yet taken within tol of r, or nullptr
  const PairImpulse* take(const double* r, double tol) {
    int best = -1;
    double best_d2 = tol * tol;
    for (int k = 0; k < count; ++k) {
      if (used >> k & 1) continue;
      const double d[3] = {first[k].r[0] - r[0], first[k].r[1] - r[1], first[k].r[2] - r[2]};
      const double d2 = dot3(d, d);
      if (d2 < best_d2) best_d2 = d2, best = k;
    }
    if (best < 0) return nullptr;
    used |= uint64_t(1) << best;
    return first + best;
  }
};

// a body taking part in the stage
struct Cand {
  uint32_t body;
  bool dynamic;  // moving (not sleeping)
  PairPose pose;
  Vec3 lo, hi;   // bounding box widened by the margin
  double margin; // what it closes in one step, m
  Vec3 vw, ww;   // world velocity and spin
};

// The pairs (a < b, indices into c) whose boxes overlap, sorted by their bodies' indices: a
// uniform grid of cells as large as the largest box, so that a box spans at most 2 cells per
// axis; each box is tested against the boxes already in its cells, and a pair is kept in one
// cell only, the one holding the larger of the two lower corners. While bodies are far apart
// most cells hold one box: about n cell lookups, no sort of all the boxes.
template <class Box>
std::vector<std::pair<int, int>> overlapping_pairs(const std::vector<Box>& c) {
  std::vector<std::pair<int, int>> pairs;
  if (c.size() < 2) return pairs;
  double size = 0;
  for (const Box& b : c) size = std::max(size, (b.hi - b.lo).maxCoeff());
  const double inv = 1.0 / std::max(size, 1e-9);
  auto cell = [&](double x) { return static_cast<int64_t>(std::floor(x * inv)); };
  // open addressing, at least twice as many slots as entries (a box's cells)
  size_t entries = 0;
  for (const Box& b : c)
    entries += size_t(cell(b.hi.x()) - cell(b.lo.x()) + 1) *
               size_t(cell(b.hi.y()) - cell(b.lo.y()) + 1) *
               size_t(cell(b.hi.z()) - cell(b.lo.z()) + 1);
  size_t cap = 16;
  while (cap < 2 * entries) cap <<= 1;
  struct Slot {
    uint64_t key = 0;
    int head = -1;  // the cell's last entry; -1: an empty slot
  };
  // (kept from call to call: a table of a few MB allocated afresh each time is mapped and
  // faulted in page by page)
  static thread_local std::vector<Slot> table;
  static thread_local std::vector<int> next, owner;  // entries: the box and the previous entry
  table.assign(cap, Slot{});
  next.clear();
  owner.clear();
  next.reserve(entries);
  owner.reserve(entries);
  // (cells 2^21 apart share a key: their boxes are tested against each other for nothing)
  auto slot_of = [&](int64_t i, int64_t j, int64_t k) -> Slot& {
    const uint64_t key = (uint64_t(i) & 0x1FFFFF) << 42 | (uint64_t(j) & 0x1FFFFF) << 21 |
                         (uint64_t(k) & 0x1FFFFF);
    uint64_t h = key * 0x9E3779B97F4A7C15ULL;
    h ^= h >> 31;
    for (size_t s = h & (cap - 1);; s = (s + 1) & (cap - 1)) {
      Slot& t = table[s];
      if (t.head < 0) {
        t.key = key;
        return t;
      }
      if (t.key == key) return t;
    }
  };
  for (int b = 0; b < int(c.size()); ++b) {
    const int64_t i0 = cell(c[b].lo.x()), i1 = cell(c[b].hi.x());
    const int64_t j0 = cell(c[b].lo.y()), j1 = cell(c[b].hi.y());
    const int64_t k0 = cell(c[b].lo.z()), k1 = cell(c[b].hi.z());
    for (int64_t i = i0; i <= i1; ++i)
      for (int64_t j = j0; j <= j1; ++j)
        for (int64_t k = k0; k <= k1; ++k) {
          Slot& t = slot_of(i, j, k);
          for (int e = t.head; e >= 0; e = next[e]) {
            const int a = owner[e];
            const bool overlap =
                c[a].lo.x() <= c[b].hi.x() && c[b].lo.x() <= c[a].hi.x() &&
                c[a].lo.y() <= c[b].hi.y() && c[b].lo.y() <= c[a].hi.y() &&
                c[a].lo.z() <= c[b].hi.z() && c[b].lo.z() <= c[a].hi.z();
            if (!overlap) continue;
            const Vec3 lo = c[a].lo.cwiseMax(c[b].lo);
            if (cell(lo.x()) == i && cell(lo.y()) == j && cell(lo.z()) == k)
              pairs.emplace_back(std::min(a, b), std::max(a, b));
          }
          owner.push_back(b);
          next.push_back(t.head);
          t.head = int(owner.size()) - 1;
        }
  }
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

// body i as the stage takes it; widen: its box widened by its margin (else the shape's own box)
Cand make_cand(const Model& model, const State& st, size_t i, bool widen = true) {
  Cand c;
  c.body = static_cast<uint32_t>(i);
  c.dynamic = st.status[i] == BodyStatus::Moving;
  const BodyType& type = model.types[st.type[i]];
  c.pose.x = st.x[i];
  c.pose.R = st.q[i].toRotationMatrix();
  c.vw = c.pose.R * st.v[i];
  c.ww = c.pose.R * st.w[i];
  c.margin = !widen      ? 0.0
             : c.dynamic ? pair_margin(type, c.vw.norm(), c.ww.norm(), model.dt)
                         : kPairSkin;
  pair_aabb(*type.pair, c.pose, &c.lo, &c.hi);
  c.lo.array() -= c.margin;
  c.hi.array() += c.margin;
  return c;
}

bool takes_part(const State& st, size_t i) {
  const BodyStatus s = st.status[i];
  return (s == BodyStatus::Moving || s == BodyStatus::Sleeping) && !st.hidden[i];
}

int find(std::vector<int>& parent, int a) {
  while (parent[a] != a) a = parent[a] = parent[parent[a]];
  return a;
}

}  // namespace

BodyContactStats body_contacts(const Model& model, State* state, BodyContactScratch* scratch,
                               size_t n0, size_t n, int threads) {
  std::vector<uint32_t> bodies(n > n0 ? n - n0 : 0);
  std::iota(bodies.begin(), bodies.end(), uint32_t(n0));
  return body_contacts(model, state, scratch, bodies, threads);
}

BodyContactStats body_contacts(const Model& model, State* state, BodyContactScratch* scratch,
                               const std::vector<uint32_t>& bodies, int threads) {
  BodyContactStats stats;
  State& st = *state;
  // the last step's impulses: this step's warm start; replaced by this step's
  const std::vector<PairImpulse> warm = std::move(st.pair_impulses);
  st.pair_impulses.clear();
  const double h = model.dt;
  const double t_end = static_cast<double>(st.step) * h;
  thread_local std::vector<Cand> kept_cand;  // (kept from step to step, see mf below)
  std::vector<Cand>& cand = kept_cand;
  cand.clear();
  for (const uint32_t i : bodies) {
    if (!takes_part(st, i)) continue;
    // without a colliding ground or walls the step's contact pass does not run: what touches
    // nothing is flying (the islands below say what touches)
    if (!model.contacts() && st.status[i] == BodyStatus::Moving) mark_flying(&st, i);
    cand.push_back(make_cand(model, st, i));
  }
  const std::vector<std::pair<int, int>> pairs = overlapping_pairs(cand);
  if (pairs.empty()) return stats;
  // the narrow phase of the pairs with a moving body
  // (grown only, kept from step to step: a pile's manifolds are megabytes, which allocated
  // afresh would be zeroed and page-faulted in every step; done[] says which hold a result)
  // (a reference: the threads of the narrow phase below fill this thread's vector, not theirs)
  thread_local std::vector<PairManifold> kept_manifolds;
  std::vector<PairManifold>& mf = kept_manifolds;
  if (mf.size() < pairs.size()) mf.resize(pairs.size());
  std::vector<uint8_t> done(pairs.size(), 0);
  auto narrow = [&](size_t p) {
    const Cand &a = cand[pairs[p].first], &b = cand[pairs[p].second];
    collide(*model.types[st.type[a.body]].pair, a.pose, *model.types[st.type[b.body]].pair,
            b.pose, a.margin + b.margin, &mf[p]);
    done[p] = 1;
  };
  const auto np = static_cast<int64_t>(pairs.size());
#pragma omp parallel for num_threads(threads) schedule(dynamic, 64) if (np > 64)
  for (int64_t p = 0; p < np; ++p)
    if (cand[pairs[p].first].dynamic || cand[pairs[p].second].dynamic) narrow(size_t(p));

  // waking: a sleeping body touched by a moving body that is not resting (it was not resting
  // before this step, or a point approaches faster than the resting speed) wakes, with the
  // sleeping bodies that touch it
  // each candidate's pairs: adj[adj_at[k], adj_at[k + 1]), in pair order
  std::vector<int> adj_at(cand.size() + 1, 0), adj(2 * pairs.size());
  for (const auto& [a, b] : pairs) ++adj_at[size_t(a) + 1], ++adj_at[size_t(b) + 1];
  for (size_t k = 0; k < cand.size(); ++k) adj_at[k + 1] += adj_at[k];
  {
    std::vector<int> at(adj_at.begin(), adj_at.end() - 1);
    for (size_t p = 0; p < pairs.size(); ++p) {
      adj[size_t(at[size_t(pairs[p].first)]++)] = int(p);
      adj[size_t(at[size_t(pairs[p].second)]++)] = int(p);
    }
  }
  std::vector<int> woken;
  auto wake = [&](int s) {
    std::vector<int> stack{s};
    cand[s].dynamic = true;
    while (!stack.empty()) {
      const int k = stack.back();
      stack.pop_back();
      const uint32_t i = cand[k].body;
      st.u_seen[i] = wake_sleeper(&st, i);
      woken.push_back(k);
      for (int e = adj_at[size_t(k)]; e < adj_at[size_t(k) + 1]; ++e) {
        const int p = adj[size_t(e)];
        const int o = pairs[p].first == k ? pairs[p].second : pairs[p].first;
        if (cand[o].dynamic) continue;
        if (!done[p]) narrow(size_t(p));
        if (mf[p].count == 0) continue;
        cand[o].dynamic = true;
        stack.push_back(o);
      }
    }
  };
  for (size_t p = 0; p < pairs.size(); ++p) {
    if (!done[p] || mf[p].count == 0) continue;
    const int a = pairs[p].first, b = pairs[p].second;
    if (cand[a].dynamic == cand[b].dynamic) continue;
    const int mover = cand[a].dynamic ? a : b, sleeper = cand[a].dynamic ? b : a;
    const uint32_t i = cand[mover].body;
    bool hits = scratch->rest_before.size() > i ? scratch->rest_before[i] == 0 : true;
    for (int k = 0; k < mf[p].count && !hits; ++k) {
      const PairPoint& q = mf[p].pts[k];
      const Vec3 vc = cand[mover].vw + cand[mover].ww.cross(q.p - cand[mover].pose.x);
      const Vec3 nn = mover == a ? q.n : Vec3(-q.n);
      hits = vc.dot(nn) < -model.rest_speed;
    }
    if (hits) wake(sleeper);
  }
  stats.woken = woken.size();
  // pairs a wake made dynamic on both sides and not yet tested
  for (size_t p = 0; p < pairs.size(); ++p)
    if (!done[p] && (cand[pairs[p].first].dynamic || cand[pairs[p].second].dynamic)) narrow(p);

  // islands: moving bodies joined by touching pairs
  std::vector<int> parent(cand.size());
  std::iota(parent.begin(), parent.end(), 0);
  std::vector<uint8_t> in_island(cand.size(), 0);
  for (size_t p = 0; p < pairs.size(); ++p) {
    if (!done[p] || mf[p].count == 0) continue;
    const int a = pairs[p].first, b = pairs[p].second;
    ++stats.touching;
    in_island[a] |= cand[a].dynamic;
    in_island[b] |= cand[b].dynamic;
    if (cand[a].dynamic && cand[b].dynamic) {
      const int ra = find(parent, a), rb = find(parent, b);
      if (ra != rb) parent[std::max(ra, rb)] = std::min(ra, rb);
    }
  }
  // each island's bodies (in body order) and pairs (in pair order)
  std::vector<int> root_island(cand.size(), -1);
  std::vector<std::vector<int>> ibodies, ipairs;
  for (size_t k = 0; k < cand.size(); ++k) {
    if (!in_island[k]) continue;
    const int r = find(parent, int(k));
    if (root_island[r] < 0) {
      root_island[r] = int(ibodies.size());
      ibodies.emplace_back();
      ipairs.emplace_back();
    }
    ibodies[root_island[r]].push_back(int(k));
  }
  for (size_t p = 0; p < pairs.size(); ++p) {
    if (!done[p] || mf[p].count == 0) continue;
    const int a = pairs[p].first, b = pairs[p].second;
    const int k = cand[a].dynamic ? a : b;
    ipairs[root_island[find(parent, k)]].push_back(int(p));
  }

  const auto nis = static_cast<int64_t>(ibodies.size());
  std::vector<std::vector<PairImpulse>> solved(ibodies.size());
#pragma omp parallel for num_threads(threads) schedule(dynamic, 1) if (nis > 1)
  for (int64_t is = 0; is < nis; ++is) {
    const std::vector<int>& members = ibodies[is];
    const int nm = static_cast<int>(members.size());
    // (the island's arrays are kept from step to step, per thread: a pile's are megabytes, page
    // faults every step when allocated afresh)
    thread_local std::vector<IslandBody> bodies, before;
    thread_local std::vector<IslandPoint> pts;
    bodies.assign(members.size(), IslandBody{});
    auto local_of = [&](int k) {
      return int(std::lower_bound(members.begin(), members.end(), k) - members.begin());
    };
    for (int m = 0; m < nm; ++m) {
      const Cand& c = cand[members[m]];
      const BodyType& type = model.types[st.type[c.body]];
      world_inverse_mass(type.M_inv, c.pose.R, bodies[m].W);
      for (int a = 0; a < 3; ++a) bodies[m].v[a] = c.vw[a], bodies[m].w[a] = c.ww[a];
    }
    pts.clear();
    // each point's key in the impulses kept for the next step: its bodies (the lower first)
    // and whether the island's a is the higher one (then the impulse on the lower is -J)
    struct Key {
      uint32_t a, b;
      bool flip;
    };
    thread_local std::vector<Key> keys;
    keys.clear();
    for (const int p : ipairs[is]) {
      int a = pairs[p].first, b = pairs[p].second;
      double sign = 1;
      if (!cand[a].dynamic) std::swap(a, b), sign = -1;
      const BodyType& ta = model.types[st.type[cand[a].body]];
      const BodyType& tb = model.types[st.type[cand[b].body]];
      const ContactParams& ka = *ta.contact;
      const ContactParams& kb = *tb.contact;
      const PairMaterial mat = pair_material(ka, kb);
      const Key key{std::min(cand[a].body, cand[b].body), std::max(cand[a].body, cand[b].body),
                    sign < 0};
      WarmRange prev(warm, key.a, key.b);
      const double tol = kWarmMatch * std::min(ta.reach, tb.reach);
      for (int k = 0; k < mf[p].count; ++k) {
        const PairPoint& q = mf[p].pts[k];
        IslandPoint ip;
        ip.a = local_of(a);
        ip.b = cand[b].dynamic ? local_of(b) : -1;
        const Vec3 ra = q.p - cand[a].pose.x, rb = q.p - cand[b].pose.x;
        for (int e = 0; e < 3; ++e) ip.ra[e] = ra[e], ip.rb[e] = rb[e], ip.n[e] = sign * q.n[e];
        ip.depth = q.depth;
        ip.restitution = mat.restitution;
        ip.friction = mat.friction;
        ip.rolling = mat.rolling;
        ip.rest_speed = std::max(ka.rest_speed, kb.rest_speed);
        ip.slop = position_slop(ta, tb);
        if (const PairImpulse* c = prev.take(key.flip ? ip.rb : ip.ra, tol)) {
          ip.jn = c->jn;
          for (int e = 0; e < 3; ++e) ip.jt[e] = key.flip ? -c->jt[e] : c->jt[e];
        }
        pts.push_back(ip);
        keys.push_back(key);
      }
    }
    // the members' points on the ground and the walls, solved with the pairs
    if (model.contacts()) {
      for (int m = 0; m < nm; ++m) {
        const Cand& c = cand[members[m]];
        const BodyType& type = model.types[st.type[c.body]];
        const BodyState b = load_body(st, c.body);
        Touching t;
        // (points within the skin count as touching: the contact pass has just put the body
        // on the surface, at a depth of 0 give or take the round-off)
        gather(model, type, b, c.pose.R, t_end, 0.0, &t, nullptr, kPairSkin, h);
        WarmRange prev(warm, c.body, PairImpulse::kSurface);
        for (int k = 0; k < t.count; ++k) {
          IslandPoint ip;
          ip.a = m;
          const Vec3 r = c.pose.R * Vec3(t.r[3 * k], t.r[3 * k + 1], t.r[3 * k + 2]);
          const Vec3 nn = c.pose.R * Vec3(t.n[3 * k], t.n[3 * k + 1], t.n[3 * k + 2]);
          for (int e = 0; e < 3; ++e) ip.ra[e] = r[e], ip.n[e] = nn[e];
          ip.depth = t.depth[k];
          ip.restitution = type.contact->restitution;
          ip.friction = type.contact->friction;
          ip.rolling = type.contact->rolling_resistance;
          ip.rest_speed = type.contact->rest_speed;
          ip.slop = position_slop(type, type);
          if (const PairImpulse* w = prev.take(ip.ra, kWarmMatch * type.reach)) {
            ip.jn = w->jn;
            for (int e = 0; e < 3; ++e) ip.jt[e] = w->jt[e];
          }
          pts.push_back(ip);
          keys.push_back({c.body, PairImpulse::kSurface, false});
        }
      }
    }
    before = bodies;
    const int passes =
        std::clamp(kIslandSweeps / std::max(1, int(pts.size())), kIslandMinPasses,
                   std::max(kIslandMinPasses, std::min(kIslandPasses, kIslandPassesPerBody * nm)));
    // (how much of the velocity change the step's position update takes)
    const double cw = model.integrator == Integrator::Euler ? 0.0 : 0.5 * h;
    thread_local std::vector<double> moves;
    moves.assign(3 * members.size(), 0.0);
    island_resolve(bodies.data(), pts.data(), int(pts.size()), passes, h, cw, moves.data(),
                   kIslandMinPasses);
    // the impulses the points carry, for the next step's warm start
    for (size_t k = 0; k < pts.size(); ++k) {
      const IslandPoint& ip = pts[k];
      if (!(ip.jn > 0)) continue;
      PairImpulse w;
      w.a = keys[k].a, w.b = keys[k].b;
      const double s = keys[k].flip ? -1.0 : 1.0;
      for (int e = 0; e < 3; ++e)
        w.r[e] = keys[k].flip ? ip.rb[e] : ip.ra[e], w.jt[e] = s * ip.jt[e];
      w.jn = ip.jn;
      solved[is].push_back(w);
    }
    const double still = kRestFraction * model.rest_speed;
    std::vector<uint8_t> rests(members.size(), 1);
    std::vector<int> touching(members.size(), 0);
    for (const IslandPoint& ip : pts) {
      double vc[3];
      island_point_velocity(bodies.data(), ip, vc);
      // (a point within the skin holds the body as a touching one does: the speculative
      // contact keeps it there)
      if (!(ip.depth > -kPairSkin)) continue;
      ++touching[ip.a];
      if (ip.b >= 0) ++touching[ip.b];
      const bool moves = std::sqrt(dot3(vc, vc)) >= still;
      if (moves) {
        rests[ip.a] = 0;
        if (ip.b >= 0) rests[ip.b] = 0;
      }
    }
    bool all_rested = true;
    for (int m = 0; m < nm; ++m) {
      const Cand& c = cand[members[m]];
      const uint32_t i = c.body;
      const BodyType& type = model.types[st.type[i]];
      const Vec3 v(bodies[m].v[0], bodies[m].v[1], bodies[m].v[2]);
      const Vec3 w(bodies[m].w[0], bodies[m].w[1], bodies[m].w[2]);
      const Vec3 v0(before[m].v[0], before[m].v[1], before[m].v[2]);
      const Vec3 w0(before[m].w[0], before[m].w[1], before[m].w[2]);
      // positions: the step's update with the velocity change, then the island's correction of
      // what remains of the penetrations
      st.x[i] += cw * (v - v0) + Vec3(moves[3 * m], moves[3 * m + 1], moves[3 * m + 2]);
      st.q[i] = rotate_body(st.q[i], cw * (c.pose.R.transpose() * (w - w0)));
      st.v[i] = c.pose.R.transpose() * v;
      st.w[i] = c.pose.R.transpose() * w;
      // a body whose points are all off by more than the skin touches nothing: the step's own
      // contact pass said what it is (flying, or on the ground)
      if (touching[m] == 0) {
        all_rested = false;
        continue;
      }
      const bool r = rests[m] && w.norm() * type.reach < still;
      const uint32_t before_rest =
          i < scratch->rest_before.size() ? scratch->rest_before[i] : st.rest_steps[i];
      st.contact[i] = r ? ContactState::Resting : ContactState::Sliding;
      st.rest_steps[i] = r ? before_rest + 1 : 0;
      all_rested = all_rested && double(st.rest_steps[i]) * h >= model.sleep_time;
    }
    if (!all_rested) continue;
    // the island sleeps when the flow as it is moves none of its bodies
    std::vector<BodyState> saved(members.size());
    std::vector<double> t_stop(members.size());
    int slept = 0;
    for (; slept < nm; ++slept) {
      const uint32_t i = cand[members[slept]].body;
      const BodyType& type = model.types[st.type[i]];
      // what it lies on: of its touching points, the normal (into the body) that holds it most
      // directly against its weight less its buoyancy
      const double sink = type.density >= model.fluid_density ? 1.0 : -1.0;
      const Vec3 up = -sink * model.gravity.normalized();
      Vec3 base = up;
      double best = -HUGE_VAL;
      for (const IslandPoint& ip : pts) {
        const bool on_a = ip.a == slept, on_b = ip.b == slept;
        if ((!on_a && !on_b) || !(ip.depth >= 0)) continue;
        const Vec3 nn = (on_a ? 1.0 : -1.0) * Vec3(ip.n[0], ip.n[1], ip.n[2]);
        if (nn.dot(up) > best) best = nn.dot(up), base = nn;
      }
      saved[slept] = load_body(st, i);
      t_stop[slept] = st.t_stop[i];
      BodyState b = saved[slept];
      if (!fall_asleep(model, type, i, t_end, base, &b, &st)) break;
      store_body(b, i, &st);
    }
    if (slept == nm) continue;
    // one of them stays awake: the island does, and is asked again after another sleep_time
    for (int m = 0; m < nm; ++m) {
      const uint32_t i = cand[members[m]].body;
      if (m < slept) {
        store_body(saved[m], i, &st);
        st.status[i] = BodyStatus::Moving;
        st.t_stop[i] = t_stop[m];
        if (i < st.watch.size()) st.watch[i].valid = 0;
      }
      st.rest_steps[i] = 0;
    }
  }
  // the islands' impulses, sorted by their bodies (each island's in the order solved)
  size_t kept = 0;
  for (const auto& v : solved) kept += v.size();
  st.pair_impulses.reserve(kept);
  for (const auto& v : solved) st.pair_impulses.insert(st.pair_impulses.end(), v.begin(), v.end());
  std::stable_sort(st.pair_impulses.begin(), st.pair_impulses.end(), key_less);
  return stats;
}

double deepest_pair_overlap(const Model& model, const State& st, int* i_out, int* j_out) {
  std::vector<Cand> cand;
  for (size_t i = 0; i < st.size(); ++i) {
    if (!takes_part(st, i)) continue;
    cand.push_back(make_cand(model, st, i, false));
  }
  double deepest = 0;
  if (i_out) *i_out = -1;
  if (j_out) *j_out = -1;
  for (const auto& [a, b] : overlapping_pairs(cand)) {
    PairManifold m;
    collide(*model.types[st.type[cand[a].body]].pair, cand[a].pose,
            *model.types[st.type[cand[b].body]].pair, cand[b].pose, 0.0, &m);
    for (int k = 0; k < m.count; ++k)
      if (m.pts[k].depth > deepest) {
        deepest = m.pts[k].depth;
        if (i_out) *i_out = int(cand[a].body);
        if (j_out) *j_out = int(cand[b].body);
      }
  }
  return deepest;
}

bool in_body_contacts(const State& st, size_t i) { return takes_part(st, i); }

PairBox still_pair_box(const Model& model, const State& st, size_t i) {
  PairBox b;
  const Cand c = make_cand(model, st, i, false);
  b.lo = c.lo.array() - kPairSkin;
  b.hi = c.hi.array() + kPairSkin;
  b.moving = false;
  return b;
}

bool pair_touches(const Model& model, uint16_t type_a, const Vec3& xa, const Quat& qa,
                  double margin_a, uint16_t type_b, const Vec3& xb, const Quat& qb,
                  double margin_b) {
  const PairShape& sa = *model.types[type_a].pair;
  const PairShape& sb = *model.types[type_b].pair;
  const PairPose pa{xa, qa.toRotationMatrix()}, pb{xb, qb.toRotationMatrix()};
  Vec3 alo = Vec3::Zero(), ahi = Vec3::Zero(), blo = Vec3::Zero(), bhi = Vec3::Zero();
  pair_aabb(sa, pa, &alo, &ahi);
  pair_aabb(sb, pb, &blo, &bhi);
  alo.array() -= margin_a;
  ahi.array() += margin_a;
  blo.array() -= margin_b;
  bhi.array() += margin_b;
  if (!((alo.array() <= bhi.array()).all() && (blo.array() <= ahi.array()).all())) return false;
  PairManifold m;
  collide(sa, pa, sb, pb, margin_a + margin_b, &m);
  return m.count > 0;
}

std::vector<std::pair<int, int>> overlapping_pair_boxes(const std::vector<PairBox>& boxes) {
  std::vector<std::pair<int, int>> pairs = overlapping_pairs(boxes);
  pairs.erase(std::remove_if(pairs.begin(), pairs.end(),
                             [&](const std::pair<int, int>& p) {
                               return !boxes[p.first].moving && !boxes[p.second].moving;
                             }),
              pairs.end());
  return pairs;
}

}  // namespace lrigid
