// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_BLENDED_SHAPE_BLENDING_INTERNAL_STRIP_INVERSE_H
#define CGAL_BLENDED_SHAPE_BLENDING_INTERNAL_STRIP_INVERSE_H

// The inverse of the strip coordinate map of one segment (eq. 24): the strip
// coordinates (d, gamma) of a chart point, and the convex-hull test that
// tells which segments can hold it (end of A.2).

#include <CGAL/Blended_shape/Blending/internal/Bezier_loop.h>
#include <CGAL/Blended_shape/Blending/internal/Strip_segment.h>

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

namespace CGAL {
namespace Blended_shapes {
namespace internal {

/// The convex hull of the extremal control polygons `d = +- 1` of a segment:
/// by the convex hull property, a point outside it is not in the segment's strip.
struct Segment_hull
{
  std::vector<Eigen::Vector2d> points; ///< counterclockwise
  Eigen::Vector2d lo, hi;              ///< the bounding box

  /// The hull of the six control points `k_j +- n_j` of `s` (monotone chain).
  static Segment_hull of(const Strip_segment& s)
  {
    std::vector<Eigen::Vector2d> pts = {s.k0 + s.n0, s.k0 - s.n0, s.k1 + s.n1, s.k1 - s.n1, s.k2 + s.n2, s.k2 - s.n2};
    std::sort(pts.begin(), pts.end(), [](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
      return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
    });
    std::vector<Eigen::Vector2d> h(2 * pts.size());
    std::size_t k = 0;
    for(std::size_t p = 0; p < pts.size(); ++p)
    {
      while(k >= 2 && cross(h[k - 1] - h[k - 2], pts[p] - h[k - 2]) <= 0.)
        --k;
      h[k++] = pts[p];
    }
    for(std::size_t p = pts.size() - 1, t = k + 1; p-- > 0;)
    {
      while(k >= t && cross(h[k - 1] - h[k - 2], pts[p] - h[k - 2]) <= 0.)
        --k;
      h[k++] = pts[p];
    }
    h.resize(k - 1);
    Segment_hull H;
    H.points = h;
    H.lo = pts.front();
    H.hi = pts.front();
    for(const Eigen::Vector2d& p : pts)
    {
      H.lo = H.lo.cwiseMin(p);
      H.hi = H.hi.cwiseMax(p);
    }
    return H;
  }

  /// Whether `u` is in the hull, up to `eps`.
  bool contains(const Eigen::Vector2d& u, double eps) const
  {
    if(u.x() < lo.x() - eps || u.y() < lo.y() - eps || u.x() > hi.x() + eps || u.y() > hi.y() + eps)
      return false;
    const std::size_t m = points.size();
    for(std::size_t a = 0; a < m; ++a)
    {
      const Eigen::Vector2d& p = points[a];
      const Eigen::Vector2d e = points[(a + 1) % m] - p;
      if(cross(e, u - p) < -eps * e.norm())
        return false;
    }
    return true;
  }
};

/// The parameter of the point of the quadratic Bézier `(p0, p1, p2)`,
/// restricted to [0, 1], closest to `u` (eq. 25): coarse samples, then Newton
/// on `(K - u) . K' = 0` clamped to the segment. Scalar code, as in Strip_segment.
inline double closest_curve_parameter(const Eigen::Vector2d& p0, const Eigen::Vector2d& p1, const Eigen::Vector2d& p2,
                                      const Eigen::Vector2d& u)
{
  const double ax = p0.x() - 2. * p1.x() + p2.x(), ay = p0.y() - 2. * p1.y() + p2.y(); // K = p0 + 2 g b + g^2 a
  const double bx = p1.x() - p0.x(), by = p1.y() - p0.y();
  const double cx = p0.x() - u.x(), cy = p0.y() - u.y();
  double g = 0., best = std::numeric_limits<double>::infinity();
  for(int s = 0; s <= 8; ++s)
  {
    const double t = s / 8.;
    const double ex = cx + t * (2. * bx + t * ax), ey = cy + t * (2. * by + t * ay);
    if(ex * ex + ey * ey < best)
    {
      best = ex * ex + ey * ey;
      g = t;
    }
  }
  for(int it = 0; it < 20; ++it)
  {
    const double ex = cx + g * (2. * bx + g * ax), ey = cy + g * (2. * by + g * ay);
    const double tx = 2. * (bx + g * ax), ty = 2. * (by + g * ay);
    const double f = ex * tx + ey * ty, fp = tx * tx + ty * ty + 2. * (ex * ax + ey * ay);
    if(!(fp > 0.))
      break;
    const double gn = (std::min)(1., (std::max)(0., g - f / fp));
    const bool done = std::abs(gn - g) < 1e-14;
    g = gn;
    if(done)
      break;
  }
  return g;
}

/// Solves `C_i(d, gamma) = u` in segment `s` by Newton's method from the
/// closest point of the curve and the projected distance there (eq. 25),
/// with backtracking so that the residual never grows; no range check on the
/// result. Returns false unless the residual ends below `tolerance` (`u` far
/// outside the segment's strip).
inline bool solve_strip_coordinates(const Strip_segment& s, const Eigen::Vector2d& u, double tolerance, double& d,
                                    double& gamma)
{
  const double g = closest_curve_parameter(s.k0, s.k1, s.k2, u);
  const Eigen::Vector2d N = s.jacobian(0., g).col(0);
  d = (u - bezier(s.k0, s.k1, s.k2, g)).dot(N) / N.squaredNorm();
  gamma = g;

  Eigen::Vector2d F = s.point(d, gamma) - u;
  double res = F.norm();
  for(int it = 0; it < 60 && res > 0.; ++it)
  {
    const Eigen::Matrix2d A = s.jacobian(d, gamma);
    const double det = det2(A);
    if(!(std::abs(det) > 0.) || !std::isfinite(det))
      return false;
    const Eigen::Vector2d step = -solve_2x2(A, det, F);
    double t = 1.;
    bool improved = false;
    for(int ls = 0; ls < 30; ++ls, t *= 0.5)
    {
      const double nd = d + t * step.x(), ng = gamma + t * step.y();
      if(nd == d && ng == gamma)
        break; // the step no longer moves the point, nor would any shorter one
      const Eigen::Vector2d Fn = s.point(nd, ng) - u;
      const double rn = Fn.norm();
      if(rn < res)
      {
        d = nd;
        gamma = ng;
        F = Fn;
        res = rn;
        improved = true;
        break;
      }
    }
    if(!improved)
      break; // at the rounding floor
    if(!(std::abs(gamma) < 4.) || !(std::abs(d) < 1e3))
      return false; // left the segment's neighbourhood: the point is elsewhere
  }
  return res <= tolerance;
}

} // namespace internal
} // namespace Blended_shapes
} // namespace CGAL

#endif // CGAL_BLENDED_SHAPE_BLENDING_INTERNAL_STRIP_INVERSE_H
