// SPDX-License-Identifier: LGPL-3.0-or-later
// Accuracy, iterations, time and memory of the single-superquadric fit on
// seeded random superellipsoids (a_i in [0.5, 2.5], exponents in [0.3, 1.7],
// random pose), sampled all around or from one view, with Gaussian noise of
// 0.2 % of the bounding-box diagonal, for 2k / 20k / 200k points with the
// default (Gauss-Newton) integrator and 2k points with the explicit one. Prints a Markdown table (also to --output FILE).
//
//   fit_single_superquadric [--quick] [--points N] [--threads N] [--area-weight W] [--output FILE]
//   fit_single_superquadric --equivariance N [--output FILE]
//   fit_single_superquadric --outliers FRACTION --outlier-box FACTOR [--fits N] [--output FILE]
//   fit_single_superquadric --similar-search N [--output FILE]
//   fit_single_superquadric --scanner-views N [--threads N] [--output FILE]
//
// --points N: only the clouds of N points: 2000, 20000 or 200000 as above, or
// any other N (20 fits of each view with the default integrator).
// --threads N: the fits on N threads (Fitting_settings::number_of_threads;
// default 0, all cores): the results are the same, only the times change.
// --area-weight W: Fitting_settings::area_weight (default 0: no area term).
//
// With --equivariance, it fits N random full views of 2000 points twice, as
// sampled and rotated, translated and scaled by 3.7, and reports how far the
// two fits are apart: relative RMS (eq. 14) and surfaces (the second against
// the first, transformed).
//
// With --outliers, it fits N (default 10) random full views of 6000 points of
// which FRACTION are strays spread uniformly over FACTOR times the bounding
// box of the others (the EMS protocol), and reports the RMS distance of the
// true points to the fitted surface over their bounding-box diagonal, the
// seconds and the strays found: one table row.
//
// With --similar-search, it runs the steps of fit_superquadric() (the
// search's best_start(), the full fit, search_similar_basins()) on the N
// single views of 2000 points of the main table (the same seeds) and reports
// how often the search after the full fit is skipped, how often it
// corrects the fit, and whether a skipped one would have corrected it (the
// search run by a search of its own, which cannot skip), with how far each
// fit moved from its start (semi-axes over the largest, exponents).
//
// With --scanner-views, it scans N random superellipsoids (tessellated) with
// the range scanner from a random direction, no noise, no strays: unlike
// synthetic_scan(), whose samples are spread evenly by area, the scanner's
// density follows the view (dense where the surface faces it, sparse where
// it is seen at a slant). Each cloud is fitted with the robust default,
// with the robust default without mending missed surfaces
// (fit_superquadric()'s mend_missed_surfaces) and with least squares; a
// fit is wrong if the RMS of the points' distances to it is over 0.5 % of
// their diagonal or more than 2 % of the points are farther than 1 % of it
// (testing::fits_view()). One table row per kind of fit.
//
// Every fit runs in its own child process, whose peak resident memory is
// reported (points, model meshes, AABB tree and the fit together).
#include "benchmark_util.h"

#include <CGAL/Blended_shape/Blending/Blended_shape_mesh.h>
#include <CGAL/Blended_shape/Fitting/Deformable_blended_model.h>
#include <CGAL/Blended_shape/Fitting/fit_superquadric.h>
#include <CGAL/Blended_shape/Scanning/Range_scan_simulator.h>
#include <blended_shape_testing/compare_superquadrics.h>
#include <blended_shape_testing/equivariance.h>
#include <CGAL/Blended_shape/internal/write_file_atomically.h>
#include <blended_shape_testing/scanner_views.h>
#include <blended_shape_testing/synthetic_scans.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <iomanip>
#include <memory>
#include <iostream>
#include <random>
#include <vector>

namespace BS = CGAL::Blended_shapes;
namespace BB = blended_shape_benchmark;
typedef CGAL::Exact_predicates_inexact_constructions_kernel K;

