// SPDX-License-Identifier: LGPL-3.0-or-later
// blended_make_object: writes one of the CAD test objects of the paper's
// experiments (sec. 6) as a closed triangle mesh.

#include <CGAL/Blended_shape/Scanning/CAD_objects.h>
#include <CGAL/Blended_shape/internal/write_file_atomically.h>

#include "internal/command_line.h"

#include <CGAL/boost/graph/IO/OBJ.h>
#include <CGAL/boost/graph/IO/OFF.h>
#include <CGAL/boost/graph/IO/PLY.h>
#include <CGAL/boost/graph/IO/STL.h>

#include <iostream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace {

namespace BS = CGAL::Blended_shapes;
namespace cl = blended_shape_tools;

const char* const tool = "blended_make_object";

// The usage shows the library's defaults, so it cannot drift from them.
std::string usage()
{
  const BS::Box_cylinder_parameters bc;
  const BS::Mug_parameters mug;
  const BS::Two_holed_box_parameters thb;
  const BS::Box_hole_cylinder_parameters bhc;
  std::ostringstream u;
  u << "usage: blended_make_object NAME -o MESH.off [options]\n"
       "\n"
       "Builds a closed triangle mesh of a test object of DeCarlo & Metaxas (PAMI 1998,\n"
       "sec. 6) with Boolean operations. NAME is one of:\n"
       "  box_cylinder       a box with a cylinder on top (genus 0, Fig. 19)\n"
       "  mug                a cup with a bottom and a ring handle (genus 1, Fig. 20)\n"
       "  two_holed_box      a box with two through-holes of different sizes (genus 2, Fig. 22)\n"
       "  box_hole_cylinder  a box with a through-hole and a cylinder on top (genus 1, Fig. 24)\n"
       "\n"
       "Options (lengths in world units, defaults in brackets; boxes stand on z = 0):\n"
       "  -o FILE                  output mesh: .off, .obj, .ply or .stl (ASCII)\n"
       "  --segments N             segments per circle, 8 to 1024 ["
    << bc.segments << ", " << mug.segments << ", " << thb.segments << ", " << bhc.segments << "]\n"
    << "  -h, --help               print this help and exit\n"
       " box_cylinder:\n"
       "  --box-size L,W,H         box extents along x, y, z ["
    << bc.box_length << ',' << bc.box_width << ',' << bc.box_height << "]\n"
    << "  --cylinder-radius R      [" << bc.cylinder_radius << "]\n"
    << "  --cylinder-height H      [" << bc.cylinder_height << "]\n"
    << " mug:\n"
       "  --radius R               outer radius of the cup [" << mug.radius << "]\n"
    << "  --height H               [" << mug.height << "]\n"
    << "  --wall T                 wall thickness [" << mug.wall_thickness << "]\n"
    << "  --bottom T               bottom thickness [" << mug.bottom_thickness << "]\n"
    << "  --handle-radius R        radius of the handle ring [" << mug.handle_radius << "]\n"
    << "  --handle-thickness T     radius of the handle tube [" << mug.handle_thickness << "]\n"
    << " two_holed_box:\n"
       "  --box-size L,W,H         ["
    << thb.box_length << ',' << thb.box_width << ',' << thb.box_height << "]\n"
    << "  --hole-radii BIG,SMALL   [" << thb.big_hole_radius << ',' << thb.small_hole_radius << "]\n"
    << " box_hole_cylinder:\n"
       "  --box-size L,W,H         ["
    << bhc.box_length << ',' << bhc.box_width << ',' << bhc.box_height << "]\n"
    << "  --hole-radius R          [" << bhc.hole_radius << "]\n"
    << "  --cylinder-radius R      [" << bhc.cylinder_radius << "]\n"
    << "  --cylinder-height H      [" << bhc.cylinder_height << "]\n"
    << "\n"
       "Exit status: 0 on success; 1 if the parameters do not give a valid object;\n"
       "2 on a command-line error. On failure no file is written.\n";
  return u.str();
}

// Which flags each object takes (besides -o and --segments).
const std::map<std::string, std::set<std::string>>& object_flags()
{
  static const std::map<std::string, std::set<std::string>> flags = {
    {"box_cylinder", {"--box-size", "--cylinder-radius", "--cylinder-height"}},
    {"mug", {"--radius", "--height", "--wall", "--bottom", "--handle-radius", "--handle-thickness"}},
    {"two_holed_box", {"--box-size", "--hole-radii"}},
    {"box_hole_cylinder", {"--box-size", "--hole-radius", "--cylinder-radius", "--cylinder-height"}}};
  return flags;
}

template <class Parameters>
void set_box_size(Parameters& p, const std::string& flag, const std::string& value)
{
  const auto s = cl::parse_triple(flag, value);
  p.box_length = s[0];
  p.box_width = s[1];
  p.box_height = s[2];
}

