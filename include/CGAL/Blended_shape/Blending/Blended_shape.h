// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_BLENDED_SHAPE_BLENDING_BLENDED_SHAPE_H
#define CGAL_BLENDED_SHAPE_BLENDING_BLENDED_SHAPE_H

#include <CGAL/Blended_shape/Blending/Blend.h>
#include <CGAL/Blended_shape/Blending/Shape_point.h>
#include <CGAL/Blended_shape/Blending/internal/Parameter_layout.h>
#include <CGAL/Blended_shape/Blending/internal/blend_correspondence.h>
#include <CGAL/Blended_shape/Blending/internal/blend_region_checks.h>
#include <CGAL/Blended_shape/Blending/internal/hole_placement.h>
#include <CGAL/Blended_shape/Primitives/Component_shape.h>
#include <CGAL/Blended_shape/Primitives/Hole_component.h>
#include <CGAL/Blended_shape/Primitives/Superquadric_ellipsoid.h>
#include <CGAL/Blended_shape/Primitives/Superquadric_toroid.h>
#include <CGAL/Blended_shape/internal/quaternion.h>

#include <Eigen/Core>
#include <Eigen/Dense>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <memory>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace CGAL {
namespace Blended_shapes {

/// \ingroup PkgBlendedShapeBlending
/// A block of consecutive columns of a model Jacobian: a point depends only
/// on the components and blends that reach it (sparse, eq. 10).
struct Jacobian_block
{
  std::size_t first_column = 0;                    ///< the index of the block's first parameter
  Eigen::Matrix<double, 3, Eigen::Dynamic> columns; ///< the block, 3 x its number of parameters
};

/*!
\ingroup PkgBlendedShapeBlending

A blended shape (sec. 3): components cut and glued by blends, nested so
that every blend's base is the blended shape built so far (sec. 3.6).

<b>Components.</b> Component 0 is the root; every other component has a
rigid placement relative to its parent (sec. 3.5), the base component of the
blend that added it (for a hole, the base of its end 0): a translation and a
quaternion (normalized in use, as in `Deformable_model`), which are
parameters of the shape. A component point is `t + R s(u)` in its parent's
frame; composed along the parents, `T + Q s(u)` in the root's frame
(root_translation(), root_rotation()), so a part moves with the part it is
attached to.

<b>Domain.</b> The domain is the disjoint union of the components' charts
glued by the primitives' own seams (`to_chart()`) and by the blends'
correspondences `beta` (eq. 1, 2, 16). `canonical_point()` picks one
representative per point of the quotient: a point in the added side of a
blend goes to its base point (eq. 3 defines `s` on `omega_1` only); a
point in a base region's strip or disk goes to the region's chart (so a
region may reach past a chart seam into the chart margin, A.2.1); points in
discarded parts of the domain are not on the surface.

<b>Evaluation</b> (eq. 3, 4). At a canonical point in the strip or disk of
blend `b`: `s = alpha s_1(u) + (1 - alpha) s_2(beta(u))`, with `s_1` the
base component and `s_2` the added one (both placed). Elsewhere a component
is itself. Regions of different blends do not overlap (checked when blends
are added), so at most one blend reaches a point.

<b>Jacobian</b> (eq. 10, 11). `alpha L_1`, `(1 - alpha) L_2` (placement
and shape of both components) and, for the blend's seven parameters,
`(s_1 - s_2) ∂alpha/∂q_b + (1 - alpha) (∂s_2/∂u_2)(∂beta/∂q_b)`.
The second term, absent from eq. 11, is the motion of `beta(u)` when
the region moves: without it the Jacobian is not the derivative of `s`.

<b>Parameters.</b> In order: the root's shape parameters; for every other
component its placement (3 + 4) then its shape parameters; then for every
blend the seven region parameters `(e_u, e_v, e_1, e_2, e_theta, w, h)`.
Some are held fixed (`is_fixed_parameter()`): `h` of annulus blends and
`a4`, `a5` of a hole component in its Two_disks domain, and those a user
holds (`hold_parameter()`).

\tparam GeomTraits a CGAL kernel whose `FT` is `double`.
*/
template <class GeomTraits>
class Blended_shape
{
public:
  typedef GeomTraits Geom_traits;                  ///< the kernel
  typedef typename Geom_traits::Point_3 Point_3;   ///< the point type
  typedef typename Geom_traits::Vector_3 Vector_3; ///< the vector type
  typedef Superquadric_ellipsoid<GeomTraits> Ellipsoid; ///< the ellipsoid primitive
  typedef Superquadric_toroid<GeomTraits> Toroid;       ///< the toroid primitive
  typedef Hole_component<GeomTraits> Hole;              ///< the hole component
  typedef std::vector<Jacobian_block> Sparse_jacobian;  ///< a sparse model Jacobian at one point

  /// Number of placement parameters of a non-root component.
  static constexpr std::size_t number_of_placement_parameters = internal::Parameter_layout::number_of_placement_parameters;
  /// Number of parameters of a blend (eq. 29).
  static constexpr std::size_t number_of_blend_parameters = Ellipse_blending_region::number_of_parameters;

  /// A component: the primitive and its placement relative to its parent.
  class Component
  {
  public:
    /// The primitive.
    const Component_shape& shape() const { return *m_shape; }
    /// The translation relative to the parent (Blended_shape::parent()).
    const Eigen::Vector3d& translation() const { return m_t; }
    /// The quaternion (w, x, y, z) relative to the parent.
    const Eigen::Vector4d& quaternion() const { return m_q; }
    /// The rotation matrix of quaternion().
    const Eigen::Matrix3d& rotation() const { return m_R; }

    /// A deep copy.
    Component(const Component& o) : m_shape(o.m_shape->clone()), m_t(o.m_t), m_q(o.m_q), m_R(o.m_R), m_dR(o.m_dR) {}
    /// A deep copy.
    Component& operator=(const Component& o)
    {
      Component c(o);
      std::swap(m_shape, c.m_shape);
      m_t = o.m_t;
      m_q = o.m_q;
      m_R = o.m_R;
      m_dR = o.m_dR;
      return *this;
    }

  private:
    friend class Blended_shape;
    Component(std::unique_ptr<Component_shape> s, const Eigen::Vector3d& t, const Eigen::Vector4d& q)
      : m_shape(std::move(s)), m_t(t)
    {
      set_placement_quaternion(q);
    }
    void set_placement_quaternion(const Eigen::Vector4d& q)
    {
      if(!q.allFinite() || !(q.norm() > 1e-12))
        throw std::invalid_argument("Blended_shape: a placement quaternion must be finite and nonzero");
      m_q = q;
      m_R = internal::rotation_matrix(q);
      m_dR = internal::rotation_matrix_derivatives(q);
    }
    Component_shape& mutable_shape() { return *m_shape; }

    std::unique_ptr<Component_shape> m_shape;
    Eigen::Vector3d m_t;
    Eigen::Vector4d m_q;
    Eigen::Matrix3d m_R;
    std::array<Eigen::Matrix3d, 4> m_dR;
  };

  /// A hole: its component and its two blends (ends 0 and 1).
  struct Hole_record
  {
    std::size_t component;         ///< the hole component
    std::array<std::size_t, 2> blends; ///< the blends of ends 0 and 1
  };

