/*!
\class BlendedShapePrimitive BlendedShapePrimitive.h <CGAL/Blended_shape.h>
\ingroup PkgBlendedShapeConcepts
\cgalConcept

A component shape of a blended model (paper sec. 3 and App. B): a map
`s(u; q)` from chart points `u` to points of 3D space, with a fixed
number of real parameters `q`, its exact parameter Jacobian `ds/dq`, its
outward unit normal, and a set of chart domains without singularity (sec. 3.2)
that together cover the surface.

A primitive is placed in space by `CGAL::Blended_shapes::Deformable_model`
(`x(u) = c + R s(u)`, eq. 5), tessellated by `CGAL::Blended_shapes::Chart_mesh`
and fitted by `CGAL::Blended_shapes::Deformable_model_fitter`; a model of this
concept only describes the shape in its own frame.

<b>Charts.</b> Each chart `c` in `[0, number_of_charts())` has a domain
(`chart_domain(c)`: a disk, a periodic torus square or an open tube periodic in `x` only) on which the map, its
Jacobian and its normal are smooth. Charts may overlap (the two halves of the
ellipsoid overlap in a band around the equator); where they do, the same
surface point has several chart points, and the primitive tells which ones with
`to_chart()` and gives each surface point one representative with
`canonical_chart_point()` (the quotient domain of eq. 1 and 2). A periodic chart
identifies chart points that differ by a period. Every chart is oriented so that
counterclockwise triangles of the chart plane map to triangles whose normal,
by the right-hand rule, points outward: `normal(u)` is the unit normal in the
direction of `d s/dx x d s/dy`.

<b>Parameters.</b> Parameter `i` has a name, closed bounds and a default value
(`CGAL::Blended_shapes::Parameter_info`), and a kind
(`CGAL::Blended_shapes::Parameter_kind`): lengths scale with the shape and are
capped by the fitter at a multiple of the data's size
(`Fitting_settings::maximum_size_factor`); dimensionless parameters are not.
The fitter keeps every parameter inside its bounds, so the map, the Jacobian
and the normal must be finite for every parameter vector inside the bounds and
every chart point of a domain, including the chart centres and seams.

<b>Checking a model.</b> `CGAL::Blended_shapes::check_jacobian()` compares
`point_and_jacobian()` with finite differences of `point()`, and
`CGAL::Blended_shapes::check_chart_jacobian()` does the same for
`point_and_chart_jacobian()`;
`CGAL::Blended_shapes::check_chart_consistency()` checks that `to_chart()`,
`canonical_chart_point()`, `point()` and `normal()` agree where charts overlap.
A new model should pass all three (see \ref custom_primitive.cpp).

Models are copied freely (the fitter copies the model to try a step), so they
should be cheap to copy. A default constructor is not required.

\cgalHasModelsBegin
\cgalHasModels{CGAL::Blended_shapes::Superquadric_ellipsoid}
\cgalHasModels{CGAL::Blended_shapes::Superquadric_toroid}
\cgalHasModels{`Tapered_superquadric` in \ref custom_primitive.cpp "examples/custom_primitive.cpp"}
\cgalHasModelsEnd

\sa `CGAL::Blended_shapes::Deformable_model`
*/
class BlendedShapePrimitive
{
public:
  /// \name Types
  /// @{

  /// A CGAL kernel. The package's models and algorithms convert coordinates
  /// to `double` (Eigen); kernels whose `FT` is `double`, such as
  /// `CGAL::Simple_cartesian<double>` and
  /// `CGAL::Exact_predicates_inexact_constructions_kernel`, are the ones tested.
  typedef unspecified_type Geom_traits;

  /// `Geom_traits::FT`.
  typedef unspecified_type FT;

  /// `Geom_traits::Point_3`: the type of the points of the surface.
  typedef unspecified_type Point_3;

  /// `Geom_traits::Vector_3`: the type of the normals.
  typedef unspecified_type Vector_3;

  /// The number `P` of parameters, a compile-time constant.
  static constexpr int number_of_parameters = P;

  /// The parameter vector: `Eigen::Matrix<double, P, 1>`.
  typedef Eigen::Matrix<double, P, 1> Parameter_vector;

  /// The parameter Jacobian `ds/dq` at one chart point: `Eigen::Matrix<double, 3, P>`;
  /// column `i` is the derivative of the point with respect to parameter `i`.
  typedef Eigen::Matrix<double, 3, P> Jacobian;

