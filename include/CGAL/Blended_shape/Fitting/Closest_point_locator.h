// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_BLENDED_SHAPE_FITTING_CLOSEST_POINT_LOCATOR_H
#define CGAL_BLENDED_SHAPE_FITTING_CLOSEST_POINT_LOCATOR_H

#include <CGAL/Blended_shape/Primitives/Chart_mesh.h>

#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>

#include <Eigen/Dense>

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <type_traits>
#include <utility>
#include <vector>

namespace CGAL {
namespace Blended_shapes {

/// \ingroup PkgBlendedShapeFitting
/// Where a query point's closest point on the model mesh lies.
template <class GeomTraits>
struct Located_point
{
  Chart_point chart_point;                  ///< the domain point of the closest mesh point
  typename GeomTraits::Point_3 mesh_point;  ///< the closest point on the (piecewise linear) mesh
  std::size_t chart_mesh = 0;               ///< index of the chart mesh holding it
  typename Chart_mesh<GeomTraits>::face_descriptor face; ///< the face of that chart mesh holding it
  std::array<double, 3> barycentric;        ///< in the vertex order of Chart_mesh::face_vertices()
};

namespace internal {

/// Barycentric coordinates of `q` (a point of the triangle's plane) in (a, b, c).
template <class Point_3>
std::array<double, 3> barycentric_coordinates(const Point_3& a, const Point_3& b, const Point_3& c, const Point_3& q)
{
  const auto v0 = b - a, v1 = c - a, v2 = q - a;
  const double d00 = CGAL::to_double(v0 * v0), d01 = CGAL::to_double(v0 * v1), d11 = CGAL::to_double(v1 * v1);
  const double d20 = CGAL::to_double(v2 * v0), d21 = CGAL::to_double(v2 * v1);
  const double den = d00 * d11 - d01 * d01;
  if(!(den > 0.)) // degenerate triangle: take its first vertex
    return {{1., 0., 0.}};
  double l1 = (d11 * d20 - d01 * d21) / den, l2 = (d00 * d21 - d01 * d20) / den;
  l1 = (std::min)((std::max)(l1, 0.), 1.);
  l2 = (std::min)((std::max)(l2, 0.), 1. - l1);
  return {{1. - l1 - l2, l1, l2}};
}

/// AABB traits whose closest-point test of a leaf triangle first compares
/// the distance to the triangle's plane with the best distance so far (the
/// bound): the triangle is no closer than its plane, so where the plane is
/// farther, the projection onto the triangle (CGAL's leaf test, 15 % of the
/// time of `blended_fit --splits creases` on the box/cylinder scan) is
/// skipped: that run 6.9 -> 6.2 s on one core, with the same bits. The plane must be farther by
/// a margin (1e-9 of the query's distance to the triangle's first corner,
/// far above the rounding of either distance): the answers are those of
/// CGAL's test, to the bit.
template <class GeomTraits, class Primitive>
class Plane_first_AABB_traits : public CGAL::AABB_traits<GeomTraits, Primitive>
{
  typedef CGAL::AABB_traits<GeomTraits, Primitive> Base;

public:
  class Closest_point
  {
    typedef typename GeomTraits::Point_3 Point;

  public:
    explicit Closest_point(const Plane_first_AABB_traits& traits) : m_traits(traits) {}

    Point operator()(const Point& p, const Primitive& pr, const Point& bound) const
    {
      const auto& t = pr.datum();
      const auto ab = t.vertex(1) - t.vertex(0), ac = t.vertex(2) - t.vertex(0), ap = p - t.vertex(0);
      const auto n = CGAL::cross_product(ab, ac);
      const double nn = CGAL::to_double(n * n);
      if(nn > 0.)
      {
        const double s = CGAL::to_double(ap * n);
        const double d = std::sqrt(CGAL::to_double(CGAL::squared_distance(p, bound))) +
                         1e-9 * std::sqrt(CGAL::to_double(ap * ap));
        if(s * s > d * d * nn)
          return bound;
      }
      return typename Base::Closest_point(m_traits)(p, pr, bound);
    }

  private:
    const Plane_first_AABB_traits& m_traits;
  };

