// SPDX-License-Identifier: LGPL-3.0-or-later
// A user-defined primitive: a tapered superquadric ellipsoid (the deformation
// superquadric users ask for most). It models BlendedShapePrimitive by
// composing the package's Superquadric_ellipsoid (reusing its two disk
// charts and their quotient) with a linear taper along z, and passes the
// package's generic checkers: the analytic parameter and chart Jacobians
// agree with finite differences and the two charts agree where they overlap.
#include <CGAL/Blended_shape/Primitives/Chart_mesh.h>
#include <CGAL/Blended_shape/Primitives/Superquadric_ellipsoid.h>
#include <CGAL/Blended_shape/Primitives/check_primitive.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <cmath>
#include <iostream>
#include <random>

namespace BS = CGAL::Blended_shapes;

template <class GeomTraits>
class Tapered_superquadric
{
  typedef BS::Superquadric_ellipsoid<GeomTraits> Base;

public:
  typedef GeomTraits Geom_traits;
  typedef typename GeomTraits::FT FT;
  typedef typename GeomTraits::Point_3 Point_3;
  typedef typename GeomTraits::Vector_3 Vector_3;
  static constexpr int number_of_parameters = Base::number_of_parameters + 2; // + taper kx, ky
  typedef Eigen::Matrix<double, number_of_parameters, 1> Parameter_vector;
  typedef Eigen::Matrix<double, 3, number_of_parameters> Jacobian;
  typedef Eigen::Matrix<double, 3, 2> Chart_jacobian;
  enum { KX = Base::number_of_parameters, KY };

  Tapered_superquadric(double a1, double a2, double a3, double e1, double e2, double kx, double ky)
  {
    Parameter_vector q;
    q << a1, a2, a3, e1, e2, kx, ky;
    set_parameters(q);
  }

  static const BS::Parameter_info& parameter_info(int i)
  {
    static const BS::Parameter_info taper[2] = {{"kx", -0.95, 0.95, 0., BS::Parameter_kind::Dimensionless},
                                                     {"ky", -0.95, 0.95, 0., BS::Parameter_kind::Dimensionless}};
    return i < KX ? Base::parameter_info(i) : taper[i - KX];
  }
  static const char* parameter_name(int i) { return parameter_info(i).name; }
  static double parameter_lower_bound(int i) { return parameter_info(i).lower_bound; }
  static double parameter_upper_bound(int i) { return parameter_info(i).upper_bound; }
  static double parameter_default_value(int i) { return parameter_info(i).default_value; }

  const Parameter_vector& parameters() const { return m_q; }
  void set_parameters(const Parameter_vector& q)
  {
    for(int i = KX; i <= KY; ++i)
      if(!(q[i] >= parameter_lower_bound(i) && q[i] <= parameter_upper_bound(i)))
        throw std::invalid_argument("Tapered_superquadric: taper must be in [-0.95, 0.95]");
    m_base.set_parameters(q.template head<Base::number_of_parameters>()); // checks the rest
    m_q = q;
  }

  // The charts, and which chart points are the same surface point, are the base ellipsoid's.
  std::size_t number_of_charts() const { return m_base.number_of_charts(); }
  BS::Chart_domain chart_domain(std::size_t c) const { return m_base.chart_domain(c); }
  bool to_chart(const BS::Chart_point& p, std::size_t t, BS::Chart_point& q) const { return m_base.to_chart(p, t, q); }
  BS::Chart_point canonical_chart_point(const BS::Chart_point& p) const { return m_base.canonical_chart_point(p); }

  Point_3 point(const BS::Chart_point& p) const
  {
    Jacobian J;
    return point_and_jacobian(p, J);
  }

  // Taper: X = (kx z / a3 + 1) x, Y = (ky z / a3 + 1) y, Z = z.
  Point_3 point_and_jacobian(const BS::Chart_point& p, Jacobian& J) const
  {
    typename Base::Jacobian Jb;
    const Point_3 s = m_base.point_and_jacobian(p, Jb);
    const double x = s.x(), y = s.y(), z = s.z(), a3 = m_q[Base::A3];
    const double kx = m_q[KX], ky = m_q[KY];
    const double fx = kx * z / a3 + 1., fy = ky * z / a3 + 1.;
    J.setZero();
    J.row(0).template head<Base::number_of_parameters>() = fx * Jb.row(0) + (x * kx / a3) * Jb.row(2);
    J.row(1).template head<Base::number_of_parameters>() = fy * Jb.row(1) + (y * ky / a3) * Jb.row(2);
    J.row(2).template head<Base::number_of_parameters>() = Jb.row(2);
    J(0, Base::A3) -= x * kx * z / (a3 * a3); // the taper is relative to a3
    J(1, Base::A3) -= y * ky * z / (a3 * a3);
    J(0, KX) = x * z / a3;
    J(1, KY) = y * z / a3;
    return Point_3(fx * x, fy * y, z);
  }
  void jacobian(const BS::Chart_point& p, Jacobian& J) const { point_and_jacobian(p, J); }

