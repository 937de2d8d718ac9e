// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_BLENDED_SHAPE_BLENDING_INTERNAL_HOLE_PLACEMENT_H
#define CGAL_BLENDED_SHAPE_BLENDING_INTERNAL_HOLE_PLACEMENT_H

// Where a new hole component goes (sec. 4.2): its frame, size and end angles
// from the two region curves on the surface that its ends are glued to.

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <array>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace CGAL {
namespace Blended_shapes {
namespace internal {

/// The placement of a hole component between two closed curves.
struct Hole_placement
{
  Eigen::Vector3d centre;     ///< the midpoint of the curves' centres
  Eigen::Matrix3d rotation;   ///< columns x, y, z: z from the first curve to the second
  double mean_radius = 0.;    ///< `a1 = a2`, the mean distance of the curves' points to their centres
  double half_length = 0.;    ///< `a3`, half the distance of the centres
  std::array<double, 2> phase; ///< the angle offsets of ends 0 and 1
};

/// The hole placement whose end circles run through `curves[0]` and
/// `curves[1]` (the same number of samples each, the first at theta = 0):
/// axis from the first curve's centre to the second's, x toward the first
/// curve's theta = 0 point.
/// \throws std::invalid_argument if the curves are too close to hold a hole.
inline Hole_placement place_hole(const std::array<std::vector<Eigen::Vector3d>, 2>& curves)
{
  Eigen::Vector3d centre[2], start[2];
  double mean_radius = 0.;
  for(int e = 0; e < 2; ++e)
  {
    const std::vector<Eigen::Vector3d>& pts = curves[std::size_t(e)];
    const double samples = double(pts.size());
    centre[e].setZero();
    for(const Eigen::Vector3d& x : pts)
      centre[e] += x / samples;
    for(const Eigen::Vector3d& x : pts)
      mean_radius += (x - centre[e]).norm() / (2. * samples);
    start[e] = pts.front();
  }
  const Eigen::Vector3d axis = centre[1] - centre[0];
  const double length = axis.norm();
  if(!(length > 1e-9 * (mean_radius + 1.)) || !(mean_radius > 0.))
    throw std::invalid_argument("Blended_shape::add_hole: the two places are too close to hold a hole");
  // Frame: z from the first curve to the second, x toward the first curve's theta = 0 point.
  const Eigen::Vector3d z = axis / length;
  Eigen::Vector3d x = start[0] - centre[0];
  x -= x.dot(z) * z;
  if(!(x.norm() > 1e-12 * mean_radius))
    x = z.unitOrthogonal();
  x.normalize();
  Hole_placement h;
  h.rotation.col(0) = x;
  h.rotation.col(1) = z.cross(x);
  h.rotation.col(2) = z;
  h.centre = 0.5 * (centre[0] + centre[1]);
  // End 0 sits at local z = -a3, end 1 at z = +a3; the toroid's angle v
  // is -(theta + phase) at end 0 and theta + phase at end 1.
  for(int e = 0; e < 2; ++e)
  {
    const Eigen::Vector3d local = h.rotation.transpose() * (start[e] - h.centre);
    const double psi = std::atan2(local.y(), local.x());
    h.phase[std::size_t(e)] = (e == 0) ? -psi : psi;
  }
  h.mean_radius = mean_radius;
  h.half_length = 0.5 * length;
  return h;
}

} // namespace internal
} // namespace Blended_shapes
} // namespace CGAL

#endif // CGAL_BLENDED_SHAPE_BLENDING_INTERNAL_HOLE_PLACEMENT_H
