// SPDX-License-Identifier: LGPL-3.0-or-later
// blended_fit: fit a blended model to a point cloud (part evolution,
// fit_blended_shape()) and report it as JSON.
#include "internal/command_line.h"

// The package's umbrella header, as a user's program includes it (this
// tool uses most of it, so the check that it compiles on its own costs
// little here; the tests include only what they use).
#include <CGAL/Blended_shape.h>
#include <CGAL/Blended_shape/internal/write_file_atomically.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <filesystem>
#include <iomanip>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>
#include <string>

namespace BS = CGAL::Blended_shapes;
namespace tools = blended_shape_tools;
typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
typedef BS::Blended_fit_result<K> Result;
typedef Result::Model Model;
typedef BS::internal::Json Json;

namespace {

// The usage text, its defaults those of the settings the tool starts from.
std::string usage()
{
  const BS::Evolution_settings evolution;
  const BS::Fitting_settings fitting;
  const auto n = [](std::size_t value) { return std::to_string(value); };
  return std::string(
    "Usage: blended_fit INPUT [options]\n"
    "Fit a blended-shape model to the point cloud INPUT (.xyz .pts .pwn .txt .ply .off .obj .stl)\n"
    "and print a JSON summary on stdout: one superquadric first, then parts blended in where\n"
    "the data has pieces between concave creases, each kept only if it pays for its parameters\n"
    "(the JSON's 'evolution' lists every split tried).\n"
    "\n"
    "Options:\n"
    "  --json FILE          write the JSON summary to FILE instead of stdout\n"
    "  --mesh FILE          write the model's component pieces (sec. 3.3 of the paper) as\n"
    "                       FILE.ply (binary, faces coloured by component) or FILE.off\n"
    "  --hierarchy FILE     write the blending hierarchy as Graphviz DOT\n"
    "  --model FILE         write the model as JSON: its pose and its blended shape (a model\n"
    "                       file as read_blended_shape() reads, in the model's own frame)\n"
    "  --no-split           one superquadric: no part evolution\n"
    "  --max-parts N        at most N parts (default " + n(evolution.maximum_number_of_parts) + "; 1 is --no-split)\n"
    "  --splits SOURCE      where splits come from: creases (default: a part fitted to each\n"
    "                       piece of the data between concave creases, blended in gradually),\n"
    "                       forces (the force analysis at rest, sec. 5.4 of the paper), both,\n"
    "                       or branches (the limbs of the data joined one at a time from its\n"
    "                       centre, each offered as a part)\n"
    "  --evolution-points N decide the splits on at most N of the points (default " + n(evolution.maximum_evolution_points) + "; 0:\n"
    "                       all), then fit the final model to all of them\n"
    "  --blend-stages N     a crease split's part comes in over N stages (default " + n(evolution.blend_stages) + "; 1: at once)\n"
    "  --stage-iterations N iteration limit of each of those stages but the last (default " + n(evolution.intermediate_stage_iterations) + ")\n"
    "  --first-split-stages N, --first-split-stage-iterations N\n"
    "                       the same for the first split (a part on a one-part base;\n"
    "                       defaults " + n(evolution.first_split_blend_stages) + " and " + n(evolution.first_split_stage_iterations) + ")\n"
    "  --runs N             evolve N times, run r on the points scaled by 1 + r 2^-23 about their\n"
    "                       centre (other rounding, other paths; default " + n(evolution.evolution_runs) + "), and keep the run\n"
    "                       whose model describes the points in the fewest nats (see the manual,\n"
    "                       Inputs changed by 1e-7); the runs go on concurrently on the --threads\n"
    "                       (on one core the time grows with N)\n"
    "  --area-weight W      weight of the model's surface area in every fit (default 0: none;\n"
    "                       0.3 keeps the surface from growing where no point is, see the\n"
    "                       manual, Compact Models)\n"
    "  --trace DIR          write, as the fit goes, the model after each split tried (kept or\n"
    "                       undone), each part removed and a revert, then the first fit and the\n"
    "                       final model, to DIR (created if missing): NN_KIND.ply (pieces\n"
    "                       coloured by component) and NN_KIND.dot (hierarchy), KIND first_fit,\n"
    "                       split, undo, remove, revert or final (with --runs, every run's in turn)\n"
    "  --no-holes           do not add holes (this release never does)\n"
    "  --max-iterations N   iteration limit of each fit to rest (default " + n(fitting.maximum_iterations) + ")\n"
    "  --seed N             random seed for the point subsets (default " + n(fitting.random_seed) + ")\n"
    "  --strays FILE        write the indices (from 0, in input order) of the points the model\n"
    "                       leaves out (stray or isolated), one a line\n"
    "  --reference MESH     a mesh of the scanned object (.off .obj .ply .stl): the JSON then\n"
    "                       gives the model's symmetric Chamfer distance to it (in the\n"
    "                       points' unit)\n"
    "  --robust             a one-part result down-weights stray points (the default: a Gaussian\n"
    "                       and uniform mixture, see the manual); evolution fits the points that\n"
    "                       are not isolated by least squares\n"
    "  --no-robust          the paper's plain least squares: every point pulls alike\n"
    "  --explicit           use the paper's explicit integrator instead of Gauss-Newton\n"
    "  --threads N          threads of the fit (default 0: all cores); the result does not depend on it\n"
    "  --quiet              no progress on stderr\n"
    "  --help               this text\n"
    "Exit code 0 on success, 1 on a failure (unreadable input, ...), 2 on a command-line mistake.\n"
    "No output file is written unless the fit succeeds (the --trace files are written as it goes).\n");
}

// JSON numbers must be finite, and a model's always are: anything else is a bug.
Json number(double x)
{
  if(!std::isfinite(x))
    throw std::runtime_error("internal error: a non-finite number in the result");
  return Json(x);
}

Json numbers(const double* x, std::size_t n)
{
  Json a = Json::array();
  for(std::size_t i = 0; i < n; ++i)
    a.push_back(number(x[i]));
  return a;
}

// The model: its pose (x = c + R s) and its blended shape in its own frame.
Json model_json(const Model& model)
{
  Json pose = Json::object();
  pose["translation"] = numbers(model.translation().data(), 3);
  pose["quaternion_wxyz"] = numbers(model.quaternion().data(), 4);
  Json m = Json::object();
  m["pose"] = pose;
  m["shape"] = BS::internal::blended_shape_to_json(model.shape());
  return m;
}

Json event_json(const BS::Evolution_event& e)
{
  Json j = Json::object();
  j["kind"] = BS::evolution_event_name(e.kind);
  j["iteration"] = double(e.iteration);
  j["component"] = double(e.component);
  // (a removal and a revert have no proposal)
  if(e.kind == BS::Evolution_event_kind::Split || e.kind == BS::Evolution_event_kind::Undo)
  {
    j["new_component"] = double(e.new_component);
    if(e.proposal.segment != BS::Split_proposal::none) // (a crease segment's proposal has no boundary)
      j["segment"] = double(e.proposal.segment);
    else
      j["boundary"] = double(e.boundary);
    Json region = Json::object();
    region["chart"] = double(e.proposal.chart);
    region["ellipse"] = numbers(e.proposal.region.data(), std::size_t(e.proposal.region.size()));
    region["half_width"] = number(e.proposal.half_width);
    j["region"] = region;
  }
  j["rms_before"] = number(e.rms_before);
  j["rms_after"] = number(e.rms_after);
  j["description_length_before"] = number(e.description_length_before);
  j["description_length_after"] = number(e.description_length_after);
  j["accepted"] = e.accepted();
  return j;
}

// How flat the points are (Fit_metrics::degeneracy).
const char* degeneracy_name(BS::Point_cloud_degeneracy d)
{
  switch(d)
  {
    case BS::Point_cloud_degeneracy::Coplanar: return "coplanar";
    case BS::Point_cloud_degeneracy::Collinear: return "collinear";
    default: return "none";
  }
}

const char* end_of_evolution(const Result& r, bool no_split)
{
  if(no_split) return "not run (--no-split)";
  if(r.status.aborted) return "stopped";
  if(r.status.part_limit_reached) return "part limit reached";
  if(r.status.target_reached) return "target accuracy reached";
  return "no split paid for its parameters";
}

std::string summary_text(const Result& r, const std::string& input, std::size_t number_of_points, bool no_split,
                         std::size_t max_parts, BS::Split_source split_source)
{
  const BS::Fit_metrics& m = r.metrics;
  Json s = Json::object();
  s["input"] = input;
  s["points"] = double(number_of_points); // (the first fit's may be those of evolution's sample)
  s["parameters"] = double(r.model.number_of_parameters());
  s["iterations"] = double(m.iterations);
  s["iterations_on_all_points"] = double(m.iterations_on_all_points);
  s["converged"] = m.converged;
  s["relative_rms"] = numbers(m.relative_rms.data(), 3);
  s["rms"] = number(m.rms);
  s["rms_over_bbox_diagonal"] = number(m.rms_over_bbox_diagonal);
  s["stray_points"] = double(r.stray_points.size());
  s["degeneracy"] = degeneracy_name(m.degeneracy);
  if(m.chamfer_distance) // (with --reference)
    s["chamfer_distance"] = number(*m.chamfer_distance);
  s["parts"] = double(r.number_of_parts());
  s["holes"] = double(r.model.shape().holes().size());
  s["genus"] = double(r.model.shape().genus());
  Json evolution = Json::object();
  evolution["splits_enabled"] = !no_split;
  evolution["holes_enabled"] = false;
  evolution["maximum_parts"] = double(max_parts);
  evolution["split_source"] = BS::split_source_name(split_source);
  evolution["ended"] = end_of_evolution(r, no_split);
  evolution["splits_kept"] = double(r.number_of_splits());
  evolution["runs"] = double(r.run_description_lengths.size());
  evolution["run_kept"] = double(r.evolution_run);
  Json lengths = Json::array();
  for(double l : r.run_description_lengths)
    lengths.push_back(number(l));
  evolution["run_description_lengths"] = lengths;
  Json events = Json::array();
  for(const BS::Evolution_event& e : r.events)
    events.push_back(event_json(e));
  evolution["events"] = events;
  s["evolution"] = evolution;
  s["seconds"] = number(m.seconds);
  s["model"] = model_json(r.model);
  std::ostringstream out;
  BS::internal::write_json(out, s);
  return out.str();
}

BS::Blended_shape_pieces<K> pieces_of(const Model& model)
{
  return BS::Blended_shape_pieces<K>(model.shape(), 24, [&model](const K::Point_3& p) { return model.placed(p); });
}

// `model`'s pieces and hierarchy as DIR/NN_KIND.ply and DIR/NN_KIND.dot.
void write_trace(const std::string& dir, std::size_t index, const std::string& kind, const Model& model)
{
  std::ostringstream name;
  name << dir << '/' << std::setw(2) << std::setfill('0') << index << '_' << kind;
  // ASCII: easy to read for scripts (scripts/render_trace.py)
  BS::write_blended_shape_pieces_ply(name.str() + ".ply", pieces_of(model), CGAL::parameters::use_binary_mode(false));
  BS::internal::write_file_atomically(name.str() + ".dot",
                                      [&](std::ostream& o) { BS::write_blending_hierarchy_dot(o, model.shape()); });
}

// Progress on stderr (unless quiet) and the trace (if a directory is given).
struct Reporter : BS::Default_evolution_visitor
{
  bool quiet = false;
  std::string trace;
  // the events of every run (--runs), counted across the copies the fit makes of its visitor
  std::shared_ptr<std::size_t> events = std::make_shared<std::size_t>(0);
  std::size_t parts = 1;

