// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_BLENDED_SHAPE_BLENDING_INTERNAL_BLEND_CORRESPONDENCE_H
#define CGAL_BLENDED_SHAPE_BLENDING_INTERNAL_BLEND_CORRESPONDENCE_H

// The correspondence beta of a blend (eq. 16, extended to the disk of a
// gradual blend, Fig. 7): the added component's chart point u2 = beta(u) of a
// point u of the base region's strip or disk, with the derivatives that the
// blended surface's Jacobians need (eq. 10, 11).

#include <CGAL/Blended_shape/Blending/Blend.h>
#include <CGAL/Blended_shape/Blending/Blending_region.h>
#include <CGAL/Blended_shape/Primitives/Chart_domain.h>

#include <CGAL/assertions.h>

#include <Eigen/Core>
#include <Eigen/Dense>

#include <cmath>
#include <optional>

namespace CGAL {
namespace Blended_shapes {
namespace internal {

/// `beta(u)` and its derivatives at a base point `u`.
struct Blend_correspondence
{
  Chart_point u2;                                                          ///< `beta(u)`
  Eigen::Matrix<double, 2, 7> du2_dq = Eigen::Matrix<double, 2, 7>::Zero(); ///< `∂beta/∂q_b`
  Eigen::Matrix2d du2_du = Eigen::Matrix2d::Zero();                        ///< `∂beta/∂u`
  Eigen::RowVector2d dalpha_du = Eigen::RowVector2d::Zero();               ///< `∂alpha/∂u`
};

/// `dbeta/du` in the disk of gradual blend `B` at base point `v` with disk
/// coordinates `c` (`Jb`: the added side's `[d/dt, d/dtheta]`): through the
/// inverse of the base disk map's Jacobian, or, next to the centre where
/// theta is not defined (beta is smooth there), by central differences of beta.
inline Eigen::Matrix2d core_beta_derivatives(const Blend& B, const Eigen::Vector2d& v, const Core_coordinates& c,
                                             const Eigen::Matrix2d& Jb)
{
  const Ellipse_blending_region& R = B.base_region();
  const double k = B.core_stretch();
  Eigen::Matrix2d Jc;
  R.core_point(c.t, c.theta, -1., k, &Jc);
  if(std::abs(Jc.determinant()) > 1e-10 * Jc.squaredNorm())
    return Jb * Jc.inverse();
  auto beta = [&](const Eigen::Vector2d& w) {
    const std::optional<Core_coordinates> q = R.core_coordinates(w, -1., k);
    const Chart_point u2 = q ? B.added_side().core_point(q->t, q->theta, k) : B.added_side().core_point(0., 0., k);
    return Eigen::Vector2d(u2.x, u2.y);
  };
  const double h = 1e-7 * (1. + v.norm());
  Eigen::Matrix2d P;
  P.col(0) = (beta(v + Eigen::Vector2d(h, 0.)) - beta(v - Eigen::Vector2d(h, 0.))) / (2. * h);
  P.col(1) = (beta(v + Eigen::Vector2d(0., h)) - beta(v - Eigen::Vector2d(0., h))) / (2. * h);
  return P;
}

/// `beta(v)` for the point `v` of blend `B`'s base region located by `A`
/// (`A = R.alpha_and_gradient(v)`, not on the retained side), with `∂beta/∂q_b`
/// if `with_parameter_derivatives` and `∂beta/∂u`, `∂alpha/∂u` if
/// `with_chart_derivatives`; `tube`: whether the added component is a hole in
/// its Tube domain. A point on the boundary of the disk to rounding is moved to
/// the strip's inner edge, and `A` updated. Nothing if `v` is in neither.
inline std::optional<Blend_correspondence>
blend_correspondence(const Blend& B, bool tube, const Eigen::Vector2d& v,
                     Alpha_and_gradient<Ellipse_blending_region::Parameter_vector>& A,
                     bool with_parameter_derivatives, bool with_chart_derivatives)
{
  const Ellipse_blending_region& R = B.base_region();
  const double k = B.core_stretch();
  Blend_correspondence beta;
  Eigen::Matrix2d Jb;
  std::optional<Core_coordinates> core;
  if(A.location.side != Region_side::Strip)
  {
    // Canonical points are never on the discarded side of a cut-and-glue
    // blend (canonical_point() locates them the same way, and the
    // regions are kept valid): only disks of gradual blends get here.
    CGAL_assertion(B.is_gradual());
    core = R.core_coordinates(v, -1., k);
    if(!core)
    {
      // On the boundary of the disk to rounding: the strip's inner edge.
      const std::optional<Strip_coordinates> edge = R.strip_coordinates(v);
      if(!edge)
        return std::nullopt;
      A = R.alpha_and_gradient(R.strip_point(edge->d, edge->theta));
      A.location.side = Region_side::Strip;
      A.location.coordinates = *edge;
    }
  }
  if(A.location.side == Region_side::Strip)
  {
    // The location found above carries the strip coordinates: no second Newton inversion.
    const Strip_coordinates& sc = A.location.coordinates;
    beta.u2 = B.added_side().strip_point(-sc.d, sc.theta, tube, &Jb);
    if(with_parameter_derivatives)
    {
      const auto g = R.strip_coordinates_and_gradient(sc);
      beta.du2_dq = -Jb.col(0) * g.d_gradient.transpose() + Jb.col(1) * g.theta_gradient.transpose();
    }
    if(with_chart_derivatives)
    {
      const Eigen::Matrix2d G = R.strip_coordinate_derivatives(sc); // d(d, theta)/du
      beta.du2_du = -Jb.col(0) * G.row(0) + Jb.col(1) * G.row(1);
      beta.dalpha_du = R.region().blending_derivatives(A.location).d_d * G.row(0);
    }
  }
  else
  {
    beta.u2 = B.added_side().core_point(core->t, core->theta, k, &Jb);
    if(with_parameter_derivatives)
      beta.du2_dq = Jb * R.core_gradient(*core, -1., k);
    if(with_chart_derivatives) // alpha = h in the disk; beta through the disk coordinates (t, theta)
      beta.du2_du = core_beta_derivatives(B, v, *core, Jb);
  }
  return beta;
}

} // namespace internal
} // namespace Blended_shapes
} // namespace CGAL

#endif // CGAL_BLENDED_SHAPE_BLENDING_INTERNAL_BLEND_CORRESPONDENCE_H