  /// \name Creation
  /// @{

  /// A shape made of the single component `root`.
  explicit Blended_shape(std::unique_ptr<Component_shape> root)
  {
    if(!root)
      throw std::invalid_argument("Blended_shape: the root component is null");
    m_components.push_back(Component(std::move(root), Eigen::Vector3d::Zero(), Eigen::Vector4d(1., 0., 0., 0.)));
    update_layout();
  }

  /// A shape made of one superquadric ellipsoid (the usual start, sec. 5.3).
  explicit Blended_shape(const Ellipsoid& root) : Blended_shape(make_component_shape(root, "superquadric_ellipsoid")) {}

  /// A copy.
  Blended_shape(const Blended_shape&) = default;
  /// Assignment.
  Blended_shape& operator=(const Blended_shape&) = default;
  /// @}

  /// \name Structure
  /// @{

  /// The number of components.
  std::size_t number_of_components() const { return m_components.size(); }
  /// Component `c`.
  const Component& component(std::size_t c) const { return m_components.at(c); }
  /// The number of blends.
  std::size_t number_of_blends() const { return m_blends.size(); }
  /// Blend `b`.
  const Blend& blend(std::size_t b) const { return m_blends.at(b); }
  /// The parent of component `c` > 0: the base component of the blend that
  /// added it (of end 0 for a hole), whose frame its placement is relative
  /// to; `no_parent` for the root (and for a component no blend adds).
  std::size_t parent(std::size_t c) const { return m_parent.at(c); }
  /// See parent().
  static constexpr std::size_t no_parent = std::size_t(-1);
  /// The translation of component `c` in the root's frame (its placement
  /// composed with those of its parents).
  const Eigen::Vector3d& root_translation(std::size_t c) const { return m_root_t.at(c); }
  /// The rotation of component `c` relative to the root's frame.
  const Eigen::Matrix3d& root_rotation(std::size_t c) const { return m_root_R.at(c); }
  /// The holes.
  const std::vector<Hole_record>& holes() const { return m_holes; }
  /// The hole component of hole `h`.
  const Hole& hole_component(std::size_t h) const { return *m_components.at(m_holes.at(h).component).shape().template primitive<Hole>(); }
  /// Whether hole `h` is in its Tube domain (a handle: the genus counts it).
  bool hole_is_tube(std::size_t h) const { return hole_component(h).domain() == Hole_domain::Tube; }
  /// The genus of the surface: the number of holes in their Tube domain.
  std::size_t genus() const
  {
    std::size_t g = 0;
    for(std::size_t h = 0; h < m_holes.size(); ++h)
      g += hole_is_tube(h) ? 1 : 0;
    return g;
  }
  /// @}

  /// \name Parameters
  /// @{

  /// The dimension of the parameter vector.
  std::size_t number_of_parameters() const { return m_layout.size(); }
  /// The index of component `c`'s first parameter (its placement, or for the root its shape).
  std::size_t component_offset(std::size_t c) const { return m_layout.component_offset(c); }
  /// The index of component `c`'s first shape parameter.
  std::size_t shape_offset(std::size_t c) const { return m_layout.shape_offset(c); }
  /// The index of blend `b`'s first parameter (`e_u`).
  std::size_t blend_offset(std::size_t b) const { return m_layout.blend_offset(b); }

  /// The parameter vector.
  Eigen::VectorXd parameters() const
  {
    Eigen::VectorXd q = Eigen::VectorXd::Zero(Eigen::Index(number_of_parameters()));
    for(std::size_t c = 0; c < m_components.size(); ++c)
    {
      const Component& k = m_components[c];
      Eigen::Index o = Eigen::Index(component_offset(c));
      if(c != 0)
      {
        q.segment<3>(o) = k.m_t;
        q.segment<4>(o + 3) = k.m_q;
        o += Eigen::Index(number_of_placement_parameters);
      }
      const Eigen::VectorXd s = k.shape().parameters();
      q.segment(o, s.size()) = s;
    }
    for(std::size_t b = 0; b < m_blends.size(); ++b)
      q.segment<7>(Eigen::Index(blend_offset(b))) = m_blends[b].base_region().parameters();
    return q;
  }

  /// Sets all parameters. Fixed parameters must keep their values.
  /// \throws std::invalid_argument on a wrong size, invalid values, a changed fixed
  ///         parameter, or regions that leave their charts or meet (as when
  ///         blends are added); the shape is then unchanged.
  void set_parameters(const Eigen::VectorXd& q)
  {
    const std::size_t size = number_of_parameters();
    if(q.size() != Eigen::Index(size))
      throw std::invalid_argument("Blended_shape::set_parameters: expected " + std::to_string(size) +
                                  " parameters, got " + std::to_string(q.size()));
    const Eigen::VectorXd old = parameters();
    for(std::size_t i = 0; i < size; ++i)
      if(is_fixed_parameter(i) && q[Eigen::Index(i)] != old[Eigen::Index(i)])
        throw std::invalid_argument("Blended_shape::set_parameters: parameter " + parameter_name(i) +
                                    " is fixed (see is_fixed_parameter())");
    Blended_shape copy(*this);
    copy.assign_parameters(q);
    const Eigen::Index blend_parameters = Eigen::Index(size - m_layout.first_blend_parameter());
    if(m_blends.size() > 0 && q.tail(blend_parameters) != old.tail(blend_parameters))
      copy.validate_regions();
    *this = std::move(copy);
  }

  /// The name of parameter `i` ("c1.a1", "c1.tx", "b0.e_u", ...).
  std::string parameter_name(std::size_t i) const
  {
    const internal::Parameter_layout::Address a = m_layout.address(i);
    static const char* placement[] = {"tx", "ty", "tz", "qw", "qx", "qy", "qz"};
    if(a.is_blend)
      return "b" + std::to_string(a.index) + "." + Ellipse_blending_region::parameter_name(int(a.local));
    const std::string prefix = "c" + std::to_string(a.index) + ".";
    if(a.is_placement)
      return prefix + placement[a.local];
    return prefix + m_components[a.index].shape().parameter_info(a.local).name;
  }

  /// The kind of parameter `i`: a placement's translation is a length, its
  /// quaternion and the region parameters (chart units) are dimensionless,
  /// and a component's shape parameters are of their primitive's kinds.
  Parameter_kind parameter_kind(std::size_t i) const
  {
    const internal::Parameter_layout::Address a = m_layout.address(i);
    if(a.is_blend)
      return Parameter_kind::Dimensionless;
    if(a.is_placement)
      return a.local < 3 ? Parameter_kind::Length : Parameter_kind::Dimensionless;
    return m_components[a.index].shape().parameter_info(a.local).kind;
  }

  /// Whether parameter `i` belongs to the rigid placement of a component relative to its parent (sec. 3.5).
  bool is_placement_parameter(std::size_t i) const { return m_layout.address(i).is_placement; }

  /// Whether parameter `i` is one of a blend's seven region parameters `(e_u, e_v, e_1, e_2, e_theta, w, h)`.
  bool is_blending_region_parameter(std::size_t i) const { return m_layout.address(i).is_blend; }

  /// Lower bound of parameter `i`.
  double parameter_lower_bound(std::size_t i) const { return bounds(i).first; }
  /// Upper bound of parameter `i`.
  double parameter_upper_bound(std::size_t i) const { return bounds(i).second; }

