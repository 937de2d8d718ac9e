// SPDX-License-Identifier: LGPL-3.0-or-later
// blended_scan: simulated range scan of a triangle mesh (the "CAD utility which
// simulates the scanning process on a polygon mesh" of the paper's sec. 6).

#include <CGAL/Blended_shape/Scanning/Range_scan_simulator.h>
#include <CGAL/Blended_shape/IO/read_triangle_mesh.h>

#include "internal/command_line.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>

#include <array>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <string>

namespace {

typedef CGAL::Exact_predicates_inexact_constructions_kernel Kernel;
typedef CGAL::Surface_mesh<Kernel::Point_3> Mesh;
namespace BS = CGAL::Blended_shapes;
namespace cl = blended_shape_tools;

const char* const tool = "blended_scan";

const std::string usage =
  "usage: blended_scan MESH -o OUT.xyz|OUT.ply [options]\n"
  "\n"
  "Simulates a range scanner on a triangle mesh (.off, .obj, .ply or .stl): one ray\n"
  "per pixel, first hits only. Without camera options the whole object is seen from\n"
  "the direction (1, 0.6, 0.8) with a 40 degree field of view, z up, 200 x 200 pixels.\n"
  "\n"
  "options:\n"
  "  -o FILE                   output points: .xyz (x y z per line) or .ply (ASCII)\n"
  "  --eye X,Y,Z               camera position\n"
  "  --target X,Y,Z            point looked at (default: centre of the bounding box)\n"
  "  --up X,Y,Z                up direction of the image (default: 0,0,1)\n"
  "  --fov DEGREES             vertical field of view, in (0, 180) (default: 40)\n"
  "  --width W                 image width in pixels (default: 200)\n"
  "  --height H                image height in pixels (default: 200)\n"
  "  --orthographic VIEW_HEIGHT  parallel rays; VIEW_HEIGHT is the vertical extent\n"
  "                            of the view in world units\n"
  "  --noise SIGMA             Gaussian range noise along the rays, world units (default: 0)\n"
  "  --dropout P               probability in [0, 1] that a hit pixel is lost (default: 0)\n"
  "  --seed N                  seed of the noise and the dropout (default: 0)\n"
  "  --normals                 also write the face normals, oriented toward the camera\n"
  "  -h, --help                print this help and exit\n"
  "\n"
  "Exit status: 0 on success; 1 if the mesh cannot be used, the camera is invalid or\n"
  "no ray hits the mesh; 2 on a command-line error. On failure no file is written.\n";

Kernel::Point_3 to_point(const std::array<double, 3>& a) { return Kernel::Point_3(a[0], a[1], a[2]); }

void scan(const cl::Command_line& line)
{
  std::string input, output;
  bool has_eye = false, has_target = false, has_up = false, has_fov = false, has_ortho = false;
  bool has_width = false, has_height = false, normals = false;
  std::array<double, 3> eye{}, target{}, up{};
  double fov = 0., view_height = 0.;
  std::uint64_t width = 0, height = 0;
  BS::Scan_options options;

  for(const cl::Option& o : line.options)
  {
    const std::string& a = o.flag;
    if(a == "-o")
      output = o.value;
    else if(a == "--eye")
      eye = cl::parse_triple(a, o.value), has_eye = true;
    else if(a == "--target")
      target = cl::parse_triple(a, o.value), has_target = true;
    else if(a == "--up")
      up = cl::parse_triple(a, o.value), has_up = true;
    else if(a == "--fov")
      fov = cl::parse_number(a, o.value), has_fov = true;
    else if(a == "--width")
      width = cl::parse_integer(a, o.value), has_width = true;
    else if(a == "--height")
      height = cl::parse_integer(a, o.value), has_height = true;
    else if(a == "--orthographic")
      view_height = cl::parse_number(a, o.value), has_ortho = true;
    else if(a == "--noise")
      options.noise_sigma = cl::parse_number(a, o.value);
    else if(a == "--dropout")
      options.dropout_probability = cl::parse_number(a, o.value);
    else if(a == "--seed")
      options.random_seed = cl::parse_integer(a, o.value);
    else if(a == "--normals")
      normals = true;
  }
  for(const std::string& a : line.operands)
  {
    if(input.empty())
      input = a;
    else
      throw cl::Usage_error("more than one input mesh ('" + input + "' and '" + a + "')");
  }
  if(input.empty())
    throw cl::Usage_error("no input mesh given");
  if(output.empty())
    throw cl::Usage_error("no output file given; use -o OUT.xyz or -o OUT.ply");
  const std::string ext = cl::extension_of(output);
  if(ext != "xyz" && ext != "ply")
    throw cl::Usage_error("output '" + output + "' must end in .xyz or .ply");
  cl::check_files({{"input", input}}, {{"-o", output}});

  Mesh mesh;
  BS::read_triangle_mesh(input, mesh);

  BS::Camera<Kernel> camera = BS::default_camera_for(mesh);
  if(has_eye)
    camera.eye = to_point(eye);
  if(has_target)
    camera.target = to_point(target);
  if(has_up)
    camera.up = Kernel::Vector_3(up[0], up[1], up[2]);
  if(has_fov)
    camera.field_of_view_degrees = fov;
  if(has_width)
    camera.width = std::size_t(width);
  if(has_height)
    camera.height = std::size_t(height);
  if(has_ortho)
  {
    camera.projection = BS::Projection::Orthographic;
    camera.view_height = view_height;
  }

  const auto samples = BS::simulate_range_scan(mesh, camera, options);
  if(samples.empty())
  {
    std::ostringstream what;
    what << "no ray hit the mesh '" << input << "' (" << camera.width << " x " << camera.height << " pixels";
    if(camera.projection == BS::Projection::Perspective)
    {
      // The field of view is vertical: few rows make a coarse, wide image.
      const double half = std::tan(0.5 * camera.field_of_view_degrees * CGAL_PI / 180.);
      const double pixel = 2. * half / double(camera.height);
      what << "; the field of view, " << camera.field_of_view_degrees << " degrees, is vertical: one ray every "
           << std::fixed << std::setprecision(1) << std::atan(pixel) * 180. / CGAL_PI << " degrees at the centre, "
           << 2. * std::atan(0.5 * double(camera.width) * pixel) * 180. / CGAL_PI << " degrees across";
    }
    what << "); aim the camera at the object with --eye and --target, use more rows (--height), or lower --dropout";
    throw std::runtime_error(what.str());
  }
  BS::write_range_scan(output, samples, normals);
  std::cout << tool << ": wrote " << samples.size() << " points to " << output << std::endl;
}

} // namespace

int main(int argc, char** argv)
{
  const auto options = cl::known_options({"-o", "--eye", "--target", "--up", "--fov", "--width", "--height",
                                          "--orthographic", "--noise", "--dropout", "--seed"},
                                         {"--normals"});
  return blended_shape_tools::run_tool(tool, usage, argc, argv, options, scan);
}
