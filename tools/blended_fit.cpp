// SPDX-License-Identifier: LGPL-3.0-or-later
// blended_fit: fit a model to a point cloud and report it as JSON.
#include "internal/command_line.h"

#include <CGAL/Blended_shape/Fitting/fit_superquadric.h>
#include <CGAL/Blended_shape/internal/write_file_atomically.h>
#include <CGAL/Blended_shape/IO/read_points.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <cmath>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <string>

namespace BS = CGAL::Blended_shapes;
namespace tools = blended_shape_tools;
typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
typedef BS::Fit_result<K> Result;

namespace {

const char* usage =
  "Usage: blended_fit INPUT [options]\n"
  "Fit a blended-shape model to the point cloud INPUT (.xyz .pts .pwn .txt .ply .off .obj .stl)\n"
  "and print a JSON summary on stdout.\n"
  "\n"
  "Options:\n"
  "  --json FILE          write the JSON summary to FILE instead of stdout\n"
  "  --mesh FILE          write the model's component pieces (sec. 3.3 of the paper) as\n"
  "                       FILE.ply (coloured by component) or FILE.off\n"
  "  --hierarchy FILE     write the blending hierarchy as Graphviz DOT\n"
  "  --model FILE         write the model (components, parameters, hierarchy) as JSON\n"
  "  --no-split           do not add parts (this release never does: see the JSON 'evolution')\n"
  "  --no-holes           do not add holes (this release never does)\n"
  "  --max-iterations N   iteration limit (default 100)\n"
  "  --seed N             random seed for the point subsets (default 0)\n"
  "  --strays FILE        write the indices (from 0, in input order) of the points judged\n"
  "                       stray, one a line\n"
  "  --robust             down-weight stray points (the default: a Gaussian and uniform\n"
  "                       mixture, see the manual)\n"
  "  --no-robust          the paper's plain least squares: every point pulls alike\n"
  "  --explicit           use the paper's explicit integrator instead of Gauss-Newton\n"
  "  --threads N          threads of the fit (default 0: all cores); the result does not depend on it\n"
  "  --quiet              no progress on stderr\n"
  "  --help               this text\n"
  "Exit code 0 on success, 1 on a failure (unreadable input, ...), 2 on a command-line mistake.\n"
  "No output file is written unless the fit succeeds.\n";

// Finite numbers only: JSON has no NaN, and a model never should.
std::string number(double x)
{
  if(!std::isfinite(x))
    throw std::runtime_error("internal error: a non-finite number in the result");
  std::ostringstream s;
  s << std::setprecision(17) << x;
  return s.str();
}

std::string escape(const std::string& text)
{
  std::string out;
  for(char c : text)
  {
    if(c == '"' || c == '\\') { out += '\\'; out += c; }
    else if(static_cast<unsigned char>(c) < 0x20) { out += ' '; }
    else out += c;
  }
  return out;
}

// The model: its one component (a superquadric ellipsoid), its pose, and the hierarchy.
void write_model(std::ostream& out, const Result::Model& model, const std::string& indent)
{
  const auto q = model.parameters();
  out << "{\n" << indent << "  \"components\": [\n"
      << indent << "    {\"id\": 0, \"name\": \"body\", \"primitive\": \"superquadric_ellipsoid\", \"parameters\": {";
  for(std::size_t i = Result::Model::number_of_pose_parameters; i < model.number_of_parameters(); ++i)
    out << (i > Result::Model::number_of_pose_parameters ? ", " : "") << '"' << model.parameter_name(i)
        << "\": " << number(q[Eigen::Index(i)]);
  out << "}}\n" << indent << "  ],\n"
      << indent << "  \"pose\": {\"translation\": [" << number(q[0]) << ", " << number(q[1]) << ", " << number(q[2])
      << "], \"quaternion_wxyz\": [" << number(q[3]) << ", " << number(q[4]) << ", " << number(q[5]) << ", "
      << number(q[6]) << "]},\n"
      << indent << "  \"blends\": [],\n"
      << indent << "  \"hierarchy\": {\"nodes\": [{\"id\": 0, \"kind\": \"primitive\", \"component\": 0}], \"edges\": []}\n"
      << indent << "}";
}

void write_summary(std::ostream& out, const Result& r, const std::string& input, bool no_split, bool no_holes)
{
  const BS::Fit_metrics& m = r.metrics;
  out << "{\n"
      << "  \"input\": \"" << escape(input) << "\",\n"
      << "  \"points\": " << m.number_of_points << ",\n"
      << "  \"parameters\": " << m.number_of_parameters << ",\n"
      << "  \"iterations\": " << m.iterations << ",\n"
      << "  \"converged\": " << (m.converged ? "true" : "false") << ",\n"
      << "  \"relative_rms\": [" << number(m.relative_rms[0]) << ", " << number(m.relative_rms[1]) << ", "
      << number(m.relative_rms[2]) << "],\n"
      << "  \"rms\": " << number(m.rms) << ",\n"
      << "  \"rms_over_bbox_diagonal\": " << number(m.rms_over_bbox_diagonal) << ",\n"
      << "  \"stray_points\": " << m.number_of_stray_points << ",\n"
      << "  \"parts\": 1,\n"
      << "  \"holes\": 0,\n"
      << "  \"genus\": 0,\n"
      << "  \"genus_source\": \"topology of the model: one closed primitive (the unified mesh comes with blending)\",\n"
      << "  \"evolution\": {\"splits_enabled\": false, \"holes_enabled\": false, \"requested_no_split\": "
      << (no_split ? "true" : "false") << ", \"requested_no_holes\": " << (no_holes ? "true" : "false")
      << ", \"note\": \"part splitting and hole evolution are not implemented in this release; "
         "the model is a single superquadric\"},\n"
      << "  \"seconds\": " << number(m.seconds) << ",\n"
      << "  \"model\": ";
  write_model(out, r.model, "  ");
  out << "\n}\n";
}

// The component pieces: each chart's faces that are not wholly in the part of
// the chart that the other chart owns (sec. 3.3: overlapping pieces).
void write_pieces(std::ostream& out, const Result& r, const std::string& format)
{
  std::vector<K::Point_3> points;
  std::vector<std::array<std::size_t, 4>> faces; // 3 vertices + chart
  for(const auto& cm : r.meshes)
  {
    const std::size_t base = points.size();
    for(auto v : cm.mesh().vertices())
      points.push_back(cm.mesh().point(v));
    for(auto f : cm.mesh().faces())
    {
      const auto v = cm.face_vertices(f);
      bool kept = false;
      for(auto vd : v)
        kept = kept || r.model.canonical_chart_point(cm.chart_point(vd)).chart == cm.chart_index();
      if(kept)
        faces.push_back({{base + std::size_t(v[0]), base + std::size_t(v[1]), base + std::size_t(v[2]), cm.chart_index()}});
    }
  }
  out << std::setprecision(17);
  if(format == "off")
  {
    out << "OFF\n" << points.size() << ' ' << faces.size() << " 0\n";
    for(const auto& p : points) out << p << '\n';
    for(const auto& f : faces) out << "3 " << f[0] << ' ' << f[1] << ' ' << f[2] << '\n';
    return;
  }
  static const int colours[2][3] = {{200, 120, 60}, {60, 140, 200}};
  out << "ply\nformat ascii 1.0\ncomment blended_fit component pieces, coloured by chart\n"
      << "element vertex " << points.size() << "\nproperty double x\nproperty double y\nproperty double z\n"
      << "element face " << faces.size() << "\nproperty list uchar int vertex_indices\n"
      << "property uchar red\nproperty uchar green\nproperty uchar blue\nend_header\n";
  for(const auto& p : points) out << p << '\n';
  for(const auto& f : faces)
  {
    const int* c = colours[f[3] % 2];
    out << "3 " << f[0] << ' ' << f[1] << ' ' << f[2] << ' ' << c[0] << ' ' << c[1] << ' ' << c[2] << '\n';
  }
}

struct Progress : BS::Default_fitting_visitor
{
  void on_phase(BS::Fitting_phase p, std::size_t it) const
  {
    std::cerr << "blended_fit: phase " << BS::phase_name(p) << " (iteration " << it << ")\n";
  }
  void on_iteration(std::size_t it, double energy, std::size_t n) const
  {
    std::cerr << "blended_fit: iteration " << it << "  energy " << energy << "  points " << n
              << "  parts 1  holes 0\n";
  }
};

struct Silent : BS::Default_fitting_visitor {};

} // namespace

