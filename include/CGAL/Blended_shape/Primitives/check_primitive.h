// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_BLENDED_SHAPE_PRIMITIVES_CHECK_PRIMITIVE_H
#define CGAL_BLENDED_SHAPE_PRIMITIVES_CHECK_PRIMITIVE_H

#include <CGAL/Blended_shape/Primitives/Chart_domain.h>

#include <CGAL/number_utils.h>
#include <CGAL/squared_distance_3.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <random>
#include <vector>

namespace CGAL {
namespace Blended_shapes {
namespace internal {

// The coordinates of a kernel point, as doubles.
template <class Point_3>
std::array<double, 3> coordinates(const Point_3& p)
{
  return std::array<double, 3>{{CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z())}};
}

// |M_k - fd| / max(|fd|, floor): the error of column k of an analytic
// Jacobian against its finite difference, relative but floored so that
// vanishing columns are compared at the scale of the shape.
template <class Matrix>
double relative_column_error(const Matrix& M, int k, const double fd[3], double floor)
{
  double diff = 0., norm = 0.;
  for(int r = 0; r < 3; ++r)
  {
    diff += (M(r, k) - fd[r]) * (M(r, k) - fd[r]);
    norm += fd[r] * fd[r];
  }
  return std::sqrt(diff) / (std::max)(std::sqrt(norm), floor);
}

// Whether `err` is a new largest error (a NaN counts as one, and is kept as
// infinity), kept in `maximum`.
inline bool raise_maximum(double err, double& maximum)
{
  if(err <= maximum)
    return false;
  maximum = std::isfinite(err) ? err : HUGE_VAL;
  return true;
}

} // namespace internal

/// \ingroup PkgBlendedShapeChecks
/// A uniformly distributed point of chart `chart` of `primitive`
/// (rejection sampling in the disk; uniform in the torus square `[0, 2 pi)^2`;
/// uniform in the tube strip, `x` in `[0, 2 pi)`, `y` in `[y_min, y_max)`).
template <class Primitive, class RandomEngine>
Chart_point random_chart_point(const Primitive& primitive, std::size_t chart, RandomEngine& rng)
{
  const Chart_domain d = primitive.chart_domain(chart);
  std::uniform_real_distribution<double> unit(0., 1.);
  if(d.kind == Chart_kind::Torus)
    return Chart_point(chart, d.period() * unit(rng), d.period() * unit(rng));
  if(d.kind == Chart_kind::Tube)
  {
    const double x = d.period() * unit(rng);
    return Chart_point(chart, x, d.y_min + (d.y_max - d.y_min) * unit(rng));
  }
  for(;;)
  {
    const double x = d.radius * (2. * unit(rng) - 1.), y = d.radius * (2. * unit(rng) - 1.);
    if(d.contains(x, y))
      return Chart_point(chart, x, y);
  }
}

/// \ingroup PkgBlendedShapeChecks
/// What check_jacobian() found.
struct Jacobian_check_report
{
  std::size_t points_checked = 0; ///< the number of chart points checked
  /// largest relative column error |J_i - FD_i| / max(|FD_i|, floor) over all points and parameters
  double max_relative_error = 0.;
  int worst_parameter = -1;    ///< the parameter (column) of the largest error, -1 if none
  Chart_point worst_point;     ///< the chart point of the largest error
  bool has_non_finite = false; ///< a NaN or infinity in J or in the point
};

/*!
\ingroup PkgBlendedShapeChecks
Compares the analytic parameter Jacobian of any model of `BlendedShapePrimitive`
with finite differences at the given chart points.

Column `i` of the Jacobian is compared with the central difference
(s(q + h e_i) - s(q - h e_i)) / 2h, h = `relative_step * max(|q_i|, 1)`;
next to a parameter bound it uses the second-order one-sided difference
toward the interior, so parameters at their bounds are checked too. The error
of a column is relative to its finite-difference norm, with a floor of
`1e-4 |s(u)|` so that columns that vanish (e.g. d/de where |cos| = 1) are
compared in absolute terms at the scale of the shape.
*/
template <class Primitive>
Jacobian_check_report check_jacobian(const Primitive& primitive,
                                     const std::vector<Chart_point>& points,
                                     double relative_step = 1e-5)
{
  typedef typename Primitive::Parameter_vector Parameter_vector;
  typedef typename Primitive::Jacobian Jacobian;
  const int P = Primitive::number_of_parameters;

  Jacobian_check_report report;
  const Parameter_vector q0 = primitive.parameters();
  // One perturbed copy per parameter and offset, made once.
  std::vector<std::array<Primitive, 3>> shifted;
  std::vector<std::array<double, 3>> weights; // finite-difference weights / h for offsets
  for(int i = 0; i < P; ++i)
  {
    const double h = relative_step * (std::max)(std::abs(q0[i]), 1.);
    const double lo = Primitive::parameter_lower_bound(i), hi = Primitive::parameter_upper_bound(i);
    double offsets[3];
    std::array<double, 3> w;
    if(q0[i] - h >= lo && q0[i] + h <= hi)
    { offsets[0] = -h; offsets[1] = 0.; offsets[2] = h; w = {{-0.5 / h, 0., 0.5 / h}}; }
    else if(q0[i] - h < lo)
    { offsets[0] = 0.; offsets[1] = h; offsets[2] = 2. * h; w = {{-1.5 / h, 2. / h, -0.5 / h}}; }
    else
    { offsets[0] = 0.; offsets[1] = -h; offsets[2] = -2. * h; w = {{1.5 / h, -2. / h, 0.5 / h}}; }
    std::array<Primitive, 3> copies = {{primitive, primitive, primitive}};
    for(int k = 0; k < 3; ++k)
    {
      Parameter_vector q = q0;
      q[i] += offsets[k];
      copies[std::size_t(k)].set_parameters(q);
    }
    shifted.push_back(copies);
    weights.push_back(w);
  }

  Jacobian J;
  for(const Chart_point& u : points)
  {
    const std::array<double, 3> s = internal::coordinates(primitive.point_and_jacobian(u, J));
    ++report.points_checked;
    const double scale = std::sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2]);
    if(!J.allFinite() || !std::isfinite(scale))
      report.has_non_finite = true;
    for(int i = 0; i < P; ++i)
    {
      double fd[3] = {0., 0., 0.};
      for(int k = 0; k < 3; ++k)
      {
        const std::array<double, 3> sk = internal::coordinates(shifted[std::size_t(i)][std::size_t(k)].point(u));
        for(int r = 0; r < 3; ++r)
          fd[r] += weights[std::size_t(i)][std::size_t(k)] * sk[std::size_t(r)];
      }
      const double err = internal::relative_column_error(J, i, fd, 1e-4 * scale + 1e-300);
      if(internal::raise_maximum(err, report.max_relative_error))
      {
        report.worst_parameter = i;
        report.worst_point = u;
      }
    }
  }
  return report;
}

