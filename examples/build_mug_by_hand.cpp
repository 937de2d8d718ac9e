// SPDX-License-Identifier: LGPL-3.0-or-later
// Building a blended shape by hand: a mug made through the Blended_shape API
// (paper sec. 4), the evolution that fitting performs automatically, done
// step by step: a cylinder-like body, a handle blended in gradually as a
// part (sec. 4.1), then a hole through the handle (sec. 4.2) blended in,
// switched to its tube domain and opened: a genus-1 surface. Writes the
// unified closed mesh (OFF), the per-component pieces colored by component
// (PLY) and the blending hierarchy (Graphviz DOT).
//
// Usage: build_mug_by_hand [OUT_PREFIX]      (default prefix: mug_by_hand)
// writes OUT_PREFIX.off, OUT_PREFIX.ply and OUT_PREFIX.dot.
#include <CGAL/Blended_shape/Blending/Blended_shape.h>
#include <CGAL/Blended_shape/Blending/Blended_shape_mesh.h>
#include <CGAL/Blended_shape/IO/Blended_shape_mesh_io.h>
#include <CGAL/Blended_shape/Blending/Blending_hierarchy.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/repair.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/helpers.h>

#include <Eigen/Core>

#include <array>
#include <cmath>
#include <exception>
#include <filesystem>
#include <iostream>
#include <stdexcept>
#include <string>
#include <system_error>

namespace BS = CGAL::Blended_shapes;
namespace PMP = CGAL::Polygon_mesh_processing;

typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
typedef BS::Blended_shape<K> Shape;
typedef BS::Superquadric_ellipsoid<K> Ellipsoid;
typedef BS::Ellipse_blending_region Region;
typedef CGAL::Surface_mesh<K::Point_3> Mesh;

namespace {

// Parameters are addressed by name ("b0.h", "c2.a4", ...): the shape keeps
// one parameter vector, set as a whole.
double get_parameter(const Shape& s, const std::string& name)
{
  for(std::size_t i = 0; i < s.number_of_parameters(); ++i)
    if(s.parameter_name(i) == name)
      return s.parameters()[Eigen::Index(i)];
  throw std::logic_error("no parameter " + name);
}

void set_parameter(Shape& s, const std::string& name, double value)
{
  Eigen::VectorXd q = s.parameters();
  for(std::size_t i = 0; i < s.number_of_parameters(); ++i)
    if(s.parameter_name(i) == name)
    {
      q[Eigen::Index(i)] = value;
      s.set_parameters(q);
      return;
    }
  throw std::logic_error("no parameter " + name);
}

void report(const std::string& step, const Shape& s)
{
  std::cout << step << "\n    components " << s.number_of_components() << ", blends " << s.number_of_blends()
            << ", holes " << s.holes().size() << ", genus " << s.genus() << ", parameters "
            << s.number_of_parameters() << std::endl;
}

int usage(const char* program, const std::string& problem)
{
  if(!problem.empty())
    std::cerr << program << ": " << problem << "\n";
  std::cerr << "usage: " << program << " [OUT_PREFIX]\n"
            << "  builds a mug (body, handle part, hole through the handle) with the Blended_shape API\n"
            << "  and writes OUT_PREFIX.off (unified closed mesh), OUT_PREFIX.ply (pieces colored by\n"
            << "  component) and OUT_PREFIX.dot (blending hierarchy); default prefix: mug_by_hand"
            << std::endl;
  return problem.empty() ? 0 : 2;
}

} // namespace