namespace {

struct Fit_outcome
{
  std::size_t iterations;
  std::size_t iterations_on_all_points;
  double seconds;
  double relative_rms_mean;  // mean of the three eq. 14 figures
  double rms_over_noise;     // RMS / sigma
  double size_error;         // full views: largest |a_fit / a_true - 1|
  double exponent_error;     // full views: largest exponent difference
  bool converged;
};

struct Config
{
  std::size_t points;
  bool single_view;
  BS::Integrator integrator;
  int shapes;
  std::size_t threads;
  double area_weight;
};

Fit_outcome fit_one(const Config& c, unsigned int shape_seed)
{
  std::mt19937_64 rng(shape_seed);
  const auto truth = BS::testing::random_superellipsoid<K>(rng);
  double sigma = 0.;
  const auto pts = BS::testing::synthetic_scan(truth, c.points, c.single_view, 0.002, rng, &sigma);
  const std::size_t limit = c.integrator == BS::Integrator::Explicit ? 3000 : 200;
  const auto r = BS::fit_superquadric(
    pts, BS::parameters::area_weight(c.area_weight, BS::parameters::number_of_threads(
                                                      c.threads, BS::parameters::integrator(c.integrator)))
           .number_of_iterations(limit));
  Fit_outcome o;
  o.iterations = r.metrics.iterations;
  o.iterations_on_all_points = r.metrics.iterations_on_all_points;
  o.seconds = r.metrics.seconds;
  o.relative_rms_mean = (r.metrics.relative_rms[0] + r.metrics.relative_rms[1] + r.metrics.relative_rms[2]) / 3.;
  o.rms_over_noise = r.metrics.rms / sigma;
  const auto cmp = BS::testing::compare_superquadrics(r.model, truth);
  o.size_error = cmp.size_error;
  o.exponent_error = cmp.exponent_error;
  o.converged = r.metrics.converged;
  return o;
}

double median(std::vector<double> v)
{
  std::sort(v.begin(), v.end());
  return v.empty() ? 0. : v[v.size() / 2];
}

// The table to `output` (if any), all or nothing; the exit code.
int write_table(const std::string& output, const std::string& table)
{
  try
  {
    if(!output.empty())
      BS::internal::write_file_atomically(output, [&](std::ostream& out) { out << table; });
  }
  catch(const std::exception& e)
  {
    std::cerr << "fit_single_superquadric: " << e.what() << '\n';
    return 1;
  }
  return 0;
}

// See the header: a Markdown table of how far fits of transformed copies of
// random clouds are apart.
std::string equivariance_table(int cases)
{
  std::ostringstream table;
  table << "Machine: " << BB::machine_description() << "\n\n"
        << "| case | e1 | e2 | relative RMS difference (max of 3, relative) | surface difference / diagonal |\n"
        << "|---:|---:|---:|---:|---:|\n";
  int rms_misses = 0, surface_misses = 0;
  double worst_rms = 0., worst_surface = 0.;
  for(int c = 0; c < cases; ++c)
  {
    std::mt19937_64 rng(9000u + unsigned(c));
    const auto truth = BS::testing::random_superellipsoid<K>(rng);
    const auto pts = BS::testing::synthetic_scan(truth, 2000, false, 0.002, rng);
    const BS::testing::Equivariance_gap gap = BS::testing::equivariance_gap(pts, rng);
    const double rms = *std::max_element(gap.relative_rms.begin(), gap.relative_rms.end());
    const double surface = gap.surface;
    rms_misses += rms > 1e-6 ? 1 : 0;
    surface_misses += surface > 1e-6 ? 1 : 0;
    worst_rms = (std::max)(worst_rms, rms);
    worst_surface = (std::max)(worst_surface, surface);
    const auto e = truth.shape().parameters();
    table << std::setprecision(3) << "| " << c << " | " << e[3] << " | " << e[4] << " | " << rms << " | " << surface
          << " |\n";
  }
  table << "\n" << cases << " cases: relative RMS apart by more than 1e-6 in " << rms_misses << " (worst "
        << std::setprecision(2) << worst_rms << "), surfaces by more than 1e-6 of the diagonal in " << surface_misses
        << " (worst " << worst_surface << ").\n";
  return table.str();
}

struct Outlier_outcome
{
  double inlier_rms_over_diagonal;
  double seconds;
  std::size_t strays_found; // of the strays injected, those judged stray
  std::size_t inliers_flagged;
};

// See the header: one row for `fits` clouds with `fraction` strays over `box` times the box.
std::string outlier_row(double fraction, double box, int fits, std::size_t threads)
{
  typedef BS::Deformable_model<BS::Superquadric_ellipsoid<K>> Model;
  const std::size_t total = 6000, strays = std::size_t(std::lround(fraction * double(total)));
  std::vector<double> rms, seconds;
  double found = 0., flagged = 0.;
  for(int f = 0; f < fits; ++f)
  {
    double mib = 0.;
    const Outlier_outcome o = BB::run_in_child<Outlier_outcome>([&] {
      std::mt19937_64 rng(5000u + unsigned(f));
      const Model truth = BS::testing::random_superellipsoid<K>(rng);
      const auto inliers = BS::testing::synthetic_scan(truth, total - strays, false, 0.002, rng);
      auto pts = inliers;
      BS::testing::add_stray_points(pts, strays, box, rng);
      const auto r = BS::fit_superquadric(pts, BS::parameters::number_of_threads(threads));
      BS::Deformable_model_fitter<Model> probe(inliers, r.model); // the true points' distances to the fit
      Outlier_outcome out{std::sqrt(probe.mean_squared_distance(true)) / BS::testing::bounding_box_diagonal(inliers),
                          r.metrics.seconds, 0, 0};
      for(std::size_t i : r.stray_points)
        ++(i >= inliers.size() ? out.strays_found : out.inliers_flagged);
      return out;
    }, mib);
    rms.push_back(o.inlier_rms_over_diagonal);
    seconds.push_back(o.seconds);
    found += double(o.strays_found) / fits;
    flagged += double(o.inliers_flagged) / fits;
  }
  std::ostringstream row;
  row << std::fixed << "| " << std::setprecision(0) << 100. * fraction << " % | " << box << "x | " << fits << " | "
      << std::setprecision(3) << 100. * median(rms) << " / " << 100. * *std::max_element(rms.begin(), rms.end())
      << " | " << std::setprecision(2) << median(seconds) << " / " << *std::max_element(seconds.begin(), seconds.end())
      << " | " << std::setprecision(0) << found << " of " << strays << " | " << std::setprecision(1) << flagged
      << " |\n";
  return row.str();
}

// See the header: the second similar-superquadric search of
// Superquadric_multistart_search, skipped or run, on the single views of
// 2000 points of the main table.
std::string similar_search_table(int views)
{
  typedef BS::Superquadric_multistart_search<K, std::vector<K::Point_3>, CGAL::Identity_property_map<K::Point_3>> Search;
  const BS::Fitting_settings settings = BS::settings_from_named_parameters(BS::parameters::number_of_threads(1));
  BS::Default_fitting_visitor visitor;
  int skipped = 0, corrected = 0, missed = 0;
  double skipped_axes = 0., skipped_exponents = 0.; // the largest moves of the skipped fits
  std::ostringstream corrections;
  for(int v = 0; v < views; ++v)
  {
    const unsigned int seed = 1000u + unsigned(v); // as the main table's fits
    std::mt19937_64 rng(seed);
    const auto truth = BS::testing::random_superellipsoid<K>(rng);
    const auto pts = BS::testing::synthetic_scan(truth, 2000, true, 0.002, rng);
    Search search(pts, {}, settings);
    const auto start = search.best_start(BS::initialize_from_trimmed_moments(pts), visitor, {});
    auto fitter = std::make_unique<Search::Fitter>(pts, start, settings);
    BS::Fitting_status status = fitter->run(visitor, {});
    const auto q0 = start.shape().parameters(), q1 = fitter->model().shape().parameters();
    const double axes = (q1.head<3>() - q0.head<3>()).cwiseAbs().maxCoeff() / q0.head<3>().maxCoeff();
    const double exponents = (q1.tail<2>() - q0.tail<2>()).cwiseAbs().maxCoeff();
    const auto* fitted = fitter.get();
    const std::size_t before = search.candidate_iterations();
    fitter = search.search_similar_basins(std::move(fitter), status, visitor, {});
    const bool changed = fitter.get() != fitted;
    if(search.candidate_iterations() == before) // skipped
    {
      ++skipped;
      skipped_axes = (std::max)(skipped_axes, axes);
      skipped_exponents = (std::max)(skipped_exponents, exponents);
      Search alone(pts, {}, settings);
      missed += alone.search_similar_basins(std::move(fitter), status, visitor, {}).get() != fitted ? 1 : 0;
      continue;
    }
    if(changed)
    {
      ++corrected;
      corrections << (corrected > 1 ? "; " : "") << "seed " << seed << " (moved " << std::setprecision(2) << axes
                  << ", " << exponents << ")";
    }
  }
  std::ostringstream table;
  table << "Machine: " << BB::machine_description() << "; one thread\n\n"
        << "| single views (2000 points) | second search skipped | corrected by it | skipped but correctable "
           "| largest move of a skipped fit (semi-axes / largest, exponents) | corrected fits (seed: move) |\n"
        << "|---:|---:|---:|---:|---:|---|\n"
        << "| " << views << " | " << skipped << " | " << corrected << " | " << missed << " | " << std::setprecision(2)
        << skipped_axes << ", " << skipped_exponents << " | " << corrections.str() << " |\n";
  return table.str();
}

// See the header: the robust default, unmended and mended, and least
// squares on range scans of random superellipsoids from random directions.
std::string scanner_view_table(int views, std::size_t threads)
{
  // 0: least squares, 1: the robust default, 2: robust without mending missed surfaces
  int wrong[3] = {0, 0, 0};
  std::vector<double> seconds[3];
  std::ostringstream wrong_seeds[3];
  double points = 0.;
  for(int v = 0; v < views; ++v)
  {
    const unsigned int seed = 7000u + unsigned(v);
    const std::vector<K::Point_3> pts = BS::testing::scanner_view<K>(seed).points;
    points += double(pts.size()) / views;
    for(int robust = 0; robust < 3; ++robust)
    {
      const auto r = BS::fit_superquadric(
        pts, BS::parameters::robust_weighting(robust ? BS::Fitting_settings().robust_weighting : BS::Robust_weighting::None,
                                              BS::parameters::mend_missed_surfaces(robust != 2, BS::parameters::number_of_threads(threads))));
      seconds[robust].push_back(r.metrics.seconds);
      if(!BS::testing::fits_view(pts, r.model))
        wrong_seeds[robust] << (wrong[robust]++ > 0 ? ", " : "") << seed;
    }
  }
  std::ostringstream table;
  table << "Machine: " << BB::machine_description() << "; threads: " << (threads == 0 ? std::string("all cores") : std::to_string(threads)) << "; " << views
        << " random superellipsoids scanned from a random direction (200x200 pixels), " << std::fixed
        << std::setprecision(0) << points << " points on average\n\n"
        << "| fit | fits | wrong | seconds (median / max) | wrong fits (seeds) |\n|---|---:|---:|---:|---|\n";
  const char* names[3] = {"least squares", "robust (the default)", "robust, `mend_missed_surfaces(false)`"};
  for(int robust : {1, 2, 0})
    table << "| " << names[robust] << " | " << views << " | " << wrong[robust]
          << " | " << std::setprecision(2) << median(seconds[robust]) << " / "
          << *std::max_element(seconds[robust].begin(), seconds[robust].end()) << " | " << wrong_seeds[robust].str()
          << " |\n";
  return table.str();
}

} // namespace