  void on_phase(BS::Fitting_phase p, std::size_t it) const
  {
    if(!quiet)
      std::cerr << "blended_fit: phase " << BS::phase_name(p) << " (iteration " << it << ")\n";
  }
  void on_iteration(std::size_t it, double energy, std::size_t n) const
  {
    if(!quiet)
      std::cerr << "blended_fit: iteration " << it << "  energy " << energy << "  points " << n << "  parts " << parts
                << "  holes 0\n";
  }
  void on_evolution_phase(BS::Evolution_phase p, std::size_t n)
  {
    parts = n; // the iterations that follow fit a model of n parts (a split model's, say)
    if(!quiet)
      std::cerr << "blended_fit: part evolution: " << BS::evolution_phase_name(p) << " (" << n
                << (n == 1 ? " part" : " parts") << ")\n";
  }
  template <class M>
  void on_split(const BS::Evolution_event& e, const M& model) { event(e, model); }
  template <class M>
  void on_undo(const BS::Evolution_event& e, const M& model) { event(e, model); }
  template <class M>
  void on_remove(const BS::Evolution_event& e, const M& model) { event(e, model); }

private:
  void event(const BS::Evolution_event& e, const Model& model)
  {
    parts = model.shape().number_of_components();
    const std::size_t index = ++*events;
    if(!quiet)
      std::cerr << "blended_fit: event " << index << ": " << BS::evolution_event_name(e.kind) << " of component "
                << e.component << (e.accepted() ? " kept" : "") << " (RMS " << e.rms_before << " -> " << e.rms_after
                << ", description length " << e.description_length_before << " -> " << e.description_length_after
                << "); " << parts << (parts == 1 ? " part" : " parts") << "\n";
    if(!trace.empty())
      write_trace(trace, index, BS::evolution_event_name(e.kind), model);
  }
};

} // namespace