  /// Whether parameter `i` is held fixed: `h` of an annulus blend (cut and
  /// glue has `h = 0`, sec. 3.4), `a4`, `a5` of a hole in its Two_disks
  /// domain (the two disks parameterize the hole only while it is closed),
  /// and those held by hold_parameter(). Their Jacobian columns are zero.
  bool is_fixed_parameter(std::size_t i) const
  {
    if(i >= number_of_parameters())
      throw std::out_of_range("Blended_shape: parameter index " + std::to_string(i) + " out of range");
    return m_fixed[i];
  }

  /*!
  Holds parameter `i` (`held` true) or releases it. A held parameter is
  fixed (is_fixed_parameter(): its Jacobian column is zero and
  set_parameters() must keep its value), so a fit leaves it as it is:
  evolution holds the `h` of a gradual blend while it lowers `h` in stages
  (Part_evolution). To move a held parameter, release it, set it, hold it
  again. Parameters the structure fixes (above) stay fixed when released.
  Every change of structure (split(), add_part(), add_hole(),
  remove_component(), ...: the parameters are numbered anew) releases all.
  \throws std::out_of_range if `i` is not a parameter index.
  */
  void hold_parameter(std::size_t i, bool held = true)
  {
    if(i >= number_of_parameters())
      throw std::out_of_range("Blended_shape::hold_parameter: parameter index " + std::to_string(i) +
                              " out of range (" + std::to_string(number_of_parameters()) + " parameters)");
    m_fixed[i] = held || compute_fixed(i);
  }

  /*!
  Holds (`held` true) or releases the curve of blend `b`'s region: its
  `e_u, e_v, e_1, e_2, e_theta` (eq. 29), with hold_parameter(); `w` and
  `h` are left as they are. These are the most nonlinear parameters of a
  blended shape: the points of the strip follow the curve through the
  blending function, so that a move of a fraction of the strip width
  changes the surface far more than its derivatives predict. Evolution
  holds them while it lowers a gradual blend's `h` in stages, and in the
  final fit on all points of a model it evolved on a sample.
  \throws std::out_of_range if `b` is not a blend index.
  */
  void hold_blending_region(std::size_t b, bool held = true)
  {
    if(b >= m_blends.size())
      throw std::out_of_range("Blended_shape::hold_blending_region: blend index " + std::to_string(b) +
                              " out of range (" + std::to_string(m_blends.size()) + " blends)");
    for(std::size_t j = Ellipse_blending_region::E_U; j <= Ellipse_blending_region::E_THETA; ++j)
      hold_parameter(blend_offset(b) + j, held);
  }

  /*!
  Holds (`held` true) or releases every parameter of component `c`: its
  placement (for a component other than the root) and its shape, with
  hold_parameter(). Evolution holds a gradual part so while it lowers the
  part's `h` in stages (Part_evolution).
  \throws std::out_of_range if `c` is not a component index.
  */
  void hold_component(std::size_t c, bool held = true)
  {
    if(c >= m_components.size())
      throw std::out_of_range("Blended_shape::hold_component: component index " + std::to_string(c) +
                              " out of range (" + std::to_string(m_components.size()) + " components)");
    const std::size_t end = shape_offset(c) + m_components[c].shape().number_of_parameters();
    for(std::size_t i = component_offset(c); i < end; ++i)
      hold_parameter(i, held);
  }

private:
  bool compute_fixed(std::size_t i) const
  {
    const internal::Parameter_layout::Address a = m_layout.address(i);
    if(a.is_blend)
      return a.local == Ellipse_blending_region::H && !m_blends[a.index].is_gradual();
    if(a.is_placement)
      return false;
    if(const Hole* h = m_components[a.index].shape().template primitive<Hole>())
      return h->domain() == Hole_domain::Two_disks && (a.local == Hole::A4 || a.local == Hole::A5);
    return false;
  }

public:
  /// @}

  /// \name Domain
  /// @{

  /// The component's own point `t + R s(u)`, whether or not `p` is on the surface.
  Point_3 component_point(const Shape_point& p) const { return to_point(place(p.component, p.u, nullptr, 1., nullptr)); }

  /*!
  The canonical representative of `p` in the quotient domain, or nothing
  if `p` is in a discarded part of the domain (not on the surface):
  1. the primitive's own seams (`canonical_chart_point()`);
  2. a point in the strip or disk of a base region is expressed in the
     region's chart;
  3. a point in the strip of an added side goes to its base point
     `C_1(-d, theta)`, and a point of the retained part of a gradual blend's
     added component to the base disk point with the same disk coordinates.
  */
  std::optional<Shape_point> canonical_point(const Shape_point& p) const
  {
    const std::optional<Canonical_location> c = locate_canonical(p);
    if(!c)
      return std::nullopt;
    return c->point;
  }

  /// Whether `p` is a point of the surface (not discarded).
  bool is_on_surface(const Shape_point& p) const { return bool(canonical_point(p)); }

  /// The other chart points that are the same point of the quotient as the
  /// canonical point `p` (canonical_point()): its image `beta(p)` on the added
  /// component of each blend whose base strip or disk holds it. (Across a
  /// strip, a path on the surface leaves the base's chart at the strip's
  /// discarded edge and goes on in the added component's chart: these are
  /// the coordinates to go on in.)
  std::vector<Shape_point> other_representatives(const Shape_point& p) const
  {
    std::vector<Shape_point> others;
    for(const Blend& B : m_blends)
    {
      if(B.base_component() != p.component || B.base_region().chart() != p.u.chart)
        continue;
      const Ellipse_blending_region& R = B.base_region();
      const Eigen::Vector2d v(p.u.x, p.u.y);
      const Region_location loc = R.locate(v);
      const bool tube = is_tube(B.added_component());
      if(loc.side == Region_side::Strip)
        others.push_back(Shape_point(B.added_component(),
                                     B.added_side().strip_point(-loc.coordinates.d, loc.coordinates.theta, tube)));
      else if(loc.side == Region_side::Discarded && B.is_gradual())
        if(const std::optional<Core_coordinates> c = R.core_coordinates(v, -1., B.core_stretch()))
          others.push_back(Shape_point(B.added_component(), B.added_side().core_point(c->t, c->theta, B.core_stretch())));
    }
    return others;
  }
  /// @}

  /// \name Evaluation
  /// @{

  /// `s(p)` at the canonical representative of `p`. A point of a discarded
  /// part of the domain gives the surface's continuation there: on the base
  /// of a cut-and-glue blend within two strip widths past the strip's
  /// discarded edge, the added component at `beta` extended (eq. 16 with
  /// `d < -1`: `C_2(-d, theta)`), where `alpha` is 0; elsewhere
  /// component_point(p). So a point held fixed while the regions move (a
  /// fitter's correspondence) moves continuously, and the faces of the
  /// per-component meshes that straddle a cut lie along the surface.
  Point_3 point(const Shape_point& p) const
  {
    const std::optional<Canonical_location> c = locate_canonical(p);
    if(c)
      return to_point(evaluate(*c, nullptr));
    if(const std::optional<Eigen::Vector3d> x = continuation(p))
      return to_point(*x);
    return component_point(p);
  }