int main(int argc, char** argv)
{
  bool quick = false;
  int equivariance = 0, fits = 10, similar_search = 0, scanner_views = 0;
  double outliers = -1., outlier_box = 2.;
  std::size_t only_points = 0, threads = 0, count = 0;
  double area_weight = BS::Fitting_settings().area_weight;
  std::string output;
  for(int i = 1; i < argc; ++i)
  {
    if(std::strcmp(argv[i], "--quick") == 0) quick = true;
    else if(std::strcmp(argv[i], "--output") == 0 && i + 1 < argc) output = argv[++i];
    else if(std::strcmp(argv[i], "--points") == 0 && i + 1 < argc && BB::parse_count(argv[i + 1], count) && count > 0)
      only_points = count, ++i;
    else if(std::strcmp(argv[i], "--threads") == 0 && i + 1 < argc && BB::parse_count(argv[i + 1], threads))
      ++i;
    else if(std::strcmp(argv[i], "--area-weight") == 0 && i + 1 < argc && BB::parse_number(argv[i + 1], area_weight) &&
            area_weight >= 0.)
      ++i;
    else if(std::strcmp(argv[i], "--equivariance") == 0 && i + 1 < argc && BB::parse_count(argv[i + 1], count) &&
            count > 0)
      equivariance = int(count), ++i;
    else if(std::strcmp(argv[i], "--outliers") == 0 && i + 1 < argc && std::atof(argv[i + 1]) >= 0. &&
            std::atof(argv[i + 1]) < 1.)
      outliers = std::atof(argv[++i]);
    else if(std::strcmp(argv[i], "--outlier-box") == 0 && i + 1 < argc && std::atof(argv[i + 1]) >= 1.)
      outlier_box = std::atof(argv[++i]);
    else if(std::strcmp(argv[i], "--fits") == 0 && i + 1 < argc && BB::parse_count(argv[i + 1], count) && count > 0)
      fits = int(count), ++i;
    else if(std::strcmp(argv[i], "--similar-search") == 0 && i + 1 < argc && BB::parse_count(argv[i + 1], count) &&
            count > 0)
      similar_search = int(count), ++i;
    else if(std::strcmp(argv[i], "--scanner-views") == 0 && i + 1 < argc && BB::parse_count(argv[i + 1], count) &&
            count > 0)
      scanner_views = int(count), ++i;
    else
    {
      std::cerr << "usage: fit_single_superquadric [--quick] [--points N] [--threads N] [--area-weight W] [--output FILE]\n"
                   "       fit_single_superquadric --equivariance N [--output FILE]\n"
                   "       fit_single_superquadric --outliers FRACTION --outlier-box FACTOR [--fits N] "
                   "[--threads N] [--output FILE]\n"
                   "       fit_single_superquadric --similar-search N [--output FILE]\n"
                   "       fit_single_superquadric --scanner-views N [--threads N] [--output FILE]\n";
      return 2;
    }
  }
  if(outliers >= 0.)
  {
    const std::string table = "| strays | box | fits | true points' RMS / diagonal, % (median / max) "
                              "| seconds (median / max) | strays found (mean) | inliers judged stray (mean) |\n"
                              "|---:|---:|---:|---:|---:|---:|---:|\n" +
                              outlier_row(outliers, outlier_box, fits, threads);
    std::cout << "Machine: " << BB::machine_description() << "\n\n" << table;
    return write_table(output, table);
  }
  if(scanner_views > 0)
  {
    const std::string table = scanner_view_table(scanner_views, threads);
    std::cout << table;
    return write_table(output, table);
  }
  if(similar_search > 0)
  {
    const std::string table = similar_search_table(similar_search);
    std::cout << table;
    return write_table(output, table);
  }
  if(equivariance > 0)
  {
    const std::string table = equivariance_table(equivariance);
    std::cout << table;
    return write_table(output, table);
  }
  std::vector<Config> configs;
  std::vector<std::size_t> sizes = {2000, 20000, 200000};
  if(only_points != 0 && std::find(sizes.begin(), sizes.end(), only_points) == sizes.end())
    sizes = {only_points};
  for(std::size_t n : sizes)
  {
    if((quick && n > 20000) || (only_points != 0 && n != only_points)) continue;
    // 100 fits at 2k points: enough to see how often a fit ends in a wrong
    // rest state (the last column), which is about 1 in 100 for single views.
    // Other sizes (--points N): 20 fits.
    const int shapes = n == 2000 ? 100 : (n == 20000 ? 4 : (n == 200000 ? 2 : 20));
    for(bool single : {false, true})
    {
      configs.push_back({n, single, BS::Integrator::Gauss_newton, quick ? 2 : shapes, threads, area_weight});
      // The explicit integrator needs 1000 to 2000 iterations: at 2k points
      // that already takes a minute a fit, at 20k about ten.
      if(n == 2000)
        configs.push_back({n, single, BS::Integrator::Explicit, quick ? 1 : 3, threads, area_weight});
    }
  }
  std::ostringstream table;
  table << "Machine: " << BB::machine_description() << "; threads: "
        << (threads == 0 ? std::string("all cores") : std::to_string(threads)) << "; area weight: " << area_weight
        << "\n\n"
        << "| points | view | integrator | fits | iterations (mean) | on all points (mean) | ms / iteration | total ms (median / max) "
           "| peak MiB (max) | relative RMS, mean of 3 (%) | RMS / noise sigma (max) | a error (max %) "
           "| e error (max) | RMS > 1.2 sigma |\n"
        << "|---:|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
  std::cout << table.str() << std::flush;
  for(const Config& c : configs)
  {
    std::vector<double> seconds, per_iteration, rel, ratio, size_err, expo_err;
    double iterations = 0., on_all_points = 0., peak = 0.;
    int misses = 0;
    for(int s = 0; s < c.shapes; ++s)
    {
      double mib = 0.;
      const Fit_outcome o = BB::run_in_child<Fit_outcome>([&] { return fit_one(c, 1000u + unsigned(s)); }, mib);
      peak = (std::max)(peak, mib);
      iterations += double(o.iterations) / c.shapes;
      on_all_points += double(o.iterations_on_all_points) / c.shapes;
      seconds.push_back(o.seconds);
      per_iteration.push_back(o.seconds / double((std::max)(o.iterations, std::size_t(1))));
      rel.push_back(o.relative_rms_mean);
      ratio.push_back(o.rms_over_noise);
      size_err.push_back(o.size_error);
      expo_err.push_back(o.exponent_error);
      misses += o.rms_over_noise > 1.2 ? 1 : 0;
    }
    std::ostringstream row;
    row << std::fixed << "| " << c.points << " | " << (c.single_view ? "single" : "full") << " | "
        << (c.integrator == BS::Integrator::Explicit ? "explicit" : "Gauss-Newton") << " | " << c.shapes << " | "
        << std::setprecision(1) << iterations << " | " << on_all_points << " | " << std::setprecision(2)
        << 1000. * median(per_iteration)
        << " | " << std::setprecision(0) << 1000. * median(seconds) << " / "
        << 1000. * *std::max_element(seconds.begin(), seconds.end()) << " | " << peak << " | "
        << std::setprecision(3) << 100. * median(rel) << " | " << std::setprecision(2)
        << *std::max_element(ratio.begin(), ratio.end()) << " | ";
    if(c.single_view)
      row << "- | - | ";
    else
      row << std::setprecision(2) << 100. * *std::max_element(size_err.begin(), size_err.end()) << " | "
          << std::setprecision(3) << *std::max_element(expo_err.begin(), expo_err.end()) << " | ";
    row << misses << " |\n";
    std::cout << row.str() << std::flush;
    table << row.str();
  }
  return write_table(output, table.str());
}
