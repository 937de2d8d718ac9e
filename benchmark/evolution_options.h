// SPDX-License-Identifier: LGPL-3.0-or-later
// Options shared by the evolution benchmarks (reproduce_paper, evolve_parts):
// the blending stages (--blend-stages N, --stage-iterations N,
// --first-split-stages N, --first-split-stage-iterations N, the members of
// Evolution_settings of the same meaning: blend_stages,
// intermediate_stage_iterations, first_split_blend_stages,
// first_split_stage_iterations) and the input's scaling (--input-scale S).
#ifndef BLENDED_SHAPE_BENCHMARK_EVOLUTION_OPTIONS_H
#define BLENDED_SHAPE_BENCHMARK_EVOLUTION_OPTIONS_H

#include "benchmark_util.h"

#include <CGAL/Blended_shape/Evolution/Evolution_settings.h>
#include <CGAL/Blended_shape/parameters.h>

#include <CGAL/Aff_transformation_3.h>
#include <CGAL/Polygon_mesh_processing/transform.h>

#include <cstring>
#include <string>
#include <vector>

namespace blended_shape_benchmark {

struct Stage_options
{
  std::size_t blend_stages = CGAL::Blended_shapes::Evolution_settings().blend_stages;
  std::size_t stage_iterations = CGAL::Blended_shapes::Evolution_settings().intermediate_stage_iterations;
  std::size_t first_split_stages = CGAL::Blended_shapes::Evolution_settings().first_split_blend_stages;
  std::size_t first_split_stage_iterations = CGAL::Blended_shapes::Evolution_settings().first_split_stage_iterations;

  static constexpr const char* usage =
    "[--blend-stages N] [--stage-iterations N] [--first-split-stages N] [--first-split-stage-iterations N]";

  // If argv[i] is one of the options and argv[i + 1] a count >= 1, reads it
  // and moves i to the value; false otherwise (nothing read).
  bool parse(int argc, char** argv, int& i)
  {
    const struct { const char* flag; std::size_t* value; } options[] = {
      {"--blend-stages", &blend_stages},
      {"--stage-iterations", &stage_iterations},
      {"--first-split-stages", &first_split_stages},
      {"--first-split-stage-iterations", &first_split_stage_iterations}};
    for(const auto& o : options)
    {
      std::size_t value = 0;
      if(std::strcmp(argv[i], o.flag) == 0 && i + 1 < argc && parse_count(argv[i + 1], value) && value >= 1)
      {
        *o.value = value;
        ++i;
        return true;
      }
    }
    return false;
  }

  // For the tables' headers.
  std::string description() const
  {
    return "blend stages " + std::to_string(blend_stages) + ", at most " + std::to_string(stage_iterations) +
           " iterations each but the last (first split: " + std::to_string(first_split_stages) + ", at most " +
           std::to_string(first_split_stage_iterations) + ")";
  }

  // `np` with the four settings.
  template <class NamedParameters>
  auto named_parameters(const NamedParameters& np) const
  {
    namespace BSP = CGAL::Blended_shapes::parameters;
    return BSP::blend_stages(
      blend_stages,
      BSP::intermediate_stage_iterations(
        stage_iterations, BSP::first_split_blend_stages(
                            first_split_stages, BSP::first_split_stage_iterations(first_split_stage_iterations, np))));
  }
};

// --input-scale S: `points` and, if not null, `mesh` (the mesh they were
// scanned from, for the Chamfer distance) multiplied by `s` about the
// origin; with s = 1 + 1e-7, 1 + 2e-7, ...: how much a result depends on a
// change of its input far below its noise (the manual, Inputs changed by 1e-7).
template <class Point, class Mesh>
void scale_input(double s, std::vector<Point>& points, Mesh* mesh)
{
  if(s == 1.)
    return;
  typedef typename CGAL::Kernel_traits<Point>::Kernel Kernel;
  const typename Kernel::Aff_transformation_3 scaling(CGAL::SCALING, s);
  for(Point& p : points)
    p = scaling(p);
  if(mesh)
    CGAL::Polygon_mesh_processing::transform(scaling, *mesh);
}

} // namespace blended_shape_benchmark

#endif // BLENDED_SHAPE_BENCHMARK_EVOLUTION_OPTIONS_H