  /// `s(p)` and its sparse Jacobian (eq. 10, 11) at the canonical
  /// representative of `p`. \throws std::invalid_argument if `p` is not on the surface.
  Point_3 point_and_jacobian(const Shape_point& p, Sparse_jacobian& J) const
  {
    const std::optional<Canonical_location> c = locate_canonical(p);
    if(!c)
      throw std::invalid_argument("Blended_shape::point_and_jacobian: the point is in a discarded part of the domain");
    J.clear();
    const Point_3 x = to_point(evaluate(*c, &J));
    // Fixed parameters do not move (their columns are zero), so no solver moves them.
    for(Jacobian_block& b : J)
      for(Eigen::Index k = 0; k < b.columns.cols(); ++k)
        if(m_fixed[b.first_column + std::size_t(k)])
          b.columns.col(k).setZero();
    return x;
  }

  /// The dense Jacobian (3 x number_of_parameters()) at `p`.
  Eigen::MatrixXd dense_jacobian(const Shape_point& p) const
  {
    Sparse_jacobian J;
    point_and_jacobian(p, J);
    Eigen::MatrixXd D = Eigen::MatrixXd::Zero(3, Eigen::Index(number_of_parameters()));
    for(const Jacobian_block& b : J)
      D.block(0, Eigen::Index(b.first_column), 3, b.columns.cols()) += b.columns;
    return D;
  }

  /// `s(p)` and its chart Jacobian `D` (3 x 2: its derivatives with respect
  /// to the two chart coordinates) at the canonical representative of `p`,
  /// which is returned in `canonical` if given (`D` is with respect to its
  /// chart coordinates): `alpha ds_1/du + (1 - alpha) ds_2/du_2 dbeta/du +
  /// (s_1 - s_2) dalpha/du` in a strip or disk, analytic everywhere.
  /// \throws std::invalid_argument if `p` is not on the surface.
  Point_3 point_and_chart_jacobian(const Shape_point& p, Eigen::Matrix<double, 3, 2>& D,
                                   Shape_point* canonical = nullptr) const
  {
    Shape_point c;
    const std::optional<Point_3> x = canonical_point_and_chart_jacobian(p, c, D);
    if(!x)
      throw std::invalid_argument("Blended_shape::point_and_chart_jacobian: the point is in a discarded part of the domain");
    if(canonical)
      *canonical = c;
    return *x;
  }

  /// canonical_point() in `canonical` and point_and_chart_jacobian() there,
  /// locating the point in the blends once (the closest-point search's step);
  /// nothing if `p` is not on the surface.
  std::optional<Point_3> canonical_point_and_chart_jacobian(const Shape_point& p, Shape_point& canonical,
                                                            Eigen::Matrix<double, 3, 2>& D) const
  {
    const std::optional<Canonical_location> c = locate_canonical(p);
    if(!c)
      return std::nullopt;
    canonical = c->point;
    return to_point(evaluate(*c, nullptr, &D));
  }

  /// The unit normal at `p`, from the chart Jacobian at its canonical
  /// representative (outward for outward-oriented charts); the component's
  /// own normal at points not on the surface; 0 where the chart Jacobian
  /// loses rank.
  Vector_3 normal(const Shape_point& p) const
  {
    const std::optional<Canonical_location> c = locate_canonical(p);
    Eigen::Matrix<double, 3, 2> D;
    if(c)
      evaluate(*c, nullptr, &D);
    else
      place(p.component, p.u, nullptr, 1., &D);
    return normal_of_chart_jacobian(D);
  }

  /// The unit normal of a chart Jacobian `D` (as normal() takes it from the
  /// chart Jacobian at the canonical point): `D_x x D_y` normalized, 0 where
  /// `D` loses rank.
  static Vector_3 normal_of_chart_jacobian(const Eigen::Matrix<double, 3, 2>& D)
  {
    const Eigen::Vector3d n = D.col(0).cross(D.col(1));
    const double len = n.norm();
    if(!(len > 0.) || !std::isfinite(len))
      return Vector_3(0., 0., 0.);
    return Vector_3(n.x() / len, n.y() / len, n.z() / len);
  }
  /// @}

  /// \name Evolution (sec. 4)
  /// @{

  /*!
  Splits component `c` along the ellipse `region` (parameters of eq. 29,
  `h` must be 0) of chart `chart` (sec. 4.1): the new component is a copy
  of `c` placed where `c` is (the identity relative to `c`, its parent), which keeps the inside of the curve,
  while `c` keeps the outside. Right after the split the surface is the same
  (up to rounding: `alpha x + (1 - alpha) x`). Returns the new blend.
  \throws std::invalid_argument if the region is invalid, leaves the chart,
          or meets another blend's region on `c`; the shape is then unchanged.
  */
  std::size_t split(std::size_t c, std::size_t chart, const Ellipse_blending_region::Parameter_vector& region,
                    double half_width)
  {
    check_component(c, "split");
    check_ungraded(c, "split");
    Ellipse_blending_region base(region, half_width, 8, Blending_region_kind::Annulus, Retained_side::Outside);
    base.set_chart(chart);
    Ellipse_blending_region added(region, half_width, 8, Blending_region_kind::Annulus, Retained_side::Inside);
    added.set_chart(chart);
    Blended_shape copy(*this);
    const Component& k = m_components[c];
    // the copy sits where c is: the identity relative to its parent c
    copy.m_components.push_back(Component(k.shape().clone(), Eigen::Vector3d::Zero(), Eigen::Vector4d(1., 0., 0., 0.)));
    copy.m_blends.push_back(
      Blend(Blend_kind::Split, c, base, copy.m_components.size() - 1, Added_side::ellipse(added)));
    copy.validate_new_blend(copy.m_blends.size() - 1);
    copy.update_layout();
    *this = std::move(copy);
    return m_blends.size() - 1;
  }

  /*!
  Adds the primitive `part` (any model of `BlendedShapePrimitive`, stored
  under `type_name`) with the placement `(translation, quaternion)` relative
  to the frame of component `base`, its parent (sec. 3.5), blended
  gradually into component `base` (sec. 4.1): a disk region `base_region`
  (eq. 29, its `h` is set to 1: the part starts unexpressed) in chart
  `base_chart` of `base`, corresponding to the inside of the ellipse
  `part_region` of chart `part_chart` of the part. Lower `h` to express
  the part; at `h = 0` finish_gradual_blend() makes the cut final.
  Returns the new blend.
  \throws std::invalid_argument on invalid regions or placement; the shape is then unchanged.
  */
  template <class Primitive>
  std::size_t add_part(std::size_t base, std::size_t base_chart, Ellipse_blending_region::Parameter_vector base_region,
                       double base_half_width, const Primitive& part, const std::string& type_name,
                       const Eigen::Vector3d& translation, const Eigen::Vector4d& quaternion, std::size_t part_chart,
                       const Ellipse_blending_region::Parameter_vector& part_region, double part_half_width)
  {
    check_component(base, "add_part");
    check_ungraded(base, "add_part");
    base_region[Ellipse_blending_region::H] = 1.;
    Ellipse_blending_region b(base_region, base_half_width, 8, Blending_region_kind::Disk, Retained_side::Outside);
    b.set_chart(base_chart);
    Ellipse_blending_region::Parameter_vector pr = part_region;
    pr[Ellipse_blending_region::H] = 0.;
    Ellipse_blending_region a(pr, part_half_width, 8, Blending_region_kind::Annulus, Retained_side::Inside);
    a.set_chart(part_chart);
    Blended_shape copy(*this);
    copy.m_components.push_back(Component(make_component_shape(part, type_name), translation, quaternion));
    copy.m_blends.push_back(Blend(Blend_kind::Part, base, b, copy.m_components.size() - 1, Added_side::ellipse(a)));
    copy.validate_new_blend(copy.m_blends.size() - 1);
    copy.update_layout();
    *this = std::move(copy);
    return m_blends.size() - 1;
  }