  /// The node test: whether a node's box reaches into the ball about the
  /// query through the best point so far, in plain double arithmetic
  /// (CGAL's sphere-box test goes through the kernel's filtered predicate:
  /// 13 % of the same run). The ball is widened by 1e-9 of its radius
  /// squared, far above rounding: a node it keeps too many holds no point
  /// inside the ball, so the answers stay CGAL's.
  class Compare_distance
  {
    typedef typename GeomTraits::Point_3 Point;

  public:
    CGAL::Comparison_result operator()(const Point& p, const CGAL::Bbox_3& box, const Point& bound) const
    {
      const double x = CGAL::to_double(p.x()), y = CGAL::to_double(p.y()), z = CGAL::to_double(p.z());
      const double radius2 = CGAL::to_double(CGAL::squared_distance(p, bound));
      const double dx = (std::max)({box.xmin() - x, 0., x - box.xmax()});
      const double dy = (std::max)({box.ymin() - y, 0., y - box.ymax()});
      const double dz = (std::max)({box.zmin() - z, 0., z - box.zmax()});
      return dx * dx + dy * dy + dz * dz <= radius2 * (1. + 1e-9) ? CGAL::SMALLER : CGAL::LARGER;
    }
  };

  Closest_point closest_point_object() const { return Closest_point(*this); }
  Compare_distance compare_distance_object() const { return Compare_distance(); }
};

} // namespace internal

/*!
\ingroup PkgBlendedShapeFitting

Closest points on a model made of chart meshes (sec. 3.3: the union of the
per-chart meshes, spatially overlapping near seams), with one CGAL AABB tree
over the faces of all of them. A located point carries its chart, face and
barycentric coordinates, hence its domain point, at which the model is then
evaluated analytically (the mesh is only the search structure).

The chart meshes are held by reference: call rebuild() after their
positions changed. The queries are const: several threads may query one
locator at once (not during a rebuild()); the first unbounded query builds
the AABB tree's internal search tree, under CGAL's lock. With a face mask (set_face_mask()), only the faces it
keeps are searched: the per-component pieces of a blended shape (sec. 3.3)
omit the faces wholly in a discarded part of the domain.
*/
template <class GeomTraits>
class Closest_point_locator
{
public:
  typedef Chart_mesh<GeomTraits> Chart_mesh_type;  ///< one chart's tessellation
  typedef typename Chart_mesh_type::Mesh Mesh;      ///< its mesh type
  typedef typename GeomTraits::Point_3 Point_3;     ///< the point type
  /// The AABB primitive: a face of a chart mesh, its triangle cached in the
  /// primitive (a query's leaf tests then read three points instead of
  /// walking the face's halfedges: 15-20 % of a blended model's fit iteration).
  typedef CGAL::AABB_face_graph_triangle_primitive<Mesh, CGAL::Default, CGAL::Tag_false, CGAL::Tag_true> Primitive;
  /// The AABB traits: CGAL's, with cheaper leaf and node tests (internal::Plane_first_AABB_traits).
  typedef internal::Plane_first_AABB_traits<GeomTraits, Primitive> Traits;
  typedef CGAL::AABB_tree<Traits> Tree;                     ///< the AABB tree type

  /// Builds the tree over the faces of all `charts`, which must outlive the locator.
  explicit Closest_point_locator(const std::vector<Chart_mesh_type>& charts) : m_charts(&charts) { rebuild(); }

  /// Searches only the faces `mask[i][f]` of chart mesh `i` says to keep
  /// (indexed by face index), or every face if `mask` is null; `mask` must
  /// outlive the locator. Takes effect at the next rebuild().
  void set_face_mask(const std::vector<std::vector<bool>>* mask) { m_mask = mask; }

  /// Rebuilds the tree (after the chart mesh positions, or the face mask, changed).
  void rebuild()
  {
    m_tree.clear();
    for(std::size_t i = 0; i < m_charts->size(); ++i)
    {
      const Chart_mesh_type& cm = (*m_charts)[i];
      if(m_mask == nullptr)
      {
        m_tree.insert(faces(cm.mesh()).first, faces(cm.mesh()).second, cm.mesh());
        continue;
      }
      std::vector<typename Chart_mesh_type::face_descriptor> kept;
      for(auto f : faces(cm.mesh()))
        if(is_kept(i, f))
          kept.push_back(f);
      m_tree.insert(kept.begin(), kept.end(), cm.mesh());
    }
    if(m_tree.empty())
      throw std::invalid_argument("Closest_point_locator: no face to search (the face mask keeps none)");
    m_tree.build();
    // The search tree of the unbounded queries (locate()) is built by the
    // first of them, under CGAL's lock (several threads may query at once):
    // the bounded queries (locate_closer_than()) of a fit's trial steps do
    // not need it, and most rebuilds serve only those. (Without threads
    // CGAL does not lock: there it is built now.)
#ifndef CGAL_HAS_THREADS
    m_tree.accelerate_distance_queries();
#endif
    m_any_primitive = m_tree.any_reference_point_and_id().second;
  }