/// \ingroup PkgBlendedShapeChecks
/// What check_chart_jacobian() found.
struct Chart_jacobian_check_report
{
  std::size_t points_checked = 0;    ///< the number of chart points checked
  std::size_t one_sided_columns = 0; ///< columns compared with a one-sided difference (the central stencil left the domain)
  std::size_t skipped_columns = 0;   ///< columns not compared: no stencil of that step fits in the domain
  /// largest relative column error |D_k - FD_k| / max(|FD_k|, floor) over all points and both columns
  double max_relative_error = 0.;
  int worst_column = -1;       ///< the column (0: d/dx, 1: d/dy) of the largest error, -1 if none
  Chart_point worst_point;     ///< the chart point of the largest error
  bool has_non_finite = false; ///< a NaN or infinity in D or in the point, at any of the points
};

/*!
\ingroup PkgBlendedShapeChecks
Compares the analytic chart Jacobian of any model of `BlendedShapePrimitive`
(`point_and_chart_jacobian()`) with finite differences of `point()` at the
given chart points.

Column `k` (the derivative along chart coordinate `k`, `x` or `y`) is
compared with the central difference (s(u + h e_k) - s(u - h e_k)) / 2h,
h = `step` (chart coordinates are of order 1). Where that stencil leaves the
chart's domain (`chart_domain().contains()`, e.g. at the rim of a disk) the
second-order one-sided difference toward the inside is used, and where that
leaves it too the column is skipped; periodic coordinates never leave it.
The error of a column is relative to its finite-difference norm, with a
floor of `1e-4` times the size of the shape (the largest |s(u)| over
`points`), so that columns that vanish (e.g. at a pole with exponents above
1) are compared in absolute terms.

The map need not be differentiable everywhere (signed powers with exponents
other than 1 at a zero cosine or sine, the pole of the ellipsoid, the pinch of
a closed hole): near such a place the finite differences themselves are
wrong, by about (h / d)^2 relative at a distance d from it. For an accuracy
check give points away from them; `has_non_finite` is meaningful at every point.
*/
template <class Primitive>
Chart_jacobian_check_report check_chart_jacobian(const Primitive& primitive,
                                                 const std::vector<Chart_point>& points,
                                                 double step = 1e-5)
{
  typedef typename Primitive::Chart_jacobian Chart_jacobian;
  Chart_jacobian_check_report report;
  double size = 0.;
  for(const Chart_point& u : points)
  {
    const std::array<double, 3> s = internal::coordinates(primitive.point(u));
    const double n = std::sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2]);
    if(std::isfinite(n))
      size = (std::max)(size, n);
  }
  const double floor = 1e-4 * size + 1e-300;
  const double h = step;
  Chart_jacobian D;
  for(const Chart_point& u : points)
  {
    const std::array<double, 3> s = internal::coordinates(primitive.point_and_chart_jacobian(u, D));
    ++report.points_checked;
    if(!D.allFinite() || !std::isfinite(s[0] + s[1] + s[2]))
      report.has_non_finite = true;
    const Chart_domain dom = primitive.chart_domain(u.chart);
    for(int k = 0; k < 2; ++k)
    {
      auto at = [&](double t) { return k == 0 ? Chart_point(u.chart, u.x + t, u.y) : Chart_point(u.chart, u.x, u.y + t); };
      auto inside = [&](double t) { const Chart_point v = at(t); return dom.contains(v.x, v.y); };
      double offsets[3], w[3];
      if(inside(-h) && inside(h))
      { offsets[0] = -h; offsets[1] = 0.; offsets[2] = h; w[0] = -0.5 / h; w[1] = 0.; w[2] = 0.5 / h; }
      else if(inside(h) && inside(2. * h))
      { offsets[0] = 0.; offsets[1] = h; offsets[2] = 2. * h; w[0] = -1.5 / h; w[1] = 2. / h; w[2] = -0.5 / h; }
      else if(inside(-h) && inside(-2. * h))
      { offsets[0] = 0.; offsets[1] = -h; offsets[2] = -2. * h; w[0] = 1.5 / h; w[1] = -2. / h; w[2] = 0.5 / h; }
      else
      { ++report.skipped_columns; continue; }
      if(offsets[0] == 0.)
        ++report.one_sided_columns;
      double fd[3] = {0., 0., 0.};
      for(int j = 0; j < 3; ++j)
      {
        if(w[j] == 0.)
          continue;
        const std::array<double, 3> sj = internal::coordinates(primitive.point(at(offsets[j])));
        for(int r = 0; r < 3; ++r)
          fd[r] += w[j] * sj[std::size_t(r)];
      }
      const double err = internal::relative_column_error(D, k, fd, floor);
      if(internal::raise_maximum(err, report.max_relative_error))
      {
        report.worst_column = k;
        report.worst_point = u;
      }
    }
  }
  return report;
}