BS::CAD_mesh build(const std::string& name, const std::vector<std::pair<std::string, std::string>>& flags)
{
  auto number = [](const std::pair<std::string, std::string>& f) { return cl::parse_number(f.first, f.second); };
  auto segments = [](const std::pair<std::string, std::string>& f) {
    return std::size_t(cl::parse_integer(f.first, f.second));
  };
  if(name == "box_cylinder")
  {
    BS::Box_cylinder_parameters p;
    for(const auto& f : flags)
    {
      if(f.first == "--segments") p.segments = segments(f);
      else if(f.first == "--box-size") set_box_size(p, f.first, f.second);
      else if(f.first == "--cylinder-radius") p.cylinder_radius = number(f);
      else if(f.first == "--cylinder-height") p.cylinder_height = number(f);
    }
    return BS::make_box_cylinder(p);
  }
  if(name == "mug")
  {
    BS::Mug_parameters p;
    for(const auto& f : flags)
    {
      if(f.first == "--segments") p.segments = segments(f);
      else if(f.first == "--radius") p.radius = number(f);
      else if(f.first == "--height") p.height = number(f);
      else if(f.first == "--wall") p.wall_thickness = number(f);
      else if(f.first == "--bottom") p.bottom_thickness = number(f);
      else if(f.first == "--handle-radius") p.handle_radius = number(f);
      else if(f.first == "--handle-thickness") p.handle_thickness = number(f);
    }
    return BS::make_mug(p);
  }
  if(name == "two_holed_box")
  {
    BS::Two_holed_box_parameters p;
    for(const auto& f : flags)
    {
      if(f.first == "--segments") p.segments = segments(f);
      else if(f.first == "--box-size") set_box_size(p, f.first, f.second);
      else if(f.first == "--hole-radii")
      {
        const auto r = cl::parse_numbers(f.first, f.second, 2);
        p.big_hole_radius = r[0];
        p.small_hole_radius = r[1];
      }
    }
    return BS::make_two_holed_box(p);
  }
  BS::Box_hole_cylinder_parameters p; // name was checked by the caller
  for(const auto& f : flags)
  {
    if(f.first == "--segments") p.segments = segments(f);
    else if(f.first == "--box-size") set_box_size(p, f.first, f.second);
    else if(f.first == "--hole-radius") p.hole_radius = number(f);
    else if(f.first == "--cylinder-radius") p.cylinder_radius = number(f);
    else if(f.first == "--cylinder-height") p.cylinder_height = number(f);
  }
  return BS::make_box_hole_cylinder(p);
}

void make_object(const cl::Command_line& line)
{
  std::string name, output;
  std::vector<std::pair<std::string, std::string>> flags;
  for(const cl::Option& o : line.options)
  {
    if(o.flag == "-o")
      output = o.value;
    else
      flags.emplace_back(o.flag, o.value);
  }
  for(const std::string& a : line.operands)
  {
    if(name.empty())
      name = a;
    else
      throw cl::Usage_error("more than one object name ('" + name + "' and '" + a + "')");
  }
  if(name.empty())
    throw cl::Usage_error("no object name given; use box_cylinder, mug, two_holed_box or box_hole_cylinder");
  const auto object = object_flags().find(name);
  if(object == object_flags().end())
    throw cl::Usage_error("unknown object '" + name +
                          "'; use box_cylinder, mug, two_holed_box or box_hole_cylinder");
  for(const auto& f : flags)
    if(f.first != "--segments" && !object->second.count(f.first))
      throw cl::Usage_error("option " + f.first + " does not apply to " + name);
  if(output.empty())
    throw cl::Usage_error("no output file given; use -o MESH.off");
  const std::string ext = cl::extension_of(output);
  if(ext != "off" && ext != "obj" && ext != "ply" && ext != "stl")
    throw cl::Usage_error("output '" + output + "' must end in .off, .obj, .ply or .stl");
  cl::check_files({}, {{"-o", output}});

  const BS::CAD_mesh mesh = build(name, flags); // usage errors in values surface here too

  BS::internal::write_file_atomically(output, [&](std::ostream& out) {
    const auto np = CGAL::parameters::stream_precision(17);
    bool ok = false;
    if(ext == "off") ok = CGAL::IO::write_OFF(out, mesh, np);
    else if(ext == "obj") ok = CGAL::IO::write_OBJ(out, mesh, np);
    else if(ext == "ply") ok = CGAL::IO::write_PLY(out, mesh, np);
    else ok = CGAL::IO::write_STL(out, mesh, np);
    if(!ok)
      throw std::runtime_error("writing '" + output + "' failed; nothing was written");
  });
  const long genus =
    (2 - (long(mesh.number_of_vertices()) - long(mesh.number_of_edges()) + long(mesh.number_of_faces()))) / 2;
  std::cout << tool << ": wrote " << name << " (" << mesh.number_of_vertices() << " vertices, "
            << mesh.number_of_faces() << " triangles, genus " << genus << ") to " << output << std::endl;
}

} // namespace

int main(int argc, char** argv)
{
  std::set<std::string> all_flags = {"-o", "--segments"};
  for(const auto& o : object_flags())
    all_flags.insert(o.second.begin(), o.second.end());
  const auto options = cl::known_options(std::vector<std::string>(all_flags.begin(), all_flags.end()));
  return blended_shape_tools::run_tool(tool, usage(), argc, argv, options, make_object);
}