int main(int argc, char** argv)
{
  const char* program = argc > 0 ? argv[0] : "build_mug_by_hand";
  if(argc > 2)
    return usage(program, "too many arguments");
  const std::string prefix = argc == 2 ? argv[1] : "mug_by_hand";
  if(prefix == "-h" || prefix == "--help")
    return usage(program, "");
  if(prefix.empty() || prefix[0] == '-')
    return usage(program, prefix.empty() ? "empty OUT_PREFIX" : "unknown option '" + prefix + "'");
  {
    // Fail before the work when the output directory is missing; the writers
    // check the rest (permissions, disk) and never leave a half-written file.
    const std::filesystem::path dir = std::filesystem::path(prefix + ".off").parent_path();
    std::error_code ec;
    if(!dir.empty() && !std::filesystem::is_directory(dir, ec))
      return usage(program, "cannot write '" + prefix + ".*': '" + dir.string() +
                                "' is not a directory; create it or choose another OUT_PREFIX");
    for(const char* ext : {".off", ".ply", ".dot"})
      if(std::filesystem::is_directory(prefix + ext, ec))
        return usage(program, "cannot write '" + prefix + ext + "': it is a directory; choose another OUT_PREFIX");
  }

  try
  {
    // 1. The body: a superquadric ellipsoid with a small latitude exponent
    //    (e1 = 0.3: flat top and bottom, straight sides), round in
    //    cross-section (e2 = 1), 2.5 high. Its two disk charts (upper and
    //    lower half) reach half-way into each other (chart margin 0.5), so a
    //    region on the side may cross the equator, the seam of the charts.
    // [body]
    Shape mug(Ellipsoid(1.0, 1.0, 1.25, 0.3, 1.0, 0.5));
    // [body]
    report("1. body: superquadric ellipsoid a = (1, 1, 1.25), e1 = 0.3, e2 = 1", mug);

    // 2. The handle: a flattened ellipsoid (0.75 high, 0.18 thick, 0.55
    //    deep, boxy cross-section e2 = 0.5) turned by 90 degrees about y so
    //    that its own z axis (the pole of its chart 0) points away from the
    //    body, centred at x = 1.35. It is blended gradually into the body
    //    (sec. 4.1): a disk region on the side of the body (chart 0, centred
    //    on the equator at (1, 0), radii 0.3 along the meridian and 0.2
    //    around: the handle's footprint in the chart; strip half-width 0.06)
    //    corresponds to the inside of the circle of radius 1.45 of the
    //    handle's chart 0 (all of it but the end that lies in the body).
    //    add_part sets h = 1: the handle starts unexpressed.
    // [handle]
    const double c45 = std::sqrt(0.5);
    mug.add_part(0, 0, Region::make_parameters(1.0, 0., 0.3, 0.2, 0., 1., 1.), 0.06,
                 Ellipsoid(0.75, 0.18, 0.55, 1.0, 0.5, 0.6), "superquadric_ellipsoid", Eigen::Vector3d(1.35, 0., 0.),
                 Eigen::Vector4d(c45, 0., c45, 0.), 0, Region::make_parameters(0., 0., 1.45, 1.45, 0., 1., 0.), 0.07);
    // [handle]
    report("2. handle added with add_part (blend 0, h = 1: not expressed yet)", mug);

    // 3. Lowering h blends the handle in: s = alpha s_body + (1 - alpha) s_handle
    //    in the disk and its strip (eq. 3, 4), with alpha scaled by h (eq. 15).
    // [gradual]
    for(double h : {0.75, 0.5, 0.25, 0.})
    {
      set_parameter(mug, "b0.h", h);
      std::cout << "3. b0.h = " << h << std::endl;
    }
    // [gradual]
    // At h = 0 the cut is made final: the disk becomes an annulus, the
    // handle's retained part its own surface. No point moves; h is now fixed.
    // [finish]
    mug.finish_gradual_blend(0);
    // [finish]
    report("4. finish_gradual_blend(0): the handle is a cut-and-glue part", mug);

    // 5. The hole (sec. 4.2) between the two broad faces of the handle: disk
    //    regions of radius 0.3 (strip half-width 0.06) around the points
    //    (0, 0.95) and (0, -0.95) of the handle's chart 0 (its front and back
    //    faces, next to the body), glued to the two ends of a new hole
    //    component: the pinched sphere, in its Two_disks domain, h = 1.
    // [add_hole]
    const std::size_t hole = mug.add_hole(BS::Shape_point(1, BS::Chart_point(0, 0., 0.95)),
                                          BS::Shape_point(1, BS::Chart_point(0, 0., -0.95)), 0.3, 0.06, 0.1);
    // [add_hole]
    const std::array<std::size_t, 2> ends = mug.holes()[hole].blends;
    const std::string hc = "c" + std::to_string(mug.holes()[hole].component);
    report("5. hole added with add_hole (blends " + std::to_string(ends[0]) + ", " + std::to_string(ends[1]) +
               ", component " + hc + ", pinched sphere)", mug);
    // [express_hole]
    for(double h : {0.5, 0.})
    {
      for(std::size_t b : ends)
        set_parameter(mug, "b" + std::to_string(b) + ".h", h);
      std::cout << "6. both ends h = " << h << std::endl;
    }
    // [express_hole]

    // 7. Fully expressed, the hole switches to its Tube domain: the topology
    //    changes (genus 1), the surface does not.
    // [tube]
    mug.switch_hole_to_tube(hole);
    // [tube]
    report("7. switch_hole_to_tube: the hole is a tube", mug);

    // 8. Open it: a4, a5 > 1 give the middle circle the radius a1 (a4 - 1);
    //    dividing a1, a2 by the same factor keeps the end circles (radius
    //    a1 a4) where the regions glue them. A smaller profile exponent
    //    straightens the wall of the hole. Opened much wider (a4 = 2.5), the
    //    hole's end strips would fold over (the blended surface turns over
    //    where the two sides are farther apart than the strip can bend).
    // [open]
    const double opening = 1.5;
    for(const char* a : {"a1", "a2"})
      set_parameter(mug, hc + "." + a, get_parameter(mug, hc + "." + a) / opening);
    set_parameter(mug, hc + ".a4", opening);
    set_parameter(mug, hc + ".a5", opening);
    set_parameter(mug, hc + ".e1", 0.6);
    // [open]
    report("8. hole opened: " + hc + ".a4 = " + hc + ".a5 = " + std::to_string(opening), mug);

    // The unified closed mesh (domain surgery), and its checks.
    // [check]
    const Mesh unified = BS::make_unified_mesh(mug, 48, 4);
    const long chi = long(unified.number_of_vertices()) - long(unified.number_of_edges()) +
                     long(unified.number_of_faces());
    Mesh copy = unified;
    const bool closed = CGAL::is_closed(unified);
    const bool manifold = CGAL::is_valid_polygon_mesh(unified) && PMP::duplicate_non_manifold_vertices(copy) == 0;
    const bool self_intersecting = PMP::does_self_intersect(unified);
    // [check]
    std::cout << "unified mesh: " << unified.number_of_vertices() << " vertices, " << unified.number_of_faces()
              << " faces, Euler characteristic " << chi << (closed ? ", closed" : ", NOT closed")
              << (manifold ? ", manifold" : ", NOT manifold")
              << (self_intersecting ? ", SELF-INTERSECTING" : ", no self-intersection")
              << std::endl;

    // The outputs. Each file is written through a temporary file renamed at
    // the end: a failure leaves no half-written file.
    try
    {
      // [outputs]
      BS::write_unified_mesh_off(prefix + ".off", unified);
      BS::write_blended_shape_pieces_ply(prefix + ".ply", BS::Blended_shape_pieces<K>(mug, 24));
      BS::write_blending_hierarchy_dot(prefix + ".dot", mug);
      // [outputs]
    }
    catch(const std::runtime_error& e) // unwritable OUT_PREFIX
    {
      return usage(program, e.what());
    }
    std::cout << "wrote " << prefix << ".off, " << prefix << ".ply, " << prefix << ".dot" << std::endl;

    if(!closed || !manifold || self_intersecting || chi != 0 || mug.genus() != 1)
    {
      std::cerr << program << ": the mug is not a closed manifold genus-1 surface without self-intersections "
                << "(Euler characteristic " << chi << ", expected 0)" << std::endl;
      return 1;
    }
    return 0;
  }
  catch(const std::exception& e) // a step of the construction failed
  {
    std::cerr << program << ": " << e.what() << std::endl;
    return 1;
  }
}