int main(int argc, char** argv)
{
  const auto options = tools::known_options({"--json", "--mesh", "--hierarchy", "--model", "--max-iterations", "--seed",
                                              "--threads", "--strays"},
                                             {"--no-split", "--no-holes", "--quiet", "--robust", "--no-robust", "--explicit"});
  return tools::run_tool("blended_fit", usage, argc, argv, options, [](const tools::Command_line& line) {
    std::string input, json, mesh, hierarchy, model_file, strays;
    bool no_split = false, no_holes = false, quiet = false, robust = true, explicit_integrator = false;
    std::size_t iterations = 100, threads = 0;
    unsigned int seed = 0;
    for(const tools::Option& o : line.options)
    {
      const std::string& a = o.flag;
      if(a == "--json") json = o.value;
      else if(a == "--mesh") mesh = o.value;
      else if(a == "--hierarchy") hierarchy = o.value;
      else if(a == "--model") model_file = o.value;
      else if(a == "--no-split") no_split = true;
      else if(a == "--no-holes") no_holes = true;
      else if(a == "--quiet") quiet = true;
      else if(a == "--robust") robust = true;
      else if(a == "--no-robust") robust = false;
      else if(a == "--strays") strays = o.value;
      else if(a == "--explicit") explicit_integrator = true;
      else if(a == "--max-iterations")
      {
        iterations = std::size_t(tools::parse_integer(a, o.value));
        if(iterations == 0 || iterations > 1000000)
          throw tools::Usage_error("--max-iterations must be in [1, 1000000]");
      }
      else if(a == "--threads")
      {
        threads = std::size_t(tools::parse_integer(a, o.value));
        if(threads > 4096)
          throw tools::Usage_error("--threads must be in [0, 4096] (0: all cores)");
      }
      else if(a == "--seed")
      {
        const auto s = tools::parse_integer(a, o.value);
        if(s > 0xffffffffu)
          throw tools::Usage_error("--seed must fit in 32 bits");
        seed = static_cast<unsigned int>(s);
      }
    }
    for(const std::string& a : line.operands)
      if(input.empty()) input = a;
      else throw tools::Usage_error("more than one input file ('" + input + "' and '" + a + "')");
    if(input.empty())
      throw tools::Usage_error("no input point cloud given");
    if(!mesh.empty() && tools::extension_of(mesh) != "ply" && tools::extension_of(mesh) != "off")
      throw tools::Usage_error("--mesh: '" + mesh + "' must end in .ply or .off");

    std::vector<K::Point_3> points;
    const BS::Read_report read = BS::read_points(input, points);
    if(!quiet)
      std::cerr << "blended_fit: read " << read.points_read << " points from '" << input << "'"
                << (read.non_finite_dropped ? " (dropped " + std::to_string(read.non_finite_dropped) +
                                                " with non-finite coordinates)" : std::string()) << "\n";
    auto np = BS::parameters::number_of_threads(threads,
                BS::parameters::robust_weighting(robust ? BS::Robust_weighting::Mixture : BS::Robust_weighting::None,
                BS::parameters::integrator(explicit_integrator ? BS::Integrator::Explicit : BS::Integrator::Gauss_newton)))
                .number_of_iterations(iterations)
                .random_seed(seed);
    const Result result = quiet ? BS::fit_superquadric(points, np.visitor(Silent()))
                                : BS::fit_superquadric(points, np.visitor(Progress()));

    // Everything is formatted before anything is written: no half outputs.
    std::ostringstream summary;
    write_summary(summary, result, input, no_split, no_holes);
    if(!mesh.empty())
      BS::internal::write_file_atomically(mesh, [&](std::ostream& o) { write_pieces(o, result, tools::extension_of(mesh)); });
    if(!hierarchy.empty())
      BS::internal::write_file_atomically(hierarchy, [&](std::ostream& o) {
        o << "digraph blending_hierarchy {\n  node [shape=box];\n  n0 [label=\"body\\nsuperquadric ellipsoid\"];\n}\n";
      });
    if(!strays.empty())
      BS::internal::write_file_atomically(strays, [&](std::ostream& o) {
        for(std::size_t i : result.stray_points) o << i << '\n';
      });
    if(!model_file.empty())
      BS::internal::write_file_atomically(model_file, [&](std::ostream& o) { write_model(o, result.model, ""); o << "\n"; });
    if(json.empty())
      std::cout << summary.str() << std::flush;
    else
      BS::internal::write_file_atomically(json, [&](std::ostream& o) { o << summary.str(); });
  });
}