  /// The chart Jacobian at one chart point: `Eigen::Matrix<double, 3, 2>`;
  /// column 0 is the derivative of the point with respect to the first chart
  /// coordinate `x`, column 1 with respect to `y`.
  typedef Eigen::Matrix<double, 3, 2> Chart_jacobian;

  /// @}

  /// \name Parameters
  /// @{

  /// Name, bounds, default value and kind of parameter `i`, `0 <= i < P`.
  static const CGAL::Blended_shapes::Parameter_info& parameter_info(int i);

  /// `parameter_info(i).name`, e.g. `"a1"`.
  static const char* parameter_name(int i);

  /// `parameter_info(i).lower_bound`: the smallest value allowed (included).
  static double parameter_lower_bound(int i);

  /// `parameter_info(i).upper_bound`: the largest value allowed (included;
  /// may be `HUGE_VAL`).
  static double parameter_upper_bound(int i);

  /// `parameter_info(i).default_value`.
  static double parameter_default_value(int i);

  /// The current parameters.
  const Parameter_vector& parameters() const;

  /// Sets the parameters.
  /// \throws std::invalid_argument if a value is not finite or lies outside
  ///         its bounds; the message names the parameter. The primitive is
  ///         then unchanged.
  void set_parameters(const Parameter_vector& q);

  /// @}

  /// \name Charts
  /// @{

  /// The number of charts, at least 1. It does not depend on the parameters.
  std::size_t number_of_charts() const;

  /// The domain of chart `c`, `0 <= c < number_of_charts()`.
  CGAL::Blended_shapes::Chart_domain chart_domain(std::size_t c) const;

  /// The chart point of chart `target` that is the same surface point as `p`,
  /// in `q`. Returns `false`, leaving `q` unspecified, if chart `target` does not
  /// contain that surface point. For `target == p.chart` it returns `true` and
  /// `q` is `p` itself or, for a periodic chart, `p` reduced to the period.
  bool to_chart(const CGAL::Blended_shapes::Chart_point& p, std::size_t target,
                CGAL::Blended_shapes::Chart_point& q) const;

  /// The representative of the surface point of `p`: all chart points of the
  /// same surface point (in any chart, for any period shift) have the same
  /// canonical chart point, up to rounding, and it lies in its chart's domain.
  CGAL::Blended_shapes::Chart_point canonical_chart_point(const CGAL::Blended_shapes::Chart_point& p) const;

  /// @}

  /// \name Evaluation
  /// @{

  /// The surface point `s(p)`, in the primitive's own frame.
  /// \pre `chart_domain(p.chart).contains(p.x, p.y)`
  Point_3 point(const CGAL::Blended_shapes::Chart_point& p) const;

  /// The surface point `s(p)`, returned, and the parameter Jacobian `ds/dq`
  /// at `p`, written to `J`. Exact (analytic), finite everywhere on the domain.
  Point_3 point_and_jacobian(const CGAL::Blended_shapes::Chart_point& p, Jacobian& J) const;

  /// The parameter Jacobian `ds/dq` at `p`, written to `J`.
  void jacobian(const CGAL::Blended_shapes::Chart_point& p, Jacobian& J) const;

  /// The surface point `s(p)`, returned, and the chart Jacobian
  /// `D = [ds/dx, ds/dy]` at `p` (`x`, `y` the chart coordinates of `p`),
  /// written to `D`. Exact (analytic); the foot-point projection
  /// (`CGAL::Blended_shapes::refine_closest_point()`) takes its Gauss-Newton
  /// steps with it. Where the map is not differentiable or its chart
  /// Jacobian loses rank (a signed power with an exponent other than 1 at a
  /// zero cosine, the pole of a superquadric ellipsoid, the pinch of a closed
  /// hole) `D` holds a one-sided value or a finite cap, never a NaN or an
  /// infinity. The package's models take e |c|^(e-1) at |c| = 1e-6 within
  /// 1e-6 of a zero `c = 0`: a cap where it is infinite (e < 1), a small
  /// slope where it vanishes (e > 1), so that the projection can step off
  /// such a place.
  Point_3 point_and_chart_jacobian(const CGAL::Blended_shapes::Chart_point& p, Chart_jacobian& D) const;

  /// The unit outward normal at `p` (see the chart orientation above). Defined
  /// at every point of the domain, also where the chart map is not regular
  /// (e.g. the poles of a superquadric with exponents other than 1): the
  /// limit of the normals around it.
  Vector_3 normal(const CGAL::Blended_shapes::Chart_point& p) const;

  /// @}
};
