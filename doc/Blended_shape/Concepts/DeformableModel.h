/*!
\class DeformableModel DeformableModel.h
\ingroup PkgBlendedShapeConcepts
\cgalConcept

A shape model that `CGAL::Blended_shapes::Deformable_model_fitter` can fit
(sec. 5.1): a map `x(u; q)` from chart points `u` to space with a parameter
vector `q`, its model Jacobian `L = dx/dq` (eq. 6) and its chart Jacobian
`dx/du` (for the closest-point projections), on charts that the fitter
tessellates once (`CGAL::Blended_shapes::Chart_mesh`) and positions by the model.
The numbers of parameters and charts are those of the model's structure;
when it changes (a split, say), the fitter is told by
`Deformable_model_fitter::restructure()` and tessellates the charts anew.

Parameters: the fitter keeps them within their bounds (shape lengths also
under a multiple of the data's size), and a parameter whose Jacobian column
is zero at every point (a fixed one) never moves. `set_parameters()` may
refuse a vector with `std::invalid_argument` (the model unchanged): the
fitter then treats the step as failed.

Surface: a chart point is on the surface if it is in its chart's domain and,
for a blended shape, not in a discarded part of the domain; the fitter
searches only the mesh faces with a corner on the surface, and evaluates
`point_and_jacobian()`, `point_and_chart_jacobian()` and `normal()` only at
canonical points on the surface (`canonical_surface_point()`).

Optional: a model may also have
`bool canonical_surface_point_chart_jacobian_and_normal(u, c, x, D, Vector_3* n) const`,
`canonical_surface_point_and_chart_jacobian()` that also gives, if `n` is
not null, the normal at `c` from the same evaluation, exactly `normal(c)`
where `u` is `c` itself. The closest-point search then takes the normals of
the foot points from its own evaluations instead of calling `normal()`
(`Deformable_blended_model` has it: its `normal()` locates the point in the
blends again, which a superquadric's does not need).

\cgalHasModelsBegin
\cgalHasModels{CGAL::Blended_shapes::Deformable_model}
\cgalHasModels{CGAL::Blended_shapes::Deformable_blended_model}
\cgalHasModelsEnd
*/
class DeformableModel
{
public:
  /// A CGAL kernel with `FT` = `double`.
  typedef unspecified_type Geom_traits;
  /// `Geom_traits::Point_3`.
  typedef unspecified_type Point_3;
  /// `Geom_traits::Vector_3`.
  typedef unspecified_type Vector_3;
  /// A 3 x n Eigen matrix type (n = `number_of_parameters()`).
  typedef unspecified_type Jacobian;
  /// `Eigen::Matrix<double, 3, 2>`.
  typedef unspecified_type Chart_jacobian;

  /// The dimension of `q`.
  std::size_t number_of_parameters() const;
  /// The parameter vector `q`.
  Eigen::VectorXd parameters() const;
  /// Sets `q`. \throws std::invalid_argument if the model refuses it (then unchanged).
  void set_parameters(const Eigen::VectorXd& q);
  /// Lower bound of parameter `i` (`-HUGE_VAL` if none).
  double parameter_lower_bound(std::size_t i) const;
  /// Upper bound of parameter `i` (`HUGE_VAL` if none).
  double parameter_upper_bound(std::size_t i) const;
  /// `Parameter_kind::Length` for the lengths the fitter caps by the data's size.
  CGAL::Blended_shapes::Parameter_kind parameter_kind(std::size_t i) const;
  /// Whether parameter `i` is part of the rigid pose (moved alone in the `Rigid` phase; never capped).
  bool is_pose_parameter(std::size_t i) const;
  /// Whether parameter `i` places one component relative to another (held by
  /// the fitter's loose placement spring, `Fitting_settings::placement_stiffness`).
  bool is_placement_parameter(std::size_t i) const;
  /// Whether parameter `i` places a blending region in its chart: a
  /// parameter whose moves set_parameters() may refuse although it has no
  /// bounds (a region must stay inside its chart). The fitter holds these
  /// for the rest of a step whose trial the model refused.
  bool is_blending_region_parameter(std::size_t i) const;

  /// The number of charts.
  std::size_t number_of_charts() const;
  /// The domain of chart `c` (tessellated by the fitter).
  CGAL::Blended_shapes::Chart_domain chart_domain(std::size_t c) const;
  /// Whether `u` is in its chart's domain and on the surface.
  bool is_on_surface(const CGAL::Blended_shapes::Chart_point& u) const;
  /// The canonical representative of `u` in `c`, if `u` is on the surface; otherwise false.
  bool canonical_surface_point(const CGAL::Blended_shapes::Chart_point& u, CGAL::Blended_shapes::Chart_point& c) const;
  /// Other chart points of the surface point at the canonical point `u`, in
  /// whose coordinates a closest-point projection that reached the edge of
  /// `u`'s chart part goes on (the added component's chart beyond a blend's
  /// strip); empty where charts overlap enough.
  std::vector<CGAL::Blended_shapes::Chart_point> alternative_chart_points(const CGAL::Blended_shapes::Chart_point& u) const;

  /// `x(u)` (for any `u` in its chart's domain: the meshes are positioned with it).
  Point_3 point(const CGAL::Blended_shapes::Chart_point& u) const;
  /// The unit outward normal at `u`.
  Vector_3 normal(const CGAL::Blended_shapes::Chart_point& u) const;
  /// `x(u)` and `L(u)`, resized to 3 x `number_of_parameters()`.
  Point_3 point_and_jacobian(const CGAL::Blended_shapes::Chart_point& u, Jacobian& L) const;
  /// `x(u)` and `dx/du` with respect to `u`'s chart coordinates.
  Point_3 point_and_chart_jacobian(const CGAL::Blended_shapes::Chart_point& u, Chart_jacobian& D) const;
  /// `canonical_surface_point(u, c)` and, where it is true, `x(c)` in `x` and
  /// `dx/du` at `c` in `D`: the same values as the two calls, in one pass (the
  /// closest-point search's step; a blended model locates the point in its blends once).
  bool canonical_surface_point_and_chart_jacobian(const CGAL::Blended_shapes::Chart_point& u,
                                                  CGAL::Blended_shapes::Chart_point& c, Point_3& x,
                                                  Chart_jacobian& D) const;
};