  /*!
  Adds a closed hole (sec. 4.2) between two places of the surface: disk
  regions (circles of radius `radius`, strip half-width `half_width`, chart
  units) centred at chart points `first.u` and `second.u` of components
  `first.component` and `second.component`, glued to ends 0 and 1 of a new
  hole component in its Two_disks domain (`a4 = a5 = 1`, the pinched
  sphere), with `h = 1` (not yet expressed). The hole component is placed
  so that its end circles run through the two region curves on the surface:
  axis from the first place's curve centre to the second's, `a3` half their
  distance, `a1 = a2` the mean radius of the curves, and the angle offsets
  of the ends matched to the curves. `end_half_width` is the strip
  half-width on the hole side (radial units of its disks). Returns the new hole.
  \throws std::invalid_argument if a place is not on the surface, a region
          is invalid or meets another region, or the two places coincide.
  */
  std::size_t add_hole(const Shape_point& first, const Shape_point& second, double radius, double half_width,
                       double end_half_width = 0.1)
  {
    const Shape_point places[2] = {first, second};
    std::array<Ellipse_blending_region, 2> regions = {make_disk_region(places[0], radius, half_width, "first"),
                                                      make_disk_region(places[1], radius, half_width, "second")};
    // The region curves on the surface, and the hole through them.
    const internal::Hole_placement h = internal::place_hole({region_curve(places[0], regions[0]),
                                                             region_curve(places[1], regions[1])});
    Hole hole(h.mean_radius, h.mean_radius, h.half_length, 1., 1., 1., 1., Hole_domain::Two_disks);
    // (centre, rotation) in the root's frame, placed relative to the parent: the first place's component
    const std::size_t p = places[0].component;
    const Eigen::Vector3d t_local = m_root_R[p].transpose() * (h.centre - m_root_t[p]);
    const Eigen::Matrix3d R_local = m_root_R[p].transpose() * h.rotation;

    Blended_shape copy(*this);
    copy.m_components.push_back(
      Component(make_component_shape(hole, "hole_component"), t_local, internal::quaternion_from_matrix(R_local)));
    const std::size_t hc = copy.m_components.size() - 1, hole_index = copy.m_holes.size();
    Hole_record rec;
    rec.component = hc;
    for(int e = 0; e < 2; ++e)
    {
      copy.m_blends.push_back(Blend(Blend_kind::Hole, places[e].component, regions[std::size_t(e)], hc,
                                    Added_side::hole_end(e, end_half_width, h.phase[std::size_t(e)]), hole_index));
      rec.blends[std::size_t(e)] = copy.m_blends.size() - 1;
      copy.validate_new_blend(copy.m_blends.size() - 1);
    }
    copy.m_holes.push_back(rec);
    copy.update_layout();
    *this = std::move(copy);
    return m_holes.size() - 1;
  }

  /// Makes the gradual blend `b` a cut-and-glue one (sec. 4.1, end): its
  /// disk region becomes an annulus and the added component's retained part
  /// its own surface. Geometry unchanged.
  /// \throws std::logic_error unless `h = 0` and `b` is gradual and not a hole end
  ///         (holes switch both ends at once: switch_hole_to_tube()).
  void finish_gradual_blend(std::size_t b)
  {
    if(b >= m_blends.size())
      throw std::out_of_range("Blended_shape::finish_gradual_blend: no blend " + std::to_string(b) + " (the shape has " +
                              std::to_string(m_blends.size()) + ")");
    const Blend& B = m_blends[b];
    if(B.hole() != Blend::no_hole)
      throw std::logic_error("Blended_shape::finish_gradual_blend: blend " + std::to_string(b) +
                             " is a hole end; use switch_hole_to_tube()");
    make_annulus(b);
    update_layout();
  }

  /// The topological surgery of sec. 4.2: hole `h`, fully expressed
  /// (`h = 0` on both ends), switches to its Tube domain, and both its blends
  /// become annuli. No point of the surface moves. Then `a4`, `a5` are free
  /// and the hole can open.
  /// \throws std::logic_error unless both ends have `h = 0`
  void switch_hole_to_tube(std::size_t h)
  {
    if(h >= m_holes.size())
      throw std::out_of_range("Blended_shape::switch_hole_to_tube: no hole " + std::to_string(h) + " (the shape has " +
                              std::to_string(m_holes.size()) + ")");
    const Hole_record& rec = m_holes[h];
    for(std::size_t e = 0; e < 2; ++e)
      if(m_blends[rec.blends[e]].base_region().parameters()[Ellipse_blending_region::H] != 0.)
        throw std::logic_error("Blended_shape::switch_hole_to_tube: hole " + std::to_string(h) +
                               " is not fully expressed (h must be 0 on both ends)");
    Blended_shape copy(*this);
    for(std::size_t e = 0; e < 2; ++e)
      copy.make_annulus(rec.blends[e]);
    copy.m_components[rec.component].mutable_shape().template primitive<Hole>()->set_domain(Hole_domain::Tube);
    copy.update_layout();
    *this = std::move(copy);
  }

  /// Removes component `c`, whose contribution has vanished: it is added by
  /// gradual blends whose `h` is 1 (a part, or both ends of a hole), and no
  /// blend is based on it. Its blends go too; later indices shift down.
  /// \throws std::logic_error otherwise
  void remove_component(std::size_t c)
  {
    const std::vector<std::size_t> gone = blends_adding_leaf(c, "remove_component");
    for(std::size_t b : gone)
      if(!m_blends[b].is_gradual() || m_blends[b].base_region().parameters()[Ellipse_blending_region::H] != 1.)
        throw std::logic_error("Blended_shape::remove_component: component " + std::to_string(c) +
                               " still contributes (its blend " + std::to_string(b) + " has h < 1 or is final)");
    erase_component(c, gone);
  }

  /// Undoes the split that added component `c` (split()): `c` and its blend
  /// go, and its base covers the blending region with its own surface again.
  /// Unlike remove_component(), this moves the points of the region (from the
  /// blend of the two components to the base's surface): for a part that no
  /// longer pays for itself (Part_evolution). No blend may be based on `c`.
  /// Later indices shift down.
  /// \throws std::logic_error if `c` is not added by a split, or a blend is based on it
  void merge_split(std::size_t c)
  {
    const std::vector<std::size_t> gone = blends_adding_leaf(c, "merge_split");
    if(gone.size() != 1 || m_blends[gone.front()].kind() != Blend_kind::Split)
      throw std::logic_error("Blended_shape::merge_split: component " + std::to_string(c) + " is not added by a split");
    erase_component(c, gone);
  }

private:
  // The blends that add component c > 0, which no blend may be based on.
  std::vector<std::size_t> blends_adding_leaf(std::size_t c, const char* who) const
  {
    check_component(c, who);
    if(c == 0)
      throw std::logic_error(std::string("Blended_shape::") + who + ": the root cannot be removed");
    std::vector<std::size_t> gone;
    for(std::size_t b = 0; b < m_blends.size(); ++b)
    {
      if(m_blends[b].base_component() == c)
        throw std::logic_error(std::string("Blended_shape::") + who + ": blend " + std::to_string(b) +
                               " is based on component " + std::to_string(c));
      if(m_blends[b].added_component() == c)
        gone.push_back(b);
    }
    return gone;
  }