  /// The closest point to `query` on the chart meshes, with its chart point.
  Located_point<GeomTraits> locate(const Point_3& query) const
  {
    const auto hit = m_tree.closest_point_and_primitive(query);
    return make_location(hit.second.second, hit.second.first, hit.first);
  }

  /// The closest point to `query` on the chart meshes if it is at least as
  /// close as `bound` (any point, e.g. a foot point already found on the
  /// analytic surface) and differs from it: then `true`, with it in `result`.
  /// Otherwise `false` (and `result` is unchanged). The known distance bounds
  /// the search, which makes it much cheaper than locate() when it is small.
  bool locate_closer_than(const Point_3& query, const Point_3& bound, Located_point<GeomTraits>& result) const
  {
    const auto hit = m_tree.closest_point_and_primitive(
      query, typename Tree::Point_and_primitive_id(bound, m_any_primitive));
    if(hit.first == bound)
      return false;
    result = make_location(hit.second.second, hit.second.first, hit.first);
    return true;
  }

  /// The same answer by brute force over every face (for tests).
  Located_point<GeomTraits> locate_brute_force(const Point_3& query) const
  {
    double best = HUGE_VAL;
    Located_point<GeomTraits> result;
    for(std::size_t i = 0; i < m_charts->size(); ++i)
      for(auto f : faces((*m_charts)[i].mesh()))
      {
        const Chart_mesh_type& cm = (*m_charts)[i];
        if(!is_kept(i, f))
          continue;
        const auto v = cm.face_vertices(f);
        const typename GeomTraits::Triangle_3 t(cm.mesh().point(v[0]), cm.mesh().point(v[1]), cm.mesh().point(v[2]));
        const Point_3 c = GeomTraits().construct_projected_point_3_object()(t, query);
        const double d = CGAL::to_double(CGAL::squared_distance(c, query));
        if(d < best)
        {
          best = d;
          result = make_location(&cm.mesh(), f, c);
        }
      }
    return result;
  }

  /// The AABB tree (for further queries).
  const Tree& tree() const { return m_tree; }

private:
  Located_point<GeomTraits> make_location(const Mesh* mesh, typename Chart_mesh_type::face_descriptor f,
                                          const Point_3& p) const
  {
    Located_point<GeomTraits> loc;
    loc.mesh_point = p;
    loc.face = f;
    for(std::size_t i = 0; i < m_charts->size(); ++i)
      if(&(*m_charts)[i].mesh() == mesh)
        loc.chart_mesh = i;
    const Chart_mesh_type& cm = (*m_charts)[loc.chart_mesh];
    const auto v = cm.face_vertices(f);
    loc.barycentric = internal::barycentric_coordinates(cm.mesh().point(v[0]), cm.mesh().point(v[1]),
                                                        cm.mesh().point(v[2]), p);
    loc.chart_point = cm.chart_point(f, loc.barycentric);
    return loc;
  }

  bool is_kept(std::size_t i, typename Chart_mesh_type::face_descriptor f) const
  {
    return m_mask == nullptr || (*m_mask)[i][std::size_t(f)];
  }

