// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_BLENDED_SHAPE_FITTING_INTERNAL_RIGID_POSE_H
#define CGAL_BLENDED_SHAPE_FITTING_INTERNAL_RIGID_POSE_H

#include <CGAL/Blended_shape/internal/Parameter_table.h>
#include <CGAL/Blended_shape/internal/quaternion.h>

#include <Eigen/Core>

#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

namespace CGAL {
namespace Blended_shapes {
namespace internal {

// The rigid placement x = c + R s of a deformable model (sec. 5.1, eq. 5),
// shared by Deformable_model and Deformable_blended_model: its 7 parameters
// (cx, cy, cz, qw, qx, qy, qz) come first in a model's parameter vector, the
// quaternion is stored normalized, and its Jacobian columns are
// [ I | (dR/dq) s ] (the normalization included, see quaternion.h).
struct Rigid_pose
{
  static constexpr int number_of_parameters = 7;

  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  Eigen::Vector4d quaternion = Eigen::Vector4d(1., 0., 0., 0.);
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  std::array<Eigen::Matrix3d, 4> dR = rotation_matrix_derivatives(Eigen::Vector4d(1., 0., 0., 0.));

  static const char* parameter_name(std::size_t i)
  {
    static const char* names[] = {"cx", "cy", "cz", "qw", "qx", "qy", "qz"};
    return names[i];
  }
  // The translation is a length, the quaternion dimensionless.
  static Parameter_kind parameter_kind(std::size_t i) { return i < 3 ? Parameter_kind::Length : Parameter_kind::Dimensionless; }

  // \throws std::invalid_argument (naming `who`) if the translation is not
  //         finite or the quaternion zero or not finite; then unchanged.
  void set(const Eigen::Vector3d& translation, const Eigen::Vector4d& q, const char* who)
  {
    const double n = q.norm();
    if(!translation.allFinite() || !(n > 0.) || !std::isfinite(n))
      throw std::invalid_argument(std::string(who) + ": the translation must be finite and the quaternion non-zero");
    c = translation;
    quaternion = q / n;
    R = rotation_matrix(quaternion);
    dR = rotation_matrix_derivatives(quaternion);
  }

  Eigen::Vector3d place(const Eigen::Vector3d& s) const { return c + R * s; }

  // A model's parameter vector: this pose's 7 parameters, then the shape's.
  template <class ShapeParameters>
  Eigen::VectorXd model_parameters(const ShapeParameters& shape_parameters) const
  {
    Eigen::VectorXd q(static_cast<Eigen::Index>(number_of_parameters + shape_parameters.size()));
    q << c, quaternion, shape_parameters;
    return q;
  }

  // Sets this pose from the head of a model's parameter vector `q` and the
  // shape from its tail through `set_shape_parameters`; unchanged if that
  // throws.
  // \throws std::invalid_argument (naming `who`) if `q` is not of `size`, or see set().
  template <class SetShapeParameters>
  void set_model_parameters(const Eigen::VectorXd& q, std::size_t size, SetShapeParameters&& set_shape_parameters,
                            const char* who)
  {
    if(q.size() != Eigen::Index(size))
      throw std::invalid_argument(std::string(who) + ": parameter vector of size " + std::to_string(q.size()) +
                                  ", expected " + std::to_string(size));
    Rigid_pose pose = *this;
    pose.set(q.template head<3>(), q.template segment<4>(3), who);
    set_shape_parameters(q.tail(q.size() - number_of_parameters));
    *this = pose;
  }

  // The pose's 7 Jacobian columns at the shape point s.
  template <class Block>
  void jacobian(const Eigen::Vector3d& s, Block&& columns) const
  {
    columns.template leftCols<3>().setIdentity();
    for(int k = 0; k < 4; ++k)
      columns.col(3 + k) = dR[std::size_t(k)] * s;
  }
};

} // namespace internal
} // namespace Blended_shapes
} // namespace CGAL

#endif // CGAL_BLENDED_SHAPE_FITTING_INTERNAL_RIGID_POSE_H