  // Erases component c and its blends `gone` (increasing), renumbering the rest.
  void erase_component(std::size_t c, const std::vector<std::size_t>& gone)
  {
    Blended_shape copy(*this);
    for(std::size_t k = gone.size(); k-- > 0;)
      copy.m_blends.erase(copy.m_blends.begin() + std::ptrdiff_t(gone[k]));
    copy.m_components.erase(copy.m_components.begin() + std::ptrdiff_t(c));
    std::vector<Hole_record> holes;
    for(const Hole_record& r : copy.m_holes)
      if(r.component != c)
        holes.push_back(r);
    copy.m_holes = holes;
    // Renumber components, holes and blend references.
    for(Blend& B : copy.m_blends)
    {
      if(B.base_component() > c)
        B.set_base_component(B.base_component() - 1);
      if(B.added_component() > c)
        B.set_added_component(B.added_component() - 1);
    }
    for(std::size_t hi = 0; hi < copy.m_holes.size(); ++hi)
    {
      Hole_record& r = copy.m_holes[hi];
      if(r.component > c)
        --r.component;
      for(std::size_t e = 0; e < 2; ++e)
      {
        std::size_t shift = 0;
        for(std::size_t g : gone)
          shift += (g < r.blends[e]) ? 1 : 0;
        r.blends[e] -= shift;
        copy.m_blends[r.blends[e]].set_hole(hi);
      }
    }
    copy.update_layout();
    *this = std::move(copy);
  }

public:
  /// @}

  /// \cond INTERNAL
  // Low-level construction for model files: appends without placing anything.
  std::size_t append_component(std::unique_ptr<Component_shape> s, const Eigen::Vector3d& t, const Eigen::Vector4d& q)
  {
    m_components.push_back(Component(std::move(s), t, q));
    update_layout();
    return m_components.size() - 1;
  }
  // check_regions = false: the caller checks the regions later (check_blend_regions()).
  std::size_t append_blend(const Blend& b, bool check_regions = true)
  {
    if(b.base_component() >= m_components.size() || b.added_component() >= m_components.size() ||
       b.added_component() == 0 || b.base_component() == b.added_component())
      throw std::invalid_argument("Blended_shape: a blend refers to a missing component");
    // Placements are relative to parents, which must come first.
    if(b.base_component() > b.added_component())
      throw std::invalid_argument("Blended_shape: blend of base component " + std::to_string(b.base_component()) +
                                  " adds component " + std::to_string(b.added_component()) +
                                  "; a base must precede the components it adds");
    m_blends.push_back(b);
    try
    {
      if(check_regions)
        validate_new_blend(m_blends.size() - 1);
    }
    catch(...)
    {
      m_blends.pop_back();
      throw;
    }
    update_layout();
    return m_blends.size() - 1;
  }
  // The regions of blend b against those of the blends before it (see validate_blend()).
  void check_blend_regions(std::size_t b) const { internal::validate_blend(*this, b, b); }
  void append_hole(const Hole_record& r)
  {
    if(r.component >= m_components.size() || !m_components[r.component].shape().template primitive<Hole>() ||
       r.blends[0] >= m_blends.size() || r.blends[1] >= m_blends.size())
      throw std::invalid_argument("Blended_shape: a hole refers to a missing component or blend");
    m_holes.push_back(r);
  }
  /// \endcond

private:
  std::pair<double, double> bounds(std::size_t i) const
  {
    const internal::Parameter_layout::Address a = m_layout.address(i);
    if(a.is_blend)
      return {Ellipse_blending_region::parameter_lower_bound(int(a.local)),
              Ellipse_blending_region::parameter_upper_bound(int(a.local))};
    if(a.is_placement)
      return {-HUGE_VAL, HUGE_VAL};
    const Parameter_info& info = m_components[a.index].shape().parameter_info(a.local);
    return {info.lower_bound, info.upper_bound};
  }

  void assign_parameters(const Eigen::VectorXd& q)
  {
    for(std::size_t c = 0; c < m_components.size(); ++c)
    {
      Component& k = m_components[c];
      Eigen::Index o = Eigen::Index(component_offset(c));
      if(c != 0)
      {
        if(!q.segment<3>(o).allFinite())
          throw std::invalid_argument("Blended_shape::set_parameters: the translation of component " +
                                      std::to_string(c) + " is not finite");
        k.m_t = q.segment<3>(o);
        k.set_placement_quaternion(q.segment<4>(o + 3));
        o += Eigen::Index(number_of_placement_parameters);
      }
      k.mutable_shape().set_parameters(q.segment(o, Eigen::Index(k.shape().number_of_parameters())));
    }
    for(std::size_t b = 0; b < m_blends.size(); ++b)
      m_blends[b].base_region().set_parameters(q.segment<7>(Eigen::Index(blend_offset(b))));
    update_root_placements();
  }

  void update_layout()
  {
    std::vector<std::size_t> shape_sizes(m_components.size());
    for(std::size_t c = 0; c < m_components.size(); ++c)
      shape_sizes[c] = m_components[c].shape().number_of_parameters();
    m_layout.reset(shape_sizes, m_blends.size(), number_of_blend_parameters);
    m_fixed.assign(number_of_parameters(), false);
    for(std::size_t i = 0; i < number_of_parameters(); ++i)
      m_fixed[i] = compute_fixed(i);
    m_parent.assign(m_components.size(), no_parent);
    for(const Blend& B : m_blends)
      if(m_parent[B.added_component()] == no_parent)
        m_parent[B.added_component()] = B.base_component();
    update_root_placements();
  }

  // T + Q of every component, in order: parents come first (a blend's base
  // precedes its added component, see append_blend()).
  void update_root_placements()
  {
    m_root_t.resize(m_components.size());
    m_root_R.resize(m_components.size());
    m_root_t[0].setZero();
    m_root_R[0].setIdentity();
    for(std::size_t c = 1; c < m_components.size(); ++c)
    {
      const Component& k = m_components[c];
      const std::size_t p = (m_parent[c] == no_parent) ? 0 : m_parent[c];
      m_root_t[c] = m_root_t[p] + m_root_R[p] * k.m_t;
      m_root_R[c] = m_root_R[p] * k.m_R;
    }
  }

  bool is_tube(std::size_t c) const { return internal::is_tube_component(*this, c); }

  void check_component(std::size_t c, const char* what) const
  {
    if(c >= m_components.size())
      throw std::invalid_argument(std::string("Blended_shape::") + what + ": no component " + std::to_string(c) +
                                  " (the shape has " + std::to_string(m_components.size()) + ")");
  }