  const std::vector<Chart_mesh_type>* m_charts;
  const std::vector<std::vector<bool>>* m_mask = nullptr;
  Tree m_tree;
  typename Primitive::Id m_any_primitive; // the id handed to bounded queries with their bound
};

namespace internal {

/// A foot point: the chart point `u`, the model point `x(u)` and `|p - x(u)|^2`;
/// with `has_normal`, the model's normal at `u` (as its normal() gives it).
struct Foot_point
{
  Chart_point u;
  Eigen::Vector3d x;
  double squared_distance;
  bool has_normal = false;
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
};

// Whether a model gives its normal with its chart Jacobian
// (Deformable_blended_model::canonical_surface_point_chart_jacobian_and_normal()).
template <class Model, class = void>
struct Has_normal_with_chart_jacobian : std::false_type
{};
template <class Model>
struct Has_normal_with_chart_jacobian<
  Model, std::void_t<decltype(std::declval<const Model&>().canonical_surface_point_chart_jacobian_and_normal(
           std::declval<const Chart_point&>(), std::declval<Chart_point&>(), std::declval<typename Model::Point_3&>(),
           std::declval<typename Model::Chart_jacobian&>(), std::declval<typename Model::Vector_3*>()))>>
  : std::true_type
{};

// The canonical point `v` of `w` on `model`, with the model point `x` and
// the chart Jacobian `D` there, in one pass (the point is located once);
// false if `w` is not on the surface. `has_normal`: whether `normal` is the
// model's normal() at `v`, which a model that gives it with its chart
// Jacobian (Has_normal_with_chart_jacobian) gives exactly where `w` is `v`
// itself (elsewhere it may differ by rounding: not taken).
template <class Model>
bool evaluate_canonical(const Model& model, const Chart_point& w, Chart_point& v, Eigen::Vector3d& x,
                        typename Model::Chart_jacobian& D, bool& has_normal, Eigen::Vector3d& normal)
{
  typename Model::Point_3 xm = CGAL::ORIGIN;
  has_normal = false;
  if constexpr(Has_normal_with_chart_jacobian<Model>::value)
  {
    typename Model::Vector_3 n;
    if(!model.canonical_surface_point_chart_jacobian_and_normal(w, v, xm, D, &n))
      return false;
    has_normal = v.chart == w.chart && v.x == w.x && v.y == w.y;
    normal = Eigen::Vector3d(n.x(), n.y(), n.z());
  }
  else if(!model.canonical_surface_point_and_chart_jacobian(w, v, xm, D))
    return false;
  x = Eigen::Vector3d(xm.x(), xm.y(), xm.z());
  return true;
}

/// A start of refine_foot_point() evaluated by the caller: a canonical
/// point of the surface with its model point `x`, chart Jacobian `J` and,
/// with `has_normal`, its normal (as evaluate_canonical() gives them).
template <class Model>
struct Evaluated_start
{
  Eigen::Vector3d x;
  typename Model::Chart_jacobian J;
  bool has_normal = false;
  Eigen::Vector3d normal;
};

// The state of refine_foot_point(): the current chart point `u`, model
// point `x`, squared distance `d2` to `p` and chart Jacobian `J`.
template <class Model>
class Foot_point_search
{
public:
  typedef typename Model::Chart_jacobian Chart_jacobian;

  Foot_point_search(const Model& model, const Eigen::Vector3d& p, double relative_tolerance)
    : m_model(model), m_p(p), m_relative_tolerance(relative_tolerance)
  {}

  // From the chart in which the start is canonical: a start on the rim of
  // its chart (a tessellation point near a chart seam) would otherwise be
  // stuck there by steps that leave the chart. An evaluated start is
  // canonical (see refine_foot_point()): taken as it is.
  void start_at(const Chart_point& start, const Evaluated_start<Model>* evaluated)
  {
    if(evaluated != nullptr)
    {
      u = start;
      x = evaluated->x;
      J = evaluated->J;
      has_n = evaluated->has_normal;
      n = evaluated->normal;
    }
    else if(eval_canonical(start, u, x, J))
      take_normal();
    else
      throw std::invalid_argument("refine_closest_point: the start is not a point of the model's surface");
    d2 = (m_p - x).squaredNorm();
  }

  // One iteration: true if it brought the point closer.
  bool iterate()
  {
    if(++m_iterations > newton_after && newton_step())
      return true;
    const State before = state();
    bool converged, left_surface;
    const bool improved = step_from(u, J, converged, left_surface);
    if(!converged && left_surface)
      return step_from_other_charts(before) || improved;
    return improved;
  }

