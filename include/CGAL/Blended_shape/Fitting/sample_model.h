// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_BLENDED_SHAPE_FITTING_SAMPLE_MODEL_H
#define CGAL_BLENDED_SHAPE_FITTING_SAMPLE_MODEL_H

#include <CGAL/Blended_shape/Primitives/Chart_mesh.h>

#include <cmath>
#include <random>
#include <vector>

namespace CGAL {
namespace Blended_shapes {

/// \ingroup PkgBlendedShapeMetrics
/// A point sampled on a model, with the chart point it came from and the normal there.
template <class GeomTraits>
struct Surface_sample
{
  typename GeomTraits::Point_3 point;   ///< the point on the model
  typename GeomTraits::Vector_3 normal; ///< the unit outward normal there
  Chart_point chart_point;              ///< the chart point it came from
};

/*!
\ingroup PkgBlendedShapeMetrics

`count` points spread over the surface of `model` (a `DeformableModel`:
Deformable_model or Deformable_blended_model), for tests and benchmarks:
triangles of the chart meshes are drawn with probability proportional to
their area in space, a uniform point of the triangle is mapped back to its
chart point, and the model is evaluated there. Where charts overlap (or
blends glue strips), each sample is kept only if its chart point is the
canonical one, so overlaps are not sampled twice; samples in a discarded
part of the domain are dropped. Deterministic for `seed`.

If `eye` is given, only samples whose normal faces it are kept (a
single-view scan of a convex shape); then fewer than `count` may come out.
*/
template <class Model>
std::vector<Surface_sample<typename Model::Geom_traits>>
sample_model_surface(const Model& model, std::size_t count, unsigned int seed, int resolution = 24,
                     const typename Model::Geom_traits::Point_3* eye = nullptr)
{
  typedef typename Model::Geom_traits GT;
  std::vector<Chart_mesh<GT>> charts;
  for(std::size_t c = 0; c < model.number_of_charts(); ++c)
  {
    charts.emplace_back(c, model.chart_domain(c), resolution);
    charts.back().set_positions([&](const Chart_point& u) { return model.point(u); });
  }
  struct Face_ref { std::size_t chart; typename Chart_mesh<GT>::face_descriptor face; };
  std::vector<Face_ref> faces_list;
  std::vector<double> cumulative;
  double total = 0.;
  for(std::size_t c = 0; c < charts.size(); ++c)
    for(auto f : faces(charts[c].mesh()))
    {
      const auto v = charts[c].face_vertices(f);
      const auto& m = charts[c].mesh();
      total += std::sqrt(CGAL::to_double(CGAL::squared_area(m.point(v[0]), m.point(v[1]), m.point(v[2]))));
      cumulative.push_back(total);
      faces_list.push_back({c, f});
    }
  std::vector<Surface_sample<GT>> samples;
  if(!(total > 0.))
    return samples;
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(0., 1.);
  std::size_t attempts = 0;
  while(samples.size() < count && attempts < 20 * count + 100)
  {
    ++attempts;
    const std::size_t k = std::size_t(std::lower_bound(cumulative.begin(), cumulative.end(), unit(rng) * total) -
                                      cumulative.begin());
    const Face_ref& fr = faces_list[(std::min)(k, faces_list.size() - 1)];
    double a = unit(rng), b = unit(rng);
    if(a + b > 1.) { a = 1. - a; b = 1. - b; }
    const Chart_point u = charts[fr.chart].chart_point(fr.face, {{1. - a - b, a, b}});
    Chart_point cu;
    if(!model.canonical_surface_point(u, cu))
      continue; // in a discarded part of a blended shape's domain
    if(cu.chart != u.chart)
      continue; // the other chart's copy of this band (or strip) is the one that counts
    Surface_sample<GT> s{model.point(u), model.normal(u), u};
    if(eye != nullptr && s.normal * (*eye - s.point) <= 0.)
      continue;
    samples.push_back(s);
  }
  return samples;
}

} // namespace Blended_shapes
} // namespace CGAL

#endif // CGAL_BLENDED_SHAPE_FITTING_SAMPLE_MODEL_H