  // A region on a component added by a still-gradual blend would live on a
  // domain that is not yet part of the surface.
  void check_ungraded(std::size_t c, const char* what) const
  {
    for(const Blend& B : m_blends)
      if(B.added_component() == c && B.is_gradual())
        throw std::invalid_argument(std::string("Blended_shape::") + what + ": component " + std::to_string(c) +
                                    " is still being blended in gradually; finish its blend first");
  }

  // The point `u1` of blend `B`'s base chart, if it is in that chart's domain.
  // The region's check (validate_regions()) samples its strip: between the
  // samples, the strip's outer edge may cross the chart's rim by a hair, and
  // what lies beyond it is on no surface.
  std::optional<Shape_point> base_point(const Blend& B, const Eigen::Vector2d& u1) const
  {
    const std::size_t chart = B.base_region().chart();
    if(!m_components[B.base_component()].shape().chart_domain(chart).contains(u1.x(), u1.y()))
      return std::nullopt;
    return Shape_point(B.base_component(), Chart_point(chart, u1.x(), u1.y()));
  }

  void check_point(const Shape_point& p) const
  {
    check_component(p.component, "canonical_point");
    const Component_shape& s = m_components[p.component].shape();
    if(p.u.chart >= s.number_of_charts() || !std::isfinite(p.u.x) || !std::isfinite(p.u.y))
      throw std::invalid_argument("Blended_shape: chart point (" + std::to_string(p.u.chart) + ", " +
                                  std::to_string(p.u.x) + ", " + std::to_string(p.u.y) + ") is not a point of component " +
                                  std::to_string(p.component));
    if(!s.chart_domain(p.u.chart).contains(p.u.x, p.u.y))
      throw std::invalid_argument("Blended_shape: chart point (" + std::to_string(p.u.chart) + ", " +
                                  std::to_string(p.u.x) + ", " + std::to_string(p.u.y) +
                                  ") is outside the domain of that chart of component " + std::to_string(p.component) +
                                  " (see Component_shape::chart_domain())");
  }

  // The curve of `region` (d = 0) on the surface of the place's component, sampled at 64 uniform theta.
  std::vector<Eigen::Vector3d> region_curve(const Shape_point& place, const Ellipse_blending_region& region) const
  {
    const int samples = 64;
    std::vector<Eigen::Vector3d> pts;
    for(int k = 0; k < samples; ++k)
    {
      const Eigen::Vector2d v = region.strip_point(0., 2. * M_PI * k / samples);
      const Shape_point sp(place.component, Chart_point(region.chart(), v.x(), v.y()));
      pts.push_back(internal::to_eigen(point(sp)));
    }
    return pts;
  }

  Ellipse_blending_region make_disk_region(const Shape_point& place, double radius, double half_width,
                                           const char* which) const
  {
    check_component(place.component, "add_hole");
    check_ungraded(place.component, "add_hole");
    const std::optional<Shape_point> c = canonical_point(place);
    if(!c || c->component != place.component)
      throw std::invalid_argument(std::string("Blended_shape::add_hole: the ") + which +
                                  " place is not on the surface of its component");
    Ellipse_blending_region r(Ellipse_blending_region::make_parameters(c->u.x, c->u.y, radius, radius, 0., 1., 1.),
                              half_width, 8, Blending_region_kind::Disk, Retained_side::Outside);
    r.set_chart(c->u.chart);
    return r;
  }

  void make_annulus(std::size_t b)
  {
    Blend& B = m_blends.at(b);
    if(!B.is_gradual())
      throw std::logic_error("Blended_shape: blend " + std::to_string(b) + " is already final");
    Ellipse_blending_region::Parameter_vector q = B.base_region().parameters();
    if(q[Ellipse_blending_region::H] != 0.)
      throw std::logic_error("Blended_shape: blend " + std::to_string(b) + " has h = " +
                             std::to_string(q[Ellipse_blending_region::H]) + "; finish it only at h = 0");
    const Ellipse_blending_region& old = B.base_region();
    Ellipse_blending_region r(q, old.half_width(), old.number_of_segments(), Blending_region_kind::Annulus,
                              Retained_side::Outside);
    r.set_chart(old.chart());
    B.base_region() = r;
  }

  // See point(): the added component at beta extended, for a discarded
  // base point within two strip widths past the discarded edge of a
  // cut-and-glue blend's strip.
  std::optional<Eigen::Vector3d> continuation(const Shape_point& p) const
  {
    const Component_shape& s = m_components[p.component].shape();
    for(const Blend& B : m_blends)
    {
      if(B.base_component() != p.component || B.is_gradual())
        continue;
      Chart_point v;
      if(!s.to_chart(s.canonical_chart_point(p.u), B.base_region().chart(), v))
        continue;
      const std::optional<Strip_coordinates> c = B.base_region().extended_strip_coordinates(Eigen::Vector2d(v.x, v.y), 3.);
      if(!c || !(c->d < -1.))
        continue;
      const bool tube = is_tube(B.added_component());
      const Chart_point u2 = B.added_side().strip_point(-c->d, c->theta, tube);
      const Component_shape& a = m_components[B.added_component()].shape();
      if(u2.chart >= a.number_of_charts() || !a.chart_domain(u2.chart).contains(u2.x, u2.y))
        continue;
      return place(B.added_component(), u2, nullptr, 1., nullptr);
    }
    return std::nullopt;
  }

  // The regions of every blend: inside their charts and disjoint (see internal::validate_blend()).
  void validate_regions() const
  {
    for(std::size_t b = 0; b < m_blends.size(); ++b)
      internal::validate_blend(*this, b, b);
  }

  void validate_new_blend(std::size_t b) const { internal::validate_blend(*this, b, m_blends.size()); }

  static Point_3 to_point(const Eigen::Vector3d& x) { return Point_3(x.x(), x.y(), x.z()); }

  // T + Q s(u) of component c in the root's frame; with J, appends factor *
  // (its Jacobian: its shape, its placement and those of its ancestors) and,
  // with D, Q ds/du.
  Eigen::Vector3d place(std::size_t c, const Chart_point& u, Sparse_jacobian* J, double factor,
                        Eigen::Matrix<double, 3, 2>* D) const
  {
    const Component& k = m_components[c];
    Eigen::Vector3d s;
    if(J)
    {
      Component_shape::Jacobian Js;
      s = k.shape().point_and_jacobian(u, Js);
      Jacobian_block shape_block;
      shape_block.first_column = shape_offset(c);
      shape_block.columns = factor * (m_root_R[c] * Js);
      J->push_back(std::move(shape_block));
      // Up the parents: with z the point in the frame of component a, a's
      // placement moves it by Q_parent(a) (dt + dR z).
      Eigen::Vector3d z = s;
      for(std::size_t a = c; a != 0 && a != no_parent; a = m_parent[a])
      {
        const Component& ka = m_components[a];
        const std::size_t pa = (m_parent[a] == no_parent) ? 0 : m_parent[a];
        const Eigen::Matrix3d& Qp = m_root_R[pa];
        Jacobian_block blk;
        blk.first_column = component_offset(a);
        blk.columns.resize(3, Eigen::Index(number_of_placement_parameters));
        blk.columns.template leftCols<3>() = factor * Qp;
        for(int m = 0; m < 4; ++m)
          blk.columns.col(3 + m) = factor * (Qp * (ka.m_dR[std::size_t(m)] * z));
        J->push_back(std::move(blk));
        z = ka.m_t + ka.m_R * z;
      }
    }
    if(D)
    {
      Component_shape::Chart_jacobian Ds;
      s = k.shape().point_and_chart_jacobian(u, Ds);
      *D = m_root_R[c] * Ds;
    }
    else if(!J)
      s = k.shape().point(u);
    return m_root_t[c] + m_root_R[c] * s;
  }