  // The chart Jacobian by the chain rule through the taper, like the
  // parameter Jacobian: dX = fx dx + (x kx / a3) dz, dY = fy dy + (y ky / a3) dz.
  Point_3 point_and_chart_jacobian(const BS::Chart_point& p, Chart_jacobian& D) const
  {
    typename Base::Chart_jacobian Db;
    const Point_3 s = m_base.point_and_chart_jacobian(p, Db);
    const double x = s.x(), y = s.y(), z = s.z(), a3 = m_q[Base::A3];
    const double kx = m_q[KX], ky = m_q[KY];
    const double fx = kx * z / a3 + 1., fy = ky * z / a3 + 1.;
    D.row(0) = fx * Db.row(0) + (x * kx / a3) * Db.row(2);
    D.row(1) = fy * Db.row(1) + (y * ky / a3) * Db.row(2);
    D.row(2) = Db.row(2);
    return Point_3(fx * x, fy * y, z);
  }

  // Normals transform by the inverse transpose of the taper's spatial Jacobian.
  Vector_3 normal(const BS::Chart_point& p) const
  {
    const Point_3 s = m_base.point(p);
    const Vector_3 n = m_base.normal(p);
    const double a3 = m_q[Base::A3], kx = m_q[KX], ky = m_q[KY];
    const double fx = kx * s.z() / a3 + 1., fy = ky * s.z() / a3 + 1.;
    const double m0 = n.x() / fx, m1 = n.y() / fy;
    const double m2 = n.z() - (s.x() * kx / a3) * m0 - (s.y() * ky / a3) * m1;
    const double len = std::sqrt(m0 * m0 + m1 * m1 + m2 * m2);
    return Vector_3(m0 / len, m1 / len, m2 / len);
  }

private:
  Base m_base;
  Parameter_vector m_q;
};

// Whether p is at least `margin` (in chart coordinates) away from the places
// where the ellipsoid's signed powers meet a zero cosine or sine: the chart
// axes (longitude a multiple of pi/2) and the equator rho = 1. Exponents other
// than 1 make the map non-smooth there, and finite differences cannot check
// the chart Jacobian near them.
bool away_from_zero_cosines(const BS::Chart_point& p, double margin)
{
  return std::abs(p.x) >= margin && std::abs(p.y) >= margin && std::abs(std::hypot(p.x, p.y) - 1.) >= margin;
}

int main()
{
  typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
  const Tapered_superquadric<K> pear(1., 1.2, 2., 0.6, 1.4, 0.5, -0.3);

  std::mt19937_64 rng(1);
  std::vector<BS::Chart_point> points;
  for(std::size_t c = 0; c < pear.number_of_charts(); ++c)
    for(int i = 0; i < 1000; ++i)
      points.push_back(BS::random_chart_point(pear, c, rng));
  points.emplace_back(0, 0., 0.); // the poles
  points.emplace_back(1, 0., 0.);

  const BS::Jacobian_check_report jac = BS::check_jacobian(pear, points);
  // The chart Jacobian: finite at every point, exact away from the zero cosines.
  std::vector<BS::Chart_point> smooth;
  while(smooth.size() < 2000)
  {
    const BS::Chart_point p = BS::random_chart_point(pear, smooth.size() % 2, rng);
    if(away_from_zero_cosines(p, 0.05))
      smooth.push_back(p);
  }
  const BS::Chart_jacobian_check_report chart_jac = BS::check_chart_jacobian(pear, smooth);
  const BS::Chart_jacobian_check_report chart_jac_all = BS::check_chart_jacobian(pear, points);
  const BS::Chart_consistency_report charts = BS::check_chart_consistency(pear, 2000);
  const auto meshes = BS::make_chart_meshes(pear, 16);

  std::cout << "Tapered superquadric, " << Tapered_superquadric<K>::number_of_parameters << " parameters\n"
            << "  Jacobian vs finite differences at " << jac.points_checked
            << " chart points: max relative error " << jac.max_relative_error << "\n"
            << "  chart Jacobian vs finite differences at " << chart_jac.points_checked
            << " chart points: max relative error " << chart_jac.max_relative_error
            << (chart_jac_all.has_non_finite ? " (NaN or infinity somewhere)" : " (finite everywhere)") << "\n"
            << "  charts agree at " << charts.pairs_checked << " overlapping points: max distance "
            << charts.max_relative_distance << " (relative), normals " << charts.max_normal_deviation << "\n"
            << "  chart meshes: " << meshes.size() << " x " << meshes[0].mesh().number_of_faces() << " triangles\n";
  const bool ok = !jac.has_non_finite && jac.max_relative_error < 1e-6 && !chart_jac_all.has_non_finite &&
                  !chart_jac.has_non_finite && chart_jac.max_relative_error < 1e-6 &&
                  charts.max_relative_distance < 1e-12;
  std::cout << (ok ? "custom primitive passes the generic checks" : "custom primitive FAILS the generic checks")
            << std::endl;
  return ok ? 0 : 1;
}