int main(int argc, char** argv)
{
  const auto options = tools::known_options({"--json", "--mesh", "--hierarchy", "--model", "--max-iterations", "--seed",
                                              "--threads", "--strays", "--reference", "--max-parts", "--trace",
                                              "--evolution-points", "--splits", "--area-weight", "--blend-stages",
                                              "--stage-iterations", "--first-split-stages",
                                              "--first-split-stage-iterations", "--runs"},
                                             {"--no-split", "--no-holes", "--quiet", "--robust", "--no-robust", "--explicit"});
  return tools::run_tool("blended_fit", usage(), argc, argv, options, [](const tools::Command_line& line) {
    std::string input, json, mesh, hierarchy, model_file, strays, trace, reference_file;
    bool no_split = false, quiet = false, robust = true, explicit_integrator = false, max_parts_given = false;
    std::size_t iterations = BS::Fitting_settings().maximum_iterations, threads = 0, max_parts = BS::Evolution_settings().maximum_number_of_parts;
    std::size_t evolution_points = BS::Evolution_settings().maximum_evolution_points;
    std::size_t blend_stages = BS::Evolution_settings().blend_stages;
    std::size_t stage_iterations = BS::Evolution_settings().intermediate_stage_iterations;
    std::size_t first_split_stages = BS::Evolution_settings().first_split_blend_stages;
    std::size_t first_split_stage_iterations = BS::Evolution_settings().first_split_stage_iterations;
    std::size_t runs = BS::Evolution_settings().evolution_runs;
    unsigned int seed = BS::Fitting_settings().random_seed;
    double area_weight = BS::Fitting_settings().area_weight;
    BS::Split_source split_source = BS::Evolution_settings().split_source;
    for(const tools::Option& o : line.options)
    {
      const std::string& a = o.flag;
      if(a == "--json") json = o.value;
      else if(a == "--mesh") mesh = o.value;
      else if(a == "--hierarchy") hierarchy = o.value;
      else if(a == "--model") model_file = o.value;
      else if(a == "--trace") trace = o.value;
      else if(a == "--no-split") no_split = true;
      else if(a == "--quiet") quiet = true;
      else if(a == "--robust") robust = true;
      else if(a == "--no-robust") robust = false;
      else if(a == "--strays") strays = o.value;
      else if(a == "--reference") reference_file = o.value;
      else if(a == "--explicit") explicit_integrator = true;
      else if(a == "--max-parts")
      {
        max_parts = std::size_t(tools::parse_integer_in(a, o.value, 1, 1000));
        max_parts_given = true;
      }
      else if(a == "--splits")
      {
        const std::optional<BS::Split_source> source = BS::split_source_from_name(o.value);
        if(!source)
          throw tools::Usage_error("--splits must be forces, creases, both or branches, not '" + o.value + "'");
        split_source = *source;
      }
      else if(a == "--area-weight")
      {
        area_weight = tools::parse_number(a, o.value);
        if(!(area_weight >= 0.) || !std::isfinite(area_weight))
          throw tools::Usage_error("--area-weight must be a finite number >= 0");
      }
      else if(a == "--blend-stages")
        blend_stages = std::size_t(tools::parse_integer_in(a, o.value, 1, 100));
      else if(a == "--stage-iterations")
        stage_iterations = std::size_t(tools::parse_integer_in(a, o.value, 1, 1000000));
      else if(a == "--first-split-stages")
        first_split_stages = std::size_t(tools::parse_integer_in(a, o.value, 1, 100));
      else if(a == "--first-split-stage-iterations")
        first_split_stage_iterations = std::size_t(tools::parse_integer_in(a, o.value, 1, 1000000));
      else if(a == "--runs")
        runs = std::size_t(tools::parse_integer_in(a, o.value, 1, 1000));
      else if(a == "--evolution-points")
      {
        evolution_points = std::size_t(tools::parse_integer(a, o.value));
        if(evolution_points != 0 && evolution_points < BS::minimum_evolution_points)
          throw tools::Usage_error("--evolution-points must be 0 (all points) or at least " +
                                   std::to_string(BS::minimum_evolution_points));
      }
      else if(a == "--max-iterations")
        iterations = std::size_t(tools::parse_integer_in(a, o.value, 1, 1000000));
      else if(a == "--threads")
        threads = std::size_t(tools::parse_integer_in(a, o.value, 0, 4096, "0: all cores"));
      else if(a == "--seed")
        seed = static_cast<unsigned int>(tools::parse_integer_in(a, o.value, 0, 0xffffffffu, "32 bits"));
    }
    for(const std::string& a : line.operands)
      if(input.empty()) input = a;
      else throw tools::Usage_error("more than one input file ('" + input + "' and '" + a + "')");
    if(input.empty())
      throw tools::Usage_error("no input point cloud given");
    if(!mesh.empty() && tools::extension_of(mesh) != "ply" && tools::extension_of(mesh) != "off")
      throw tools::Usage_error("--mesh: '" + mesh + "' must end in .ply or .off");
    if(no_split && max_parts_given && max_parts != 1)
      throw tools::Usage_error("--no-split and --max-parts " + std::to_string(max_parts) + " contradict; give one");
    if(no_split)
      max_parts = 1;
    tools::check_files({{"input", input}, {"--reference", reference_file}},
                       {{"--json", json}, {"--mesh", mesh}, {"--hierarchy", hierarchy}, {"--model", model_file},
                        {"--strays", strays}});

    // (the reference first: a mesh it cannot read ends the run before the points are read)
    std::optional<CGAL::Surface_mesh<K::Point_3>> reference;
    if(!reference_file.empty())
    {
      reference.emplace();
      BS::read_triangle_mesh(reference_file, *reference);
    }
    std::vector<K::Point_3> points;
    const BS::Read_report read = BS::read_points(input, points);
    if(!quiet)
      std::cerr << "blended_fit: read " << read.points_read << " points from '" << input << "'"
                << (read.non_finite_dropped ? " (dropped " + std::to_string(read.non_finite_dropped) +
                                                " with non-finite coordinates)" : std::string()) << "\n";
    if(!trace.empty())
    {
      std::error_code ec;
      std::filesystem::create_directories(trace, ec);
      if(!std::filesystem::is_directory(trace))
        throw std::runtime_error("--trace: cannot create the directory '" + trace + "'" +
                                 (ec ? " (" + ec.message() + ")" : std::string()) + "; check the path and permissions");
    }
    Reporter reporter;
    reporter.quiet = quiet;
    reporter.trace = trace;
    const Result result = BS::fit_blended_shape(
      points,
      BS::parameters::reference_mesh(reference ? &*reference : nullptr,
      BS::parameters::split_source(split_source,
      BS::parameters::blend_stages(blend_stages,
      BS::parameters::intermediate_stage_iterations(stage_iterations,
      BS::parameters::first_split_blend_stages(first_split_stages,
      BS::parameters::first_split_stage_iterations(first_split_stage_iterations,
      BS::parameters::evolution_runs(runs,
      BS::parameters::area_weight(area_weight,
      BS::parameters::maximum_evolution_points(evolution_points,
        BS::parameters::maximum_number_of_parts(max_parts,
        BS::parameters::number_of_threads(threads,
        BS::parameters::robust_weighting(robust ? BS::Robust_weighting::Mixture : BS::Robust_weighting::None,
        BS::parameters::integrator(explicit_integrator ? BS::Integrator::Explicit : BS::Integrator::Gauss_newton)))))))))))))
        .number_of_iterations(iterations)
        .random_seed(seed)
        .visitor(reporter));
    if(!trace.empty())
    {
      write_trace(trace, 0, "first_fit", BS::make_blended_model(result.first_fit.model));
      write_trace(trace, *reporter.events + 1, "final", result.model);
    }
    // Not progress: a note on the result, also with --quiet.
    const BS::Point_cloud_degeneracy flat = result.metrics.degeneracy;
    if(flat != BS::Point_cloud_degeneracy::None)
      std::cerr << "blended_fit: note: the points are " << degeneracy_name(flat) << " (to 1e-6 of their extent): "
                << (flat == BS::Point_cloud_degeneracy::Coplanar
                      ? "the model is a flat superquadric, its thickness at the lower bound"
                      : "the model is a needle, its two smaller semi-axes at the lower bound; no surface is "
                        "defined by points on a line")
                << "\n";
    if(!quiet)
      std::cerr << "blended_fit: " << result.number_of_parts() << (result.number_of_parts() == 1 ? " part" : " parts")
                << ", genus " << result.model.shape().genus() << ", RMS " << result.metrics.rms << " ("
                << 100. * result.metrics.rms_over_bbox_diagonal << " % of the diagonal), "
                << result.metrics.seconds << " s\n";

    // Everything is formatted before anything is written, and a failed
    // write removes the outputs written before it: no half outputs.
    const std::string summary = summary_text(result, input, points.size(), no_split, max_parts, split_source);
    std::ostringstream model_text;
    if(!model_file.empty())
      BS::internal::write_json(model_text, model_json(result.model));
    tools::write_all_or_none({
      {mesh, [&] {
         const auto pieces = pieces_of(result.model);
         if(tools::extension_of(mesh) == "ply")
           BS::write_blended_shape_pieces_ply(mesh, pieces);
         else
           BS::write_unified_mesh_off(mesh, pieces.merged_mesh());
       }},
      {hierarchy, [&] {
         BS::internal::write_file_atomically(hierarchy, [&](std::ostream& o) {
           BS::write_blending_hierarchy_dot(o, result.model.shape());
         });
       }},
      {strays, [&] {
         BS::internal::write_file_atomically(strays, [&](std::ostream& o) {
           for(std::size_t i : result.stray_points) o << i << '\n';
         });
       }},
      {model_file, [&] { BS::internal::write_file_atomically(model_file, [&](std::ostream& o) { o << model_text.str(); }); }},
      {json, [&] { BS::internal::write_file_atomically(json, [&](std::ostream& o) { o << summary; }); }}});
    if(json.empty() && !(std::cout << summary << std::flush))
      throw std::runtime_error("writing the summary to standard output failed (closed, or the disk is full); "
                               "give --json FILE");
  });
}