  // A canonical point (canonical_point()) with what locating it learned: when
  // `located`, the blend of its component whose base region holds it, with
  // the point's location there, or no_blend if none does (it is on the
  // retained side of all), so evaluate() need not locate it again.
  struct Canonical_location
  {
    static constexpr std::size_t no_blend = std::size_t(-1);
    Shape_point point;
    bool located = false;
    std::size_t blend = no_blend;
    Region_location location = Region_location();
  };

  // canonical_point() (see there), with the location it found.
  std::optional<Canonical_location> locate_canonical(const Shape_point& p) const
  {
    check_point(p);
    // a point on another component (through beta): evaluate() locates it there
    const auto unlocated = [](const std::optional<Shape_point>& c) -> std::optional<Canonical_location> {
      if(!c)
        return std::nullopt;
      return Canonical_location{*c};
    };
    const Component& k = m_components[p.component];
    Shape_point q(p.component, k.shape().canonical_chart_point(p.u));
    for(std::size_t b = 0; b < m_blends.size(); ++b)
    {
      const Blend& B = m_blends[b];
      if(B.base_component() != q.component)
        continue;
      Chart_point v;
      if(!k.shape().to_chart(q.u, B.base_region().chart(), v))
        continue;
      const Region_location loc = B.base_region().locate(Eigen::Vector2d(v.x, v.y));
      if(loc.side == Region_side::Retained)
        continue;
      if(loc.side == Region_side::Discarded && !B.is_gradual())
        return std::nullopt;
      return Canonical_location{Shape_point(q.component, v), true, b, loc};
    }
    for(std::size_t b = 0; b < m_blends.size(); ++b)
    {
      const Blend& B = m_blends[b];
      if(B.added_component() != q.component)
        continue;
      const bool tube = is_tube(q.component);
      const Added_side& A = B.added_side();
      Chart_point v;
      if(!k.shape().to_chart(q.u, A.chart(tube), v))
      {
        // Not in the region's chart: outside an ellipse region, whose inside
        // is all the added component keeps; a hole end's other disk is not its business.
        if(A.kind() == Added_side::Ellipse)
          return std::nullopt;
        continue;
      }
      const Added_side::Location loc = A.locate(v, tube, B.core_stretch());
      const Ellipse_blending_region& R = B.base_region();
      if(loc.side == Region_side::Strip)
        return unlocated(base_point(B, R.strip_point(-loc.d, loc.theta)));
      if(loc.side == Region_side::Discarded)
        return std::nullopt;
      if(B.is_gradual())
      {
        if(!loc.has_core)
          return std::nullopt; // outside the disk of a gradual blend: not on the surface
        return unlocated(base_point(B, R.core_point(loc.t, loc.theta, -1., B.core_stretch())));
      }
    }
    return Canonical_location{q, true};
  }

  // s at a canonical point (eq. 3), with the sparse Jacobian (eq. 10, 11) if
  // J, and with D its chart Jacobian (3 x 2, with respect to p's chart coordinates):
  //   ds/du = alpha ds1/du + (1 - alpha) ds2/du2 dbeta/du + (s1 - s2) dalpha/du.
  // A point located by locate_canonical() is not located again (eq. 3 needs
  // the one blend whose base region holds it, and the point's location there).
  Eigen::Vector3d evaluate(const Canonical_location& c, Sparse_jacobian* J, Eigen::Matrix<double, 3, 2>* D = nullptr) const
  {
    const Shape_point& p = c.point;
    if(c.located)
    {
      if(c.blend != Canonical_location::no_blend)
        if(const std::optional<Eigen::Vector3d> x =
             evaluate_in_blend(p, c.blend, m_blends[c.blend].base_region().alpha_and_gradient(c.location), J, D))
          return *x;
      return place(p.component, p.u, J, 1., D);
    }
    for(std::size_t b = 0; b < m_blends.size(); ++b)
    {
      const Blend& B = m_blends[b];
      if(B.base_component() != p.component || B.base_region().chart() != p.u.chart)
        continue;
      Alpha_and_gradient<Ellipse_blending_region::Parameter_vector> A =
        B.base_region().alpha_and_gradient(Eigen::Vector2d(p.u.x, p.u.y));
      if(A.location.side == Region_side::Retained)
        continue;
      if(const std::optional<Eigen::Vector3d> x = evaluate_in_blend(p, b, A, J, D))
        return *x;
      break;
    }
    return place(p.component, p.u, J, 1., D);
  }

  // s at point p of blend b's base region, not on its retained side, located
  // by A there: alpha x1 + (1 - alpha) x2 (eq. 3); nothing if beta is not
  // defined there (then s is p's own component point).
  std::optional<Eigen::Vector3d> evaluate_in_blend(const Shape_point& p, std::size_t b,
                                                   Alpha_and_gradient<Ellipse_blending_region::Parameter_vector> A,
                                                   Sparse_jacobian* J, Eigen::Matrix<double, 3, 2>* D) const
  {
    const Blend& B = m_blends[b];
    const Eigen::Vector2d v(p.u.x, p.u.y);
    // beta(u), its derivatives with respect to the region's parameters and
    // to u, and the derivative of alpha with respect to u.
    const std::optional<internal::Blend_correspondence> beta =
      internal::blend_correspondence(B, is_tube(B.added_component()), v, A, J != nullptr, D != nullptr);
    if(!beta)
      return std::nullopt;
    const double alpha = A.alpha;
    Eigen::Matrix<double, 3, 2> D1, D2;
    const Eigen::Vector3d x1 = place(p.component, p.u, J, alpha, D ? &D1 : nullptr);
    const Eigen::Vector3d x2 = place(B.added_component(), beta->u2, J, 1. - alpha, (J || D) ? &D2 : nullptr);
    if(J)
    {
      Jacobian_block blk;
      blk.first_column = blend_offset(b);
      blk.columns = (x1 - x2) * A.gradient.transpose() + (1. - alpha) * D2 * beta->du2_dq;
      J->push_back(std::move(blk));
    }
    if(D)
      *D = alpha * D1 + (1. - alpha) * D2 * beta->du2_du + (x1 - x2) * beta->dalpha_du;
    return alpha * x1 + (1. - alpha) * x2;
  }

  std::vector<Component> m_components;
  std::vector<Blend> m_blends;
  std::vector<Hole_record> m_holes;
  internal::Parameter_layout m_layout;
  std::vector<bool> m_fixed;
  std::vector<std::size_t> m_parent;    // see parent()
  std::vector<Eigen::Vector3d> m_root_t; // see root_translation()
  std::vector<Eigen::Matrix3d> m_root_R; // see root_rotation()
};

} // namespace Blended_shapes
} // namespace CGAL

#endif // CGAL_BLENDED_SHAPE_BLENDING_BLENDED_SHAPE_H
