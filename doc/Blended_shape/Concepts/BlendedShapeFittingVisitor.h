/*!
\class BlendedShapeFittingVisitor BlendedShapeFittingVisitor.h <CGAL/Blended_shape/Fitting/Fitting_visitor.h>
\ingroup PkgBlendedShapeConcepts
\cgalConcept

The progress hooks of a fit: `CGAL::Blended_shapes::Deformable_model_fitter::run()`
and `CGAL::Blended_shapes::fit_superquadric()` (named parameter `visitor`)
call them as the fit goes.

The easiest model is a class derived from
`CGAL::Blended_shapes::Default_fitting_visitor`, whose hooks do nothing,
overriding the hooks of interest (they are not virtual: the fitter is a
template and calls the hooks of the visitor's own type). Later releases will
add hooks for splits and holes, with empty defaults in
`Default_fitting_visitor`, so deriving from it keeps a visitor compiling.

`fit_superquadric()` takes the visitor by value (named parameters are copied):
a visitor that collects data should hold a pointer or a reference to where
the data goes. With its default `try_all_axes = true`, `fit_superquadric()`
runs several fits in a row: three short ones (one per choice of the
primitive's `z` axis, each ending with the `Subset` phase), the full one, then
short fits of its similar superquadrics and full fits of those that come out
clearly closer (`CGAL::Blended_shapes::Superquadric_multistart_search`, see
the manual); the iteration numbers start from 0 in each.

\cgalHasModelsBegin
\cgalHasModels{CGAL::Blended_shapes::Default_fitting_visitor}
\cgalHasModelsEnd
*/
class BlendedShapeFittingVisitor
{
public:
  /// Called when the fit enters `phase`, before iteration `iteration + 1`
  /// (`iteration` iterations of this run are done). The phases come in the order
  /// `Rigid` (only with `rigid_first`), `Subset` (only if the subset is smaller
  /// than the point set), `All_points`, and `Steady_state`, which is reported
  /// only when the fit came to rest on all points.
  void on_phase(CGAL::Blended_shapes::Fitting_phase phase, std::size_t iteration);

  /// Called after every iteration, accepted or not, with the iteration number
  /// (from 1), the fit energy after it
  /// (`CGAL::Blended_shapes::Step_report::energy_after`, unchanged if the step was rejected: half the sum of squared
  /// distances to the model, or of the Cauchy loss with robust weighting) and
  /// the number of points the iteration used (the subset or all points).
  void on_iteration(std::size_t iteration, double energy, std::size_t points_used);
};
