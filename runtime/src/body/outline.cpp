#include "body/outline.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace lrigid {

namespace {

// (a - o) x (b - o): > 0 when o, a, b turn counter-clockwise
double turn(const Vec2& o, const Vec2& a, const Vec2& b) {
  return (a.x() - o.x()) * (b.y() - o.y()) - (a.y() - o.y()) * (b.x() - o.x());
}

}  // namespace

std::vector<Vec2> convex_hull(std::vector<Vec2> p) {
  std::sort(p.begin(), p.end(), [](const Vec2& a, const Vec2& b) {
    return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
  });
  p.erase(std::unique(p.begin(), p.end()), p.end());
  if (p.size() < 3) return p;
  // the lower chain left to right, then the upper chain right to left, each keeping only left
  // turns (a collinear point is dropped)
  std::vector<Vec2> h(2 * p.size());
  size_t k = 0;
  for (size_t i = 0; i < p.size(); ++i) {
    while (k >= 2 && turn(h[k - 2], h[k - 1], p[i]) <= 0) --k;
    h[k++] = p[i];
  }
  for (size_t i = p.size() - 1, lower = k + 1; i-- > 0;) {
    while (k >= lower && turn(h[k - 2], h[k - 1], p[i]) <= 0) --k;
    h[k++] = p[i];
  }
  h.resize(k - 1);  // the last point is the first
  return h;
}

double OutlineRectangle::angle() const { return std::atan2(axis1.y(), axis1.x()); }

OutlineRectangle min_area_rectangle(const std::vector<Vec2>& points) {
  const std::vector<Vec2> h = convex_hull(points);
  const size_t n = h.size();
  OutlineRectangle r;
  if (n == 0) return r;
  // the best edge's direction d and its inward normal m (the hull is counter-clockwise), and the
  // hull's extents along them
  Vec2 d = Vec2::UnitX(), m = Vec2::UnitY();
  double lo_d = h[0].x(), hi_d = h[0].x(), lo_m = h[0].y(), hi_m = h[0].y();
  if (n == 2) {
    d = (h[1] - h[0]).normalized();
    m = Vec2(-d.y(), d.x());
    lo_d = std::min(h[0].dot(d), h[1].dot(d));
    hi_d = std::max(h[0].dot(d), h[1].dot(d));
    lo_m = hi_m = h[0].dot(m);
  } else if (n >= 3) {
    // the calipers: the hull points farthest along the edge (hi), against it (lo) and across it
    // (top); each moves forward (counter-clockwise) as the edges turn, so the loop visits each
    // point a bounded number of times
    const auto next = [n](size_t i) { return i + 1 == n ? 0 : i + 1; };
    size_t hi = 0, lo = 0, top = 0;
    double best = std::numeric_limits<double>::infinity();
    for (size_t i = 0; i < n; ++i) {
      const Vec2 a = h[i];
      const Vec2 e = (h[next(i)] - a).normalized();
      const Vec2 in(-e.y(), e.x());
      if (i == 0) {
        for (size_t j = 1; j < n; ++j) {
          if (h[j].dot(e) > h[hi].dot(e)) hi = j;
          if (h[j].dot(e) < h[lo].dot(e)) lo = j;
          if (h[j].dot(in) > h[top].dot(in)) top = j;
        }
      } else {
        for (size_t s = 0; s < n && h[next(hi)].dot(e) > h[hi].dot(e); ++s) hi = next(hi);
        for (size_t s = 0; s < n && h[next(lo)].dot(e) < h[lo].dot(e); ++s) lo = next(lo);
        for (size_t s = 0; s < n && h[next(top)].dot(in) > h[top].dot(in); ++s) top = next(top);
      }
      const double l0 = h[lo].dot(e), l1 = h[hi].dot(e), m0 = a.dot(in), m1 = h[top].dot(in);
      const double area = (l1 - l0) * (m1 - m0);
      if (area < best) {
        best = area;
        d = e;
        m = in;
        lo_d = l0, hi_d = l1, lo_m = m0, hi_m = m1;
      }
    }
  }
  r.centre = 0.5 * (lo_d + hi_d) * d + 0.5 * (lo_m + hi_m) * m;
  const double hd = 0.5 * (hi_d - lo_d), hm = 0.5 * (hi_m - lo_m);
  // axis1: the one of d, m, -d, -m at an angle in (-pi/4, pi/4] from the x axis
  const Vec2 cand[4] = {d, m, -d, -m};
  for (int c = 0; c < 4; ++c) {
    const Vec2& v = cand[c];
    if (v.x() > std::abs(v.y()) || (v.x() == v.y() && v.x() > 0)) {
      r.axis1 = v;
      r.h1 = c % 2 == 0 ? hd : hm;
      r.h2 = c % 2 == 0 ? hm : hd;
      break;
    }
  }
  r.axis2 = Vec2(0.0 - r.axis1.y(), r.axis1.x());  // 0.0 - 0.0: no negative zero
  return r;
}

}  // namespace lrigid
