// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_BLENDED_SHAPE_FITTING_BLENDED_MODEL_METRICS_H
#define CGAL_BLENDED_SHAPE_FITTING_BLENDED_MODEL_METRICS_H

// The symmetric Chamfer distance of a blended model to a reference mesh, apart
// from Fit_metrics.h so that the fit of one superquadric does not pull in
// the blending headers.

#include <CGAL/Blended_shape/Blending/Blended_shape_mesh.h>
#include <CGAL/Blended_shape/Fitting/Deformable_blended_model.h>
#include <CGAL/Blended_shape/Fitting/Fit_metrics.h>
#include <CGAL/Blended_shape/Fitting/sample_model.h>

#include <CGAL/Surface_mesh.h>

#include <cstddef>
#include <vector>

namespace CGAL {
namespace Blended_shapes {

/*!
\ingroup PkgBlendedShapeMetrics
Symmetric Chamfer distance between a blended model and a reference triangle
mesh, as for chart meshes (Fit_metrics.h): the mean distance of `samples`
points spread uniformly by area on the model's surface
(sample_model_surface() at `resolution`: every
surface point once, whatever pieces overlap there, the part a gradual blend
expresses through its base's disk included) to the reference, and of as
many points on the reference to the model's pieces (Blended_shape_pieces at
`resolution`, its retained faces as placed by the pose). Deterministic for `seed`.
\throws std::invalid_argument if `reference` has no face, a face that is not a triangle, or a coordinate
that is not finite or beyond `maximum_coordinate_magnitude`.
*/
template <class GeomTraits>
double symmetric_chamfer_distance(const Deformable_blended_model<GeomTraits>& model,
                                  const CGAL::Surface_mesh<typename GeomTraits::Point_3>& reference,
                                  std::size_t samples = 20000, unsigned int seed = 0, int resolution = 24)
{
  typedef typename GeomTraits::Point_3 Point_3;
  typedef CGAL::Surface_mesh<Point_3> Mesh;
  std::vector<Point_3> from_model;
  for(const auto& s : sample_model_surface(model, samples, seed, resolution))
    from_model.push_back(s.point);
  const Blended_shape_pieces<GeomTraits> pieces(model.shape(), resolution,
                                                [&](const Point_3& p) { return model.placed(p); });
  const Mesh surface = pieces.merged_mesh();
  return internal::symmetric_chamfer_distance(from_model, std::vector<const Mesh*>{&surface}, reference, samples, seed);
}

} // namespace Blended_shapes
} // namespace CGAL

#endif // CGAL_BLENDED_SHAPE_FITTING_BLENDED_MODEL_METRICS_H