  Foot_point result() const { return Foot_point{u, x, d2, has_n, n}; }
  double squared_distance() const { return d2; }

private:
  struct State
  {
    Chart_point u;
    Eigen::Vector3d x;
    double d2;
    Chart_jacobian J;
    bool has_n;
    Eigen::Vector3d n;
  };
  State state() const { return State{u, x, d2, J, has_n, n}; }
  void restore(const State& s) { u = s.u; x = s.x; d2 = s.d2; J = s.J; has_n = s.has_n; n = s.n; }

  // evaluate_canonical(), its normal kept for take_normal().
  bool eval_canonical(const Chart_point& w, Chart_point& v, Eigen::Vector3d& xv, Chart_jacobian& D)
  {
    return evaluate_canonical(m_model, w, v, xv, D, m_has_nv, m_nv);
  }
  // The normal of the last eval_canonical() becomes the current point's.
  void take_normal()
  {
    has_n = m_has_nv;
    n = m_nv;
  }

  // The point at chart point `w` becomes the current one if it is on the
  // surface and closer (then true, with its canonical chart point, Jacobian
  // and normal); `left_surface` is set if `w` is off the chart or in a
  // discarded part of the domain.
  bool move_if_closer(const Chart_point& w, bool& left_surface)
  {
    Chart_point v;
    Eigen::Vector3d xv; // with m_Jv, the Jacobian of the next step, if this one is kept
    if(!eval_canonical(w, v, xv, m_Jv))
    {
      left_surface = true;
      return false;
    }
    const double dv = (m_p - xv).squaredNorm();
    if(!(dv < d2))
      return false;
    u = v; x = xv; d2 = dv; J = m_Jv;
    take_normal();
    return true;
  }

  // One safeguarded Gauss-Newton step in the coordinates of chart point
  // `from` (the current point, or another representative of it) with the
  // chart Jacobian `Jf` there: true if it brought the point closer (then u,
  // x, d2, J are the new point's). `converged`: no step is worth taking;
  // `left_surface`: a trial left the chart or the surface.
  bool step_from(const Chart_point& from, const Chart_jacobian& Jf, bool& converged, bool& left_surface)
  {
      converged = left_surface = false;
      const double j00 = Jf.col(0).squaredNorm(), j11 = Jf.col(1).squaredNorm(), j01 = Jf.col(0).dot(Jf.col(1));
      const double t = j00 + j11;
      if(!(t > 0.) || !std::isfinite(t))
        return false;
      const Eigen::Vector3d r = m_p - x;
      const double g0 = Jf.col(0).dot(r), g1 = Jf.col(1).dot(r);
      // Levenberg-regularized: where exponents above 1 flatten the map (its chart
      // Jacobian loses rank on the poles and axes) the step still moves along
      // the direction that is left. When one column is much shorter than the
      // other (next to such a place) and the step fails, it is retried with a
      // strong damping of that direction: its Gauss-Newton step is then far too
      // long, and would otherwise take the good step along the other one with it.
      const bool ill_conditioned = (std::min)(j00, j11) < 1e-3 * t;
      for(int level = 0; level < (ill_conditioned ? 2 : 1); ++level)
      {
        // the 2 x 2 system (J^T J + mu tr I) step = J^T r, solved in closed form
        // (positive definite: the damping keeps the determinant away from zero)
        const double mu = (level == 0 ? 1e-10 : 1e-3) * t;
        const double a = j00 + mu, c = j11 + mu, det = a * c - j01 * j01;
        if(!(det > 0.))
          return false;
        Eigen::Vector2d step((c * g0 - j01 * g1) / det, (a * g1 - j01 * g0) / det);
        const double length2 = step.squaredNorm();
        // At the foot point to the accuracy that matters: a tangential error
        // of 1e-9 chart units changes the distance by ~1e-18 of the model's size.
        if(!(length2 > 1e-18) || (level == 0 && step.dot(Eigen::Vector2d(g0, g1)) <= m_relative_tolerance * d2))
        {
          converged = true;
          return false;
        }
        // A step this short that fails at full length fails on rounding alone
        // (the squared distance is only known to ~1e-13 relatively): halving it
        // cannot help.
        // Next to a point where the chart map is singular (exponents above 1
        // on both the equator and a meridian: both columns vanish) the
        // Gauss-Newton step overshoots by orders of magnitude: up to 12 halvings
        // (a step 4096 times shorter), down to that length.
        const int halvings = (length2 < 1e-14) ? 1 : 12;
        for(int half = 0; half < halvings && (half < 4 || step.squaredNorm() >= 1e-14); ++half, step *= 0.5)
          if(move_if_closer(Chart_point(from.chart, from.x + step[0], from.y + step[1]), left_surface))
            return true;
        if(length2 < 1e-14)
        {
          converged = true;
          return false;
        }
      }
      return false;
  }

