// SPDX-License-Identifier: LGPL-3.0-or-later
// Part evolution (sec. 4.1, 5.4) on data made of parts and on data of one
// superquadric: fit_blended_shape() (the least-squares fit of one
// superquadric, then Part_evolution::run()), with the events (split kept or
// undone, description lengths, RMS), the parts, the least-squares RMS over
// the bounding-box diagonal before and after evolution, the result's (with
// one part, the robust fit's, over its inliers), the symmetric Chamfer
// distance to the mesh scanned (over the points' diagonal; "-" for data
// without a mesh), and the seconds.
//
//   evolve_parts [--threads N] [--evolution-points N] [--splits forces|creases|both|branches]
//                [--blend-stages N] [--stage-iterations N] [--first-split-stages N]
//                [--first-split-stage-iterations N] [--input-scale S] [--meshes-only]
//
// --evolution-points N: Evolution_settings::maximum_evolution_points (default
// 4000; 0: evolution on all points). --splits: Evolution_settings::split_source
// (default creases). --blend-stages N, --stage-iterations N,
// --first-split-stages N, --first-split-stage-iterations N:
// Evolution_settings::blend_stages, intermediate_stage_iterations,
// first_split_blend_stages and first_split_stage_iterations.
// --input-scale S: every row's points (and the mesh scanned, for the
// Chamfer distance) multiplied by S > 0 about the origin, as in
// reproduce_paper (S = 1 + 1e-7, 1 + 2e-7, ...: the paths that rounding picks).
//
// Data: the box/cylinder CAD object scanned from the default camera (the
// paper's Figure 18 first row), the bundled real mug scan, an ellipsoid
// with one protruding part (8000 points, noise 0.2 % of the diagonal, three
// seeds), and single
// superquadrics (full view and single view, three seeds each), which must
// stay one part. A second table: the genus-0 meshes of data/ made of parts
// (cross, tripod, spool, hammer, Spot the cow), each scanned from the
// default camera, with the parts a person would name.
#include "benchmark_util.h"
#include "evolution_options.h"

#include <CGAL/Blended_shape/Evolution/fit_blended_shape.h>
#include <CGAL/Blended_shape/IO/read_points.h>
#include <CGAL/Blended_shape/IO/read_triangle_mesh.h>
#include <CGAL/Blended_shape/Fitting/sample_model.h>
#include <CGAL/Blended_shape/Scanning/CAD_objects.h>
#include <CGAL/Blended_shape/Scanning/Range_scan_simulator.h>
#include <blended_shape_testing/synthetic_scans.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <CGAL/Bbox_3.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <optional>
#include <iomanip>
#include <iostream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace BS = CGAL::Blended_shapes;
typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
typedef CGAL::Surface_mesh<K::Point_3> Mesh;
typedef BS::Deformable_model<BS::Superquadric_ellipsoid<K>> Primitive_model;

namespace {

std::vector<K::Point_3> scan(const Mesh& m)
{
  std::vector<K::Point_3> pts;
  for(const auto& s : BS::simulate_range_scan(m, BS::default_camera_for(m)))
    pts.push_back(s.point);
  return pts;
}

// A mesh and its scan: the scan is fitted, the mesh measures the result (Chamfer distance).
struct Scanned_mesh
{
  Mesh mesh;
  std::vector<K::Point_3> points;
};

Scanned_mesh box_cylinder_scan()
{
  Scanned_mesh s;
  CGAL::copy_face_graph(BS::make_box_cylinder(), s.mesh);
  s.points = scan(s.mesh);
  return s;
}

Scanned_mesh mesh_scan(const std::string& file)
{
  Scanned_mesh s;
  BS::read_triangle_mesh(std::string(BLENDED_SHAPE_DATA_DIR) + "/meshes/" + file, s.mesh);
  s.points = scan(s.mesh);
  return s;
}

std::size_t evolution_points = BS::Evolution_settings().maximum_evolution_points; // --evolution-points
BS::Split_source split_source = BS::Evolution_settings().split_source;             // --splits
blended_shape_benchmark::Stage_options stages;                                      // --blend-stages ...
double input_scale = 1.;                                                           // --input-scale

// `reference`: the mesh scanned, if any (the Chamfer column).
void evolve(const std::string& name, std::vector<K::Point_3> points, std::size_t threads,
            const Mesh* reference = nullptr)
{
  std::optional<Mesh> scaled_reference; // (--input-scale: a scaled copy of `reference`)
  if(reference && input_scale != 1.)
    reference = &scaled_reference.emplace(*reference);
  blended_shape_benchmark::scale_input(input_scale, points, scaled_reference ? &*scaled_reference : nullptr);
  const auto r = BS::fit_blended_shape(
    points, BS::parameters::reference_mesh(
              reference, BS::parameters::split_source(
                           split_source, stages.named_parameters(BS::parameters::maximum_evolution_points(
                                           evolution_points, BS::parameters::number_of_threads(threads))))));
  // The least-squares RMS of evolution: before, that of its start; after,
  // that of the last split kept, part removed or revert (the events measure
  // both; a removal is measured before the model is fitted to rest again).
  const CGAL::Bbox_3 box = CGAL::bbox_3(points.begin(), points.end());
  const double diagonal = std::sqrt(CGAL::square(box.xmax() - box.xmin()) + CGAL::square(box.ymax() - box.ymin()) +
                                    CGAL::square(box.zmax() - box.zmin()));
  const double before = r.events.empty() ? r.first_fit.metrics.rms : r.events.front().rms_before;
  double after = before;
  for(const auto& e : r.events)
    if(e.kind != BS::Evolution_event_kind::Undo) // a split kept, a part removed or a revert
      after = e.rms_after;
  std::cout << "| " << name << " | " << points.size() << " | " << std::fixed << std::setprecision(2)
            << 100. * before / diagonal << " | " << 100. * after / diagonal << " | " << r.number_of_parts() << " | "
            << 100. * r.metrics.rms_over_bbox_diagonal << " | ";
  if(r.metrics.chamfer_distance)
    std::cout << std::setprecision(4) << *r.metrics.chamfer_distance / diagonal << std::setprecision(2) << " | ";
  else
    std::cout << "- | ";
  for(const auto& e : r.events)
    std::cout << BS::evolution_event_name(e.kind) << " " << e.component << " (L " << std::setprecision(0)
              << e.description_length_before << " -> " << e.description_length_after << std::setprecision(4)
              << ", RMS/diag " << 100. * e.rms_before / diagonal << " -> " << 100. * e.rms_after / diagonal
              << " %); " << std::setprecision(2);
  std::cout << " | " << r.metrics.iterations << (r.status.converged ? "" : " (not at rest)") << " | "
            << r.metrics.seconds << " |" << std::endl;
}

void evolve_synthetic_and_scans(std::size_t threads, const char* header)
{
  std::cout << header;
  const Scanned_mesh box_cylinder = box_cylinder_scan();
  evolve("box/cylinder scan", box_cylinder.points, threads, &box_cylinder.mesh);
  std::vector<K::Point_3> mug;
  BS::read_points(std::string(BLENDED_SHAPE_DATA_DIR) + "/scans/pcl_mug_scan.xyz", mug);
  evolve("real mug scan (data/scans/pcl_mug_scan.xyz)", mug, threads);
  for(unsigned seed : {1u, 2u, 3u})
    evolve("ellipsoid + part, seed " + std::to_string(seed), BS::testing::body_with_part_scan<K>(4000, seed), threads);
  std::mt19937_64 rng(7);
  for(int k = 0; k < 6; ++k)
  {
    const Primitive_model truth = BS::testing::random_superellipsoid<K>(rng);
    const bool single_view = k % 2 == 1;
    evolve(std::string("one superquadric, ") + (single_view ? "single view" : "full"),
           BS::testing::synthetic_scan(truth, 6000, single_view, 0.002, rng), threads);
  }
}

} // namespace

