// SPDX-License-Identifier: LGPL-3.0-or-later
// The paper's experiments (sec. 6, Figure 18) next to ours: range data from
// simulated single-view scans of CAD objects (as the paper's "CAD utility")
// and of a human body mesh (the mannequin, scanned from the front over a
// 90 degree field of view), and the bundled real mug scan. Each is fitted
// with fit_superquadric() (or, with --evolve, fit_blended_shape(): part
// evolution) and reported like Figure 18, with the paper's numbers beside
// ours. Prints Markdown; --csv FILE also writes CSV.
//
//   reproduce_paper [--evolve] [--splits forces|creases|both|branches] [--evolution-points N] [--robust] [--threads N]
//                   [--seed N] [--area-weight W] [--blend-stages N] [--stage-iterations N]
//                   [--first-split-stages N] [--first-split-stage-iterations N] [--runs N] [--first-sweep]
//                   [--input-scale S] [--csv FILE] [--markdown FILE]
//
// The fits use the paper's least squares (Robust_weighting::None): its data
// have no strays, and the robust default may take a part of a multi-part
// object for strays and leave it out of the RMS figures. --robust: the default.
// --threads N: the fits on N threads (default 1, the paper's one processor;
// 0: all cores). The results do not depend on it, only the seconds.
// --seed N: Fitting_settings::random_seed (default 0), which draws the point
// subsets of the multi-start search: other seeds show how much a result
// depends on which local minimum of the first fit evolution starts from.
// --evolve: fit_blended_shape() (its least-squares start and evolution; with
// --robust a one-part result is the robust fit); the iteration / sweep
// column is then left empty (the model is not one superquadric), the
// Chamfer distance is that of the blended model (symmetric_chamfer_distance()).
// --evolution-points N: Evolution_settings::maximum_evolution_points (default
// 4000; 0: evolution on all points). --splits: Evolution_settings::split_source
// (default creases). --area-weight W: Fitting_settings::area_weight (default
// 0: the paper's fit, no area term). --blend-stages N, --stage-iterations N,
// --first-split-stages N, --first-split-stage-iterations N:
// Evolution_settings::blend_stages (default 4), intermediate_stage_iterations
// (default 30), first_split_blend_stages (default 2) and
// first_split_stage_iterations (default 1). --runs N:
// Evolution_settings::evolution_runs (default 1).
// --first-sweep (with --evolve): for each evolved model with blends, a
// second table on its first closest-point sweep (a fitter constructed on
// it, Fitting_settings::projection_start_samples; see the manual, Closest
// Points of a Blended Model): the RMS distance of the points from the
// tessellation alone and with the sampled starts, the seconds of each
// (fitter built, one sweep), the true RMS (each point's nearest of 2 million
// surface samples) and the evolution's own; and, for 3000 surface samples put
// off the surface along the normal by up to 0.4 % of the points' diagonal,
// how many end farther than the surface point they were made from.
// --input-scale S: every row's points (and the mesh they were scanned from,
// for the Chamfer distance) multiplied by S > 0 about the origin: with S =
// 1 + 1e-7, 1 + 2e-7, ... how much a result depends on a change of its
// input far below its noise (see the manual, Inputs changed by 1e-7).
//
// "iteration / sweep" is the mean time of one iteration of the fit (all its
// phases: the candidate fits on point subsets and the fit on all points) over
// the time of one plain CGAL closest-point sweep of all the points against the
// fitted model's chart meshes (AABB tree built, then one closest_point() per
// point, one thread, best of 3): the floor of an iteration, which needs at
// least one such sweep.
#include "benchmark_util.h"
#include "evolution_options.h"