/// \ingroup PkgBlendedShapeChecks
/// What check_chart_consistency() found.
struct Chart_consistency_report
{
  std::size_t points_sampled = 0;      ///< random chart points drawn, over all charts
  std::size_t pairs_checked = 0;       ///< chart points that another chart (or a period shift) also covers
  double max_relative_distance = 0.;   ///< |s(p) - s(q)| / shape size, over identified pairs
  double max_round_trip_error = 0.;    ///< chart distance of p -> other chart -> back
  double max_normal_deviation = 0.;    ///< |n(p) - n(q)| over identified pairs
  Chart_point worst_point;             ///< the chart point p of the largest distance
};

/*!
\ingroup PkgBlendedShapeChecks
Samples `samples_per_chart` random points in every chart of `primitive`, and
for every point that another chart also covers (`to_chart()` succeeds) checks
that both give the same surface point and normal, that going back lands on
the starting chart point, and that both have the same canonical
representative. Periodic charts are also checked against a shift by one
period in each periodic coordinate (both for a torus, `x` only for a tube).
Distances are relative to the largest |s(u)| seen.
*/
template <class Primitive>
Chart_consistency_report check_chart_consistency(const Primitive& primitive,
                                                 std::size_t samples_per_chart,
                                                 unsigned int seed = 0)
{
  typedef typename Primitive::Point_3 Point_3;
  typedef typename Primitive::Vector_3 Vector_3;
  std::mt19937_64 rng(seed);
  Chart_consistency_report report;
  double size = 0.;
  struct Pair { Chart_point p, q; };
  std::vector<Pair> pairs;
  auto note_size = [&](const Point_3& s) {
    size = (std::max)(size, std::sqrt(CGAL::to_double(s.x() * s.x() + s.y() * s.y() + s.z() * s.z())));
  };
  for(std::size_t c = 0; c < primitive.number_of_charts(); ++c)
  {
    const Chart_domain d = primitive.chart_domain(c);
    for(std::size_t n = 0; n < samples_per_chart; ++n)
    {
      const Chart_point p = random_chart_point(primitive, c, rng);
      ++report.points_sampled;
      note_size(primitive.point(p));
      for(std::size_t t = 0; t < primitive.number_of_charts(); ++t)
      {
        Chart_point q;
        if(t == c || !primitive.to_chart(p, t, q))
          continue;
        pairs.push_back(Pair{p, q});
        Chart_point back;
        const bool ok = primitive.to_chart(q, c, back);
        const double e = ok ? std::hypot(back.x - p.x, back.y - p.y) : HUGE_VAL;
        report.max_round_trip_error = (std::max)(report.max_round_trip_error, e);
      }
      // periodic coordinates only: the tube's y boundaries are not seams
      for(int k = 0; k < 2; ++k)
      {
        const double period = (k == 0) ? d.x_period() : d.y_period();
        if(!(period > 0.))
          continue;
        Chart_point q = p;
        (k == 0 ? q.x : q.y) += period;
        pairs.push_back(Pair{p, q});
      }
    }
  }
  for(const Pair& pq : pairs)
  {
    ++report.pairs_checked;
    const Point_3 a = primitive.point(pq.p), b = primitive.point(pq.q);
    const Vector_3 na = primitive.normal(pq.p), nb = primitive.normal(pq.q);
    const Point_3 ca = primitive.point(primitive.canonical_chart_point(pq.p));
    const Point_3 cb = primitive.point(primitive.canonical_chart_point(pq.q));
    const double dist = (std::max)(std::sqrt(CGAL::to_double(CGAL::squared_distance(a, b))),
                                   std::sqrt(CGAL::to_double(CGAL::squared_distance(ca, cb))));
    const double rel = (size > 0.) ? dist / size : dist;
    const double ndev = std::sqrt(CGAL::to_double((na - nb).squared_length()));
    if(!(rel <= report.max_relative_distance))
    {
      report.max_relative_distance = std::isfinite(rel) ? rel : HUGE_VAL;
      report.worst_point = pq.p;
    }
    report.max_normal_deviation = (std::max)(report.max_normal_deviation, std::isfinite(ndev) ? ndev : HUGE_VAL);
  }
  return report;
}

} // namespace Blended_shapes
} // namespace CGAL

#endif // CGAL_BLENDED_SHAPE_PRIMITIVES_CHECK_PRIMITIVE_H
