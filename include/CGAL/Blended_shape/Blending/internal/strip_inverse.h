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

/// Solves `C_i(d, gamma) = u` in segment `s` (eq. 24), with no range check
/// on the result. `C_i(d, gamma) = K(gamma) + d N(gamma)` with the curve `K`
/// and the normal blend `N`, both quadratic in `gamma`: `u` is on the line
/// of `N(gamma)` through `K(gamma)` where `f(gamma) = (u - K) x N` vanishes,
/// and then `d = (u - K) . N / |N|^2`. So the 2D inverse is a scalar root:
/// Newton's method on `f` from the closest point of the curve (eq. 25), with
/// backtracking so that `|f|` never grows, until the step no longer moves
/// `gamma`. Returns false unless the residual `|C_i(d, gamma) - u|` ends below
/// `tolerance` (`u` far outside the segment's strip).
inline bool solve_strip_coordinates(const Strip_segment& s, const Eigen::Vector2d& u, double tolerance, double& d,
                                    double& gamma)
{
  // K = k0 + 2 g bk + g^2 ak, N = n0 + 2 g bn + g^2 an (Bernstein to power basis)
  const double akx = s.k0.x() - 2. * s.k1.x() + s.k2.x(), aky = s.k0.y() - 2. * s.k1.y() + s.k2.y();
  const double bkx = s.k1.x() - s.k0.x(), bky = s.k1.y() - s.k0.y();
  const double anx = s.n0.x() - 2. * s.n1.x() + s.n2.x(), any = s.n0.y() - 2. * s.n1.y() + s.n2.y();
  const double bnx = s.n1.x() - s.n0.x(), bny = s.n1.y() - s.n0.y();
  const double cx = u.x() - s.k0.x(), cy = u.y() - s.k0.y();
  // f(g) and f'(g), with e = u - K and N at g
  const auto f_at = [&](double g, double& ex, double& ey, double& nx, double& ny) {
    ex = cx - g * (2. * bkx + g * akx);
    ey = cy - g * (2. * bky + g * aky);
    nx = s.n0.x() + g * (2. * bnx + g * anx);
    ny = s.n0.y() + g * (2. * bny + g * any);
    return ex * ny - ey * nx;
  };
  double g = closest_curve_parameter(s.k0, s.k1, s.k2, u);
  double ex, ey, nx, ny;
  double f = f_at(g, ex, ey, nx, ny);
  for(int it = 0; it < 60 && f != 0.; ++it)
  {
    const double kx = 2. * (bkx + g * akx), ky = 2. * (bky + g * aky); // K'
    const double mx = 2. * (bnx + g * anx), my = 2. * (bny + g * any); // N'
    const double fp = -(kx * ny - ky * nx) + (ex * my - ey * mx);
    if(!(fp != 0.) || !std::isfinite(fp))
      return false;
    const double step = -f / fp;
    double t = 1.;
    bool improved = false;
    for(int ls = 0; ls < 30; ++ls, t *= 0.5)
    {
      const double ng = g + t * step;
      if(ng == g)
        break; // the step no longer moves gamma, nor would any shorter one
      double ex1, ey1, nx1, ny1;
      const double fn = f_at(ng, ex1, ey1, nx1, ny1);
      if(std::abs(fn) < std::abs(f))
      {
        g = ng;
        f = fn;
        ex = ex1; ey = ey1; nx = nx1; ny = ny1;
        improved = true;
        break;
      }
    }
    if(!improved)
      break; // at the rounding floor
    if(!(std::abs(g) < 4.))
      return false; // left the segment's neighbourhood: the point is elsewhere
  }
  const double n2 = nx * nx + ny * ny;
  if(!(n2 > 0.))
    return false;
  gamma = g;
  d = (ex * nx + ey * ny) / n2;
  if(!(std::abs(d) < 1e3))
    return false;
  return (s.point(d, gamma) - u).norm() <= tolerance;
}

} // namespace internal
} // namespace Blended_shapes
} // namespace CGAL

#endif // CGAL_BLENDED_SHAPE_BLENDING_INTERNAL_STRIP_INVERSE_H