int main(int argc, char** argv)
{
  std::size_t threads = 1;
  bool meshes_only = false;
  for(int i = 1; i < argc; ++i)
  {
    std::optional<BS::Split_source> source;
    if(std::strcmp(argv[i], "--threads") == 0 && i + 1 < argc && blended_shape_benchmark::parse_count(argv[i + 1], threads))
      ++i;
    else if(std::strcmp(argv[i], "--meshes-only") == 0)
      meshes_only = true;
    else if(std::strcmp(argv[i], "--evolution-points") == 0 && i + 1 < argc &&
            blended_shape_benchmark::parse_count(argv[i + 1], evolution_points))
      ++i;
    else if(stages.parse(argc, argv, i)) {}
    else if(std::strcmp(argv[i], "--input-scale") == 0 && i + 1 < argc &&
            blended_shape_benchmark::parse_number(argv[i + 1], input_scale) && input_scale > 0.)
      ++i;
    else if(std::strcmp(argv[i], "--splits") == 0 && i + 1 < argc && (source = BS::split_source_from_name(argv[i + 1])))
    {
      split_source = *source;
      ++i;
    }
    else
    {
      std::cerr << "usage: evolve_parts [--threads N] [--evolution-points N] [--splits forces|creases|both|branches] "
                   << blended_shape_benchmark::Stage_options::usage << " [--input-scale S] [--meshes-only]\n";
      return 2;
    }
  }
  std::cout << blended_shape_benchmark::machine_description() << ", " << threads << " thread(s), splits from "
            << BS::split_source_name(split_source) << ", " << stages.description();
  if(input_scale != 1.)
  {
    std::ostringstream scale;
    scale << std::fixed << std::setprecision(10) << input_scale;
    std::cout << ", input scaled by " << scale.str();
  }
  std::cout << "\n\n";
  const char* header = "| data | points | least-squares RMS/diag % before | after | parts | result RMS/diag % | "
                       "Chamfer / diagonal | events | iterations | seconds |\n"
                       "|---|---:|---:|---:|---:|---:|---:|---|---:|---:|\n";
  if(!meshes_only)
    evolve_synthetic_and_scans(threads, header);
  // The parts a person would name, for comparison with the parts column.
  std::cout << "\nGenus-0 meshes made of parts, scanned from the default camera (200x200):\n\n" << header;
  struct Named_mesh { const char* name; const char* file; };
  for(const Named_mesh& m : {Named_mesh{"cross (data/meshes/cgal_cross.off; 2 bars)", "cgal_cross.off"},
                             Named_mesh{"tripod (cgal_tripod.off; 3 arms)", "cgal_tripod.off"},
                             Named_mesh{"spool (cgal_spool.off; 2 discs, 1 axle)", "cgal_spool.off"},
                             Named_mesh{"hammer (odedstein_hammer.obj; head, handle)", "odedstein_hammer.obj"},
                             Named_mesh{"Spot the cow (odedstein_spot_low_resolution.obj; body, head, 4 legs: 6)",
                                        "odedstein_spot_low_resolution.obj"}})
  {
    const Scanned_mesh scanned = mesh_scan(m.file);
    evolve(m.name, scanned.points, threads, &scanned.mesh);
  }
  return EXIT_SUCCESS;
}