  // Away from the surface Gauss-Newton converges linearly, at the rate
  // distance x curvature, which nears 1 next to a focal point (a point
  // inside a concave region at about its radius of curvature, as in the
  // strips of blends and holes): there hundreds of steps may be needed. A
  // point still moving after newton_after Gauss-Newton steps takes Newton
  // steps instead: the Hessian of |p - x(u)|^2 / 2 is J^T J - sum_i r_i
  // d^2 x_i / du^2, the second derivatives by forward differences of the
  // chart Jacobian (two more evaluations per step). Where that Hessian is not
  // positive definite, or the step does not bring the point closer (also
  // halved once), Gauss-Newton steps on. After 8 steps, not 4: with 4,
  // the Newton steps of points that would have converged anyway took 20 %
  // of a 200-point fit of one superquadric (with 8, 5 %); the 12 steps left
  // of the default 20 are plenty where Newton converges quadratically.
  static constexpr int newton_after = 8;

  bool newton_step()
  {
    const double h = 1e-6;
    Chart_jacobian dJ[2];
    for(int k = 0; k < 2; ++k)
    {
      const Chart_point w(u.chart, u.x + (k == 0 ? h : 0.), u.y + (k == 1 ? h : 0.));
      Chart_point v;
      Eigen::Vector3d xv;
      // the same chart: a canonical point elsewhere has other coordinates
      if(!eval_canonical(w, v, xv, m_Jv) || v.chart != w.chart || v.x != w.x || v.y != w.y)
        return false;
      dJ[k] = (m_Jv - J) / h;
    }
    const Eigen::Vector3d r = m_p - x;
    Eigen::Matrix2d H = J.transpose() * J;
    for(int a = 0; a < 2; ++a)
      for(int b = 0; b < 2; ++b)
        H(a, b) -= 0.5 * (r.dot(dJ[b].col(a)) + r.dot(dJ[a].col(b)));
    const double det = H.determinant();
    if(!(H(0, 0) > 0. && det > 1e-12 * CGAL::square(H.trace())))
      return false;
    Eigen::Vector2d step = H.inverse() * (J.transpose() * r);
    bool left_surface = false; // (a Newton step off the surface is only not taken)
    for(int half = 0; half < 2; ++half, step *= 0.5)
      if(move_if_closer(Chart_point(u.chart, u.x + step[0], u.y + step[1]), left_surface))
        return true;
    return false;
  }

  // A step toward the discarded edge of a blend's strip (or disk): the
  // surface goes on in the added component's chart, so a step is also taken
  // from the same point (`before`) expressed there, with a chart Jacobian by
  // central differences (rare); the closer result is kept. True if one of
  // them is closer than the step already taken from `before`.
  bool step_from_other_charts(const State& before)
  {
    const std::vector<Chart_point> others = m_model.alternative_chart_points(before.u);
    const State first = state();
    for(const Chart_point& w : others)
    {
      restore(before);
      Chart_jacobian Jw;
      if(!difference_jacobian(w, Jw))
        continue;
      bool c2, l2;
      if(step_from(w, Jw, c2, l2) && d2 < first.d2)
        return true;
      restore(first);
    }
    return false;
  }

  // The chart Jacobian at `w` by differences: central where both neighbours
  // lie on the surface, one-sided at the rim of the chart (a point there may
  // be the other chart's representative of a point near the seam). False if
  // neither neighbour of a direction is on the surface.
  bool difference_jacobian(const Chart_point& w, Chart_jacobian& Jw) const
  {
    const double h = 1e-7;
    Chart_point ignored;
    const auto on_surface = [&](const Chart_point& c) { return m_model.canonical_surface_point(c, ignored); };
    const auto position = [&](const Chart_point& c) {
      const auto xc = m_model.point(c);
      return Eigen::Vector3d(xc.x(), xc.y(), xc.z());
    };
    for(int k = 0; k < 2; ++k)
    {
      const Chart_point a(w.chart, w.x + (k == 0 ? h : 0.), w.y + (k == 1 ? h : 0.));
      const Chart_point b(w.chart, w.x - (k == 0 ? h : 0.), w.y - (k == 1 ? h : 0.));
      const bool has_a = on_surface(a), has_b = on_surface(b);
      if(has_a && has_b)
        Jw.col(k) = (position(a) - position(b)) / (2. * h);
      else if(has_a)
        Jw.col(k) = (position(a) - position(w)) / h;
      else if(has_b)
        Jw.col(k) = (position(w) - position(b)) / h;
      else
        return false;
    }
    return true;
  }