#include <CGAL/Blended_shape/Scanning/CAD_objects.h>
#include <CGAL/Blended_shape/Scanning/Range_scan_simulator.h>
#include <CGAL/Blended_shape/Evolution/fit_blended_shape.h>
#include <CGAL/Blended_shape/Fitting/fit_superquadric.h>
#include <blended_shape_testing/synthetic_scans.h>
#include <CGAL/Blended_shape/internal/write_file_atomically.h>
#include <CGAL/Blended_shape/IO/read_points.h>
#include <CGAL/Blended_shape/IO/read_triangle_mesh.h>
#include <CGAL/Blended_shape/Fitting/sample_model.h>
#include <CGAL/Blended_shape/internal/nearest_points.h>

#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>

#include <cstring>
#include <iomanip>
#include <iostream>
#include <optional>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace BS = CGAL::Blended_shapes;
namespace BB = blended_shape_benchmark;
typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
typedef CGAL::Surface_mesh<K::Point_3> Mesh;

namespace {

// Figure 18 of the paper (parts, holes and genus read off Figs. 19-22).
struct Paper_row
{
  const char* data;
  int parameters, iterations;
  double rms[3];
  const char* parts;
  int holes, genus;
};

const Paper_row paper[] = {
  {"box/cylinder", 30, 75, {0.9, 1.3, 1.8}, "2", 0, 0},
  {"mug", 69, 171, {1.2, 1.4, 2.0}, "2", 1, 1},
  {"mannequin", 180, 476, {1.5, 2.2, 3.9}, "10", 0, 0},
  {"two-holed box", 84, 291, {1.0, 1.4, 2.1}, "1", 2, 2}};

struct Experiment
{
  std::string name;      // ours
  std::string source;    // where the points come from
  int paper_row;         // index into `paper`, -1 if none
  std::vector<K::Point_3> points;
  std::optional<Mesh> reference;
};

std::vector<K::Point_3> scan(const Mesh& mesh, const BS::Camera<K>& camera)
{
  std::vector<K::Point_3> pts;
  for(const auto& s : BS::simulate_range_scan(mesh, camera))
    pts.push_back(s.point);
  return pts;
}

Mesh to_mesh(const BS::CAD_mesh& m)
{
  Mesh out;
  CGAL::copy_face_graph(m, out);
  return out;
}

// The human body (y up, facing +z) from the front, 90 degree field of view,
// from the distance at which its height just fits.
BS::Camera<K> front_camera_90(const Mesh& mesh)
{
  CGAL::Bbox_3 b;
  for(auto v : mesh.vertices())
    b += mesh.point(v).bbox();
  const K::Point_3 c(0.5 * (b.xmin() + b.xmax()), 0.5 * (b.ymin() + b.ymax()), 0.5 * (b.zmin() + b.zmax()));
  const double half_height = 0.5 * (b.ymax() - b.ymin());
  const double distance = 1.1 * half_height / std::tan(0.25 * M_PI) + 0.5 * (b.zmax() - b.zmin());
  return BS::Camera<K>::perspective(K::Point_3(c.x(), c.y(), c.z() + distance), c, K::Vector_3(0, 1, 0), 90., 240, 240);
}

// Seconds of one plain CGAL closest-point sweep of `points` against `meshes`
// (tree built, then one query per point), the best of 3.
template <class ChartMeshes>
double closest_point_sweep_seconds(const std::vector<K::Point_3>& points, const ChartMeshes& meshes)
{
  typedef CGAL::AABB_face_graph_triangle_primitive<Mesh> Primitive;
  typedef CGAL::AABB_tree<CGAL::AABB_traits<K, Primitive>> Tree;
  double best = HUGE_VAL, checksum = 0.;
  for(int run = 0; run < 3; ++run)
  {
    const auto start = std::chrono::steady_clock::now();
    Tree tree;
    for(const auto& m : meshes)
      tree.insert(faces(m.mesh()).first, faces(m.mesh()).second, m.mesh());
    tree.build();
    tree.accelerate_distance_queries();
    for(const K::Point_3& p : points)
      checksum += tree.closest_point(p).x();
    best = (std::min)(best, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  return checksum == checksum ? best : HUGE_VAL; // (the checksum keeps the queries from being optimized away)
}

// What a row reports of one fit.
struct Fit_figures
{
  BS::Fit_metrics metrics;
  std::size_t parts = 1, holes = 0, genus = 0;
  std::optional<double> iteration_over_sweep;
};

std::string fixed(double x, int digits)
{
  std::ostringstream s;
  s << std::fixed << std::setprecision(digits) << x;
  return s.str();
}

// One row of the --first-sweep table (see the header) for `model` and `points`.
std::string first_sweep_row(const std::string& name, const std::vector<K::Point_3>& points,
                            const BS::Deformable_blended_model<K>& model, double evolution_rms, double diagonal,
                            std::size_t threads)
{
  typedef BS::Deformable_blended_model<K> Model;
  // the distances of `pts` to their first sweep's foot points, and its seconds
  const auto first_sweep = [&](const std::vector<K::Point_3>& pts, std::size_t samples, double& seconds) {
    const auto start = std::chrono::steady_clock::now();
    BS::Fitting_settings settings;
    settings.robust_weighting = BS::Robust_weighting::None;
    settings.number_of_threads = threads;
    settings.projection_start_samples = samples;
    BS::Deformable_model_fitter<Model> fitter(pts, model, settings);
    std::vector<double> distance;
    for(const auto& f : fitter.forces())
      distance.push_back(std::sqrt(CGAL::squared_distance(pts[f.index], f.model_point)));
    seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return distance;
  };
  const auto rms = [](const std::vector<double>& d) {
    double s = 0.;
    for(double x : d)
      s += x * x;
    return std::sqrt(s / double(d.size()));
  };
  const auto eigen = [](const K::Point_3& p) { return Eigen::Vector3d(p.x(), p.y(), p.z()); };
  std::vector<Eigen::Vector3d> sites, queries;
  for(const auto& s : BS::sample_model_surface(model, 2000000, 1u, 48))
    sites.push_back(eigen(s.point));
  for(const K::Point_3& p : points)
    queries.push_back(eigen(p));
  std::vector<double> truth;
  const std::vector<std::size_t> nearest = BS::internal::nearest_points(sites, queries);
  for(std::size_t i = 0; i < queries.size(); ++i)
    truth.push_back((sites[nearest[i]] - queries[i]).norm());
  const std::size_t samples = BS::Fitting_settings().projection_start_samples;
  double tessellation_s, sampled_s, ignored;
  const std::vector<double> tessellation = first_sweep(points, 0, tessellation_s);
  const std::vector<double> sampled = first_sweep(points, samples, sampled_s);
  // points off the surface, each no farther from it than its offset
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> offset(-0.004 * diagonal, 0.004 * diagonal);
  std::vector<K::Point_3> off;
  std::vector<double> bound;
  for(const auto& s : BS::sample_model_surface(model, 3000, 7u))
  {
    const double o = offset(rng);
    bound.push_back(std::abs(o));
    off.push_back(s.point + o * s.normal);
  }
  const auto farther = [&](const std::vector<double>& d) {
    std::size_t n = 0;
    for(std::size_t i = 0; i < d.size(); ++i)
      n += d[i] > bound[i] + 1e-9 * diagonal ? 1 : 0;
    return n;
  };
  const std::size_t off_tessellation = farther(first_sweep(off, 0, ignored));
  const std::size_t off_sampled = farther(first_sweep(off, samples, ignored));
  std::ostringstream row;
  row << "| " << name << " | " << model.shape().number_of_components() << " | " << fixed(rms(tessellation), 4) << " | "
      << fixed(rms(sampled), 4) << " | " << fixed(rms(truth), 4) << " | " << fixed(evolution_rms, 4) << " | "
      << fixed(tessellation_s, 2) << " | " << fixed(sampled_s, 2) << " | " << off_tessellation << " | " << off_sampled
      << " |\n";
  return row.str();
}

} // namespace

int main(int argc, char** argv)
{
  std::string csv, markdown;
  std::size_t threads = 1;
  std::size_t seed = BS::Fitting_settings().random_seed;
  double area_weight = BS::Fitting_settings().area_weight;
  double input_scale = 1.;
  bool robust = false, evolve = false, first_sweep = false;
  std::size_t evolution_points = BS::Evolution_settings().maximum_evolution_points;
  BB::Stage_options stages;
  std::size_t runs = BS::Evolution_settings().evolution_runs;
  BS::Split_source split_source = BS::Evolution_settings().split_source;
  for(int i = 1; i < argc; ++i)
  {
    std::optional<BS::Split_source> source;
    if(std::strcmp(argv[i], "--csv") == 0 && i + 1 < argc) csv = argv[++i];
    else if(std::strcmp(argv[i], "--robust") == 0) robust = true;
    else if(std::strcmp(argv[i], "--evolve") == 0) evolve = true;
    else if(std::strcmp(argv[i], "--first-sweep") == 0) first_sweep = true;
    else if(std::strcmp(argv[i], "--threads") == 0 && i + 1 < argc && BB::parse_count(argv[i + 1], threads))
      ++i;
    else if(std::strcmp(argv[i], "--markdown") == 0 && i + 1 < argc) markdown = argv[++i];
    else if(std::strcmp(argv[i], "--seed") == 0 && i + 1 < argc && BB::parse_count(argv[i + 1], seed))
      ++i;
    else if(std::strcmp(argv[i], "--area-weight") == 0 && i + 1 < argc && BB::parse_number(argv[i + 1], area_weight) &&
            area_weight >= 0.)
      ++i;
    else if(std::strcmp(argv[i], "--input-scale") == 0 && i + 1 < argc && BB::parse_number(argv[i + 1], input_scale) &&
            input_scale > 0. && std::isfinite(input_scale))
      ++i;
    else if(std::strcmp(argv[i], "--evolution-points") == 0 && i + 1 < argc &&
            BB::parse_count(argv[i + 1], evolution_points))
      ++i;
    else if(stages.parse(argc, argv, i)) {}
    else if(std::strcmp(argv[i], "--runs") == 0 && i + 1 < argc && BB::parse_count(argv[i + 1], runs) && runs >= 1)
      ++i;
    else if(std::strcmp(argv[i], "--splits") == 0 && i + 1 < argc && (source = BS::split_source_from_name(argv[i + 1])))
    {
      split_source = *source;
      ++i;
    }
    else
    {
      std::cerr << "usage: reproduce_paper [--evolve] [--splits forces|creases|both|branches] [--evolution-points N] [--robust] "
                   "[--threads N] [--seed N] [--area-weight W] " << BB::Stage_options::usage << " [--runs N] [--first-sweep] "
                   "[--input-scale S] [--csv FILE] [--markdown FILE]\n";
      return 2;
    }
  }
  if(first_sweep && !evolve)
  {
    std::cerr << "reproduce_paper: --first-sweep studies evolved models: add --evolve\n";
    return 2;
  }
  const std::string data = BLENDED_SHAPE_DATA_DIR;
  std::vector<Experiment> experiments;
  {
    const Mesh m = to_mesh(BS::make_box_cylinder());
    experiments.push_back({"box/cylinder", "CAD object, one simulated view (default camera, 200x200)", 0,
                           scan(m, BS::default_camera_for(m)), m});
  }
  {
    const Mesh m = to_mesh(BS::make_mug());
    experiments.push_back({"mug (CAD)", "CAD object, one simulated view (default camera, 200x200)", 1,
                           scan(m, BS::default_camera_for(m)), m});
  }
  {
    Experiment e{"mug (real scan)", "bundled PCL stereo scan, one view", 1, {}, std::nullopt};
    BS::read_points(data + "/scans/pcl_mug_scan.xyz", e.points);
    experiments.push_back(std::move(e));
  }
  {
    Mesh m;
    BS::read_triangle_mesh(data + "/meshes/odedstein_human_man.obj", m);
    experiments.push_back({"mannequin (human mesh)", "SMPL body mesh, front view, 90 deg field of view, 240x240", 2,
                           scan(m, front_camera_90(m)), m});
  }
  {
    const Mesh m = to_mesh(BS::make_two_holed_box());
    experiments.push_back({"two-holed box", "CAD object, one simulated view (default camera, 200x200)", 3,
                           scan(m, BS::default_camera_for(m)), m});
  }

  for(Experiment& e : experiments)
    BB::scale_input(input_scale, e.points, e.reference ? &*e.reference : nullptr);

  std::ostringstream md, cs, sweeps;
  md << "Machine: " << BB::machine_description() << "; threads: "
     << (threads == 0 ? std::string("all cores") : std::to_string(threads)) << "; seed: " << seed
     << (input_scale != 1. ? "; input scaled by " + fixed(input_scale, 10) : std::string()) << "; weighting: "
     << (robust ? "robust (Mixture, the default)" : "the paper's least squares") << "; area weight: " << area_weight
     << "; "
     << (evolve ? std::string("fit_blended_shape() (part evolution, splits from ") +
                    BS::split_source_name(split_source) + "; " + stages.description() + "; " +
                    std::to_string(runs) + (runs == 1 ? " run)" : " runs)")
                : std::string("fit_superquadric() (one superquadric)")) << "\n\n"
     << "| data | points | param (paper / ours) | iter (paper / ours: all, on all points) | RMS_1,2,3 % paper | RMS_1,2,3 % ours "
        "| parts (paper / ours) | holes | genus | seconds (ours) | iteration / sweep | Chamfer / diagonal (ours) |\n"
     << "|---|---:|---:|---:|---|---|---:|---:|---:|---:|---:|---:|\n";
  cs << "data,source,points,paper_parameters,parameters,paper_iterations,iterations,iterations_on_all_points,paper_rms1,paper_rms2,paper_rms3,"
        "rms1,rms2,rms3,paper_parts,parts,paper_holes,holes,paper_genus,genus,seconds,iteration_over_sweep,"
        "chamfer_over_diagonal,converged\n";
  std::cout << md.str() << std::flush;
  for(const Experiment& e : experiments)
  {
    const auto np = BS::parameters::area_weight(
      area_weight, BS::parameters::number_of_threads(
                     threads, BS::parameters::robust_weighting(robust ? BS::Robust_weighting::Mixture
                                                                      : BS::Robust_weighting::None,
                                                               CGAL::parameters::random_seed(unsigned(seed)))));
    Fit_figures f;
    std::string chamfer = "-";
    const double diag = BS::testing::bounding_box_diagonal(e.points);
    const Mesh* reference = e.reference ? &*e.reference : nullptr; // (none: no Chamfer distance)
    if(evolve)
    {
      const auto evolution_np = BS::parameters::split_source(
        split_source, stages.named_parameters(BS::parameters::evolution_runs(
                        runs, BS::parameters::maximum_evolution_points(evolution_points, np))));
      const auto r = BS::fit_blended_shape(e.points, BS::parameters::reference_mesh(reference, evolution_np));
      f.metrics = r.metrics;
      f.parts = r.number_of_parts();
      f.holes = r.model.shape().holes().size();
      f.genus = r.model.shape().genus();
      if(first_sweep && r.number_of_parts() > 1)
        sweeps << first_sweep_row(e.name, e.points, r.model, r.metrics.rms, diag, threads);
    }
    else
    {
      const auto r = BS::fit_superquadric(e.points, BS::parameters::reference_mesh(reference, np));
      f.metrics = r.metrics;
      f.iteration_over_sweep = r.metrics.seconds / double((std::max)(r.metrics.iterations, std::size_t(1))) /
                               closest_point_sweep_seconds(e.points, r.meshes);
    }
    const BS::Fit_metrics& m = f.metrics;
    if(m.chamfer_distance)
      chamfer = fixed(*m.chamfer_distance / diag, 4);
    const Paper_row& p = paper[e.paper_row];
    const std::string ratio = f.iteration_over_sweep ? fixed(*f.iteration_over_sweep, 2) : std::string("-");
    std::ostringstream row;
    row << "| " << e.name << " | " << m.number_of_points << " | " << p.parameters << " / " << m.number_of_parameters
        << " | " << p.iterations << " / " << m.iterations << ", " << m.iterations_on_all_points
        << (m.converged ? "" : " (not converged)") << " | "
        << fixed(p.rms[0], 1) << ", " << fixed(p.rms[1], 1) << ", " << fixed(p.rms[2], 1) << " | "
        << fixed(100. * m.relative_rms[0], 1) << ", " << fixed(100. * m.relative_rms[1], 1) << ", "
        << fixed(100. * m.relative_rms[2], 1) << " | " << p.parts << " / " << f.parts << " | " << p.holes << " / "
        << f.holes << " | " << p.genus << " / " << f.genus << " | " << fixed(m.seconds, 2) << " | " << ratio << " | "
        << chamfer << " |\n";
    std::cout << row.str() << std::flush;
    md << row.str();
    cs << '"' << e.name << "\",\"" << e.source << "\"," << m.number_of_points << ',' << p.parameters << ','
       << m.number_of_parameters << ',' << p.iterations << ',' << m.iterations << ','
       << m.iterations_on_all_points << ',' << p.rms[0] << ',' << p.rms[1]
       << ',' << p.rms[2] << ',' << 100. * m.relative_rms[0] << ',' << 100. * m.relative_rms[1] << ','
       << 100. * m.relative_rms[2] << ',' << p.parts << ',' << f.parts << ',' << p.holes << ',' << f.holes << ','
       << p.genus << ',' << f.genus << ',' << m.seconds << ','
       << (f.iteration_over_sweep ? fixed(*f.iteration_over_sweep, 6) : std::string()) << ','
       << (m.chamfer_distance ? fixed(*m.chamfer_distance / diag, 6) : std::string()) << ','
       << (m.converged ? "true" : "false") << '\n';
  }
  md << (evolve ? "\nOurs: part evolution (fit_blended_shape()); holes are not added yet.\n"
                 : "\nOurs: one superquadric (parts 1, holes 0, genus 0): the rows that need parts and holes show "
                   "what a single superquadric achieves.\n");
  if(first_sweep)
  {
    std::ostringstream table;
    table << "\nFirst closest-point sweep of each evolved model with blends (RMS distances in the points' unit; "
             "sampled: Fitting_settings::projection_start_samples "
          << BS::Fitting_settings().projection_start_samples
          << "; true: each point's nearest of 2 million surface samples; evolution: its fit's own, points not "
             "isolated; off: of 3000 points put off the surface by up to 0.4 % of the diagonal, those that end "
             "farther than the surface point they were made from)\n\n"
          << "| data | parts | tessellation alone | sampled | true | evolution | s, tessellation alone | s, sampled "
             "| off, farther: tessellation alone | off, farther: sampled |\n"
          << "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n"
          << sweeps.str();
    std::cout << table.str() << std::flush;
    md << table.str();
  }
  auto write = [](const std::string& file, const std::string& text) {
    try
    {
      BS::internal::write_file_atomically(file, [&](std::ostream& out) { out << text; });
    }
    catch(const std::exception& e)
    {
      std::cerr << "reproduce_paper: " << e.what() << '\n';
      return false;
    }
    return true;
  };
  if(!csv.empty() && !write(csv, cs.str())) return 1;
  if(!markdown.empty() && !write(markdown, md.str())) return 1;
  return 0;
}