  const Model& m_model;
  const Eigen::Vector3d m_p;
  const double m_relative_tolerance;
  Chart_point u;
  Eigen::Vector3d x;
  double d2 = 0.;
  Chart_jacobian J, m_Jv;
  bool has_n = false; // whether `n` is the normal at `u`
  Eigen::Vector3d n = Eigen::Vector3d::Zero();
  bool m_has_nv = false; // the normal of the last eval_canonical(), see there
  Eigen::Vector3d m_nv = Eigen::Vector3d::Zero();
  int m_iterations = 0;
};

/// refine_closest_point(), also returning the model point and the squared
/// distance at the result (computed as `(p - model.point(u)).squaredNorm()` would be).
/// With `relative_tolerance` > 0 it also stops when a Gauss-Newton step
/// would lower the squared distance by at most that fraction of it (the
/// predicted decrease `g . step`): where the distance matters and the exact
/// foot point does not (the fitter's correspondences, whose distance is only
/// off by the square of the remaining tangential error), this saves the
/// tail of the iteration, which converges only linearly away from the
/// surface (at the rate distance x curvature).
/// With `evaluated`, the evaluation of `start`, which must be a canonical
/// point of the surface (evaluate_canonical() returned it as its own
/// canonical point): saving its evaluation and its location.
/// The result has the model's normal where the search's evaluations gave it
/// (evaluate_canonical()).
template <class Model>
Foot_point refine_foot_point(const Model& model, const Eigen::Vector3d& p, Chart_point start, int max_iterations,
                             double relative_tolerance = 0., const Evaluated_start<Model>* evaluated = nullptr)
{
  Foot_point_search<Model> search(model, p, relative_tolerance);
  search.start_at(start, evaluated);
  for(int it = 0; it < max_iterations && search.squared_distance() > 0.; ++it)
    if(!search.iterate())
      break;
  return search.result();
}

} // namespace internal

/*!
\ingroup PkgBlendedShapeFitting
The closest point of `p` on the analytic surface of `model`, starting from
`start` (typically the chart point of the closest point on the tessellation,
Closest_point_locator::locate()): at most `max_iterations` safeguarded
Gauss-Newton steps on the chart coordinates, with the analytic chart
Jacobian (`point_and_chart_jacobian()`: one evaluation per step, which also
gives the point), each kept only if it brings the model point closer (the
step is halved up to three times otherwise, and where the chart Jacobian is
ill-conditioned, retried with a strong Levenberg damping). A step that leaves
a chart is taken in the canonical chart of its end point. The iteration stops
when the step is below 1e-9 chart units (the foot point is then known far
beyond what distances and normals need), or when a step shorter than 1e-7
fails (it then only fails on rounding).

The tessellation is a piecewise linear approximation: a closest point found
on it maps back to a chart point a little off the true foot point (by the
chord error of the chart triangle), and two charts that share a mesh edge map
it to different such chart points. Refinement removes this.

`Model` provides `point_and_chart_jacobian()` and `canonical_surface_point()`
(as Deformable_model and Deformable_blended_model do); steps that leave the
surface (a chart's domain, or into a discarded part of a blended shape's
domain) are treated as failed.
\throws std::invalid_argument if `start` is not on the surface.
*/
template <class Model>
Chart_point refine_closest_point(const Model& model, const Eigen::Vector3d& p, Chart_point start, int max_iterations)
{
  return internal::refine_foot_point(model, p, start, max_iterations).u;
}


} // namespace Blended_shapes
} // namespace CGAL

#endif // CGAL_BLENDED_SHAPE_FITTING_CLOSEST_POINT_LOCATOR_H
