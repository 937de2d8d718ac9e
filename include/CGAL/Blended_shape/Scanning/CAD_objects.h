// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_BLENDED_SHAPE_SCANNING_CAD_OBJECTS_H
#define CGAL_BLENDED_SHAPE_SCANNING_CAD_OBJECTS_H

#include <CGAL/Blended_shape/Scanning/CAD_primitive_solids.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/corefinement.h>
#include <CGAL/Polygon_mesh_processing/orientation.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/helpers.h>

#include <algorithm>
#include <cstddef>
#include <stdexcept>
#include <string>

namespace CGAL {
namespace Blended_shapes {

namespace internal {

// The preconditions of the corefinement: a closed solid without self-intersection.
inline void check_boolean_operand(const CAD_mesh& m, const std::string& who, const char* what)
{
  namespace PMP = CGAL::Polygon_mesh_processing;
  if(!CGAL::is_closed(m) || PMP::does_self_intersect(m) || !PMP::does_bound_a_volume(m))
    throw std::runtime_error(who + ": the " + what +
                             " does not bound a volume; the parameters are too close to a degenerate case");
}

enum class Boolean_operation { Union, Difference };

inline CAD_mesh boolean(Boolean_operation op, CAD_mesh a, CAD_mesh b, const std::string& who,
                        const char* what_a, const char* what_b)
{
  namespace PMP = CGAL::Polygon_mesh_processing;
  check_boolean_operand(a, who, what_a);
  check_boolean_operand(b, who, what_b);
  CAD_mesh out;
  const bool ok = op == Boolean_operation::Union ? PMP::corefine_and_compute_union(a, b, out)
                                                 : PMP::corefine_and_compute_difference(a, b, out);
  if(!ok)
    throw std::runtime_error(who + ": the Boolean operation of the " + what_a + " and the " + what_b +
                             " failed; the parameters are too close to a degenerate case");
  if(out.has_garbage())
    out.collect_garbage();
  return out;
}

// What every CAD object promises: a closed, outward-oriented, self-intersection
// free triangle mesh whose Euler characteristic is 2 - 2 genus.
inline void check_solid(const CAD_mesh& m, const std::string& who, int genus)
{
  namespace PMP = CGAL::Polygon_mesh_processing;
  const long chi = long(m.number_of_vertices()) - long(m.number_of_edges()) + long(m.number_of_faces());
  if(!CGAL::is_closed(m) || !CGAL::is_triangle_mesh(m) || PMP::does_self_intersect(m) ||
     !PMP::is_outward_oriented(m) || chi != 2 - 2 * genus)
    throw std::runtime_error(who + ": the result is not a closed genus-" + std::to_string(genus) +
                             " solid; the parameters are too close to a degenerate case");
}

} // namespace internal

/// \name CAD objects of the paper's experiments (sec. 6)
/// Each function validates its parameters and throws `std::invalid_argument`
/// with what is wrong and what to do; it throws `std::runtime_error` in the
/// unlikely case that a Boolean operation fails. The result is a closed,
/// manifold, outward-oriented triangle mesh without self-intersection, of the
/// genus stated. Boxes are centred on the z axis and stand on z = 0.
/// @{

/// \ingroup PkgBlendedShapeScanning
/// Box plus cylinder on its top centre: genus 0.
/// \throws std::invalid_argument if a size is not positive, or the cylinder does not fit on the box.
inline CAD_mesh make_box_cylinder(const Box_cylinder_parameters& p = Box_cylinder_parameters())
{
  const std::string who = "make_box_cylinder";
  const auto [box, cylinder] = internal::box_cylinder_solids(p, who);
  CAD_mesh result = internal::boolean(internal::Boolean_operation::Union, box, cylinder, who, "box", "cylinder");
  internal::check_solid(result, who, 0);
  return result;
}

/// \ingroup PkgBlendedShapeScanning
/// A mug (Fig. 20): an open cylindrical cup with a bottom, and a C-shaped handle.
struct Mug_parameters
{
  double radius = 1.;             ///< outer radius of the cup
  double height = 2.;             ///< height of the cup
  double wall_thickness = 0.15;   ///< thickness of the cup's wall
  double bottom_thickness = 0.15; ///< thickness of the cup's bottom
  double handle_radius = 0.5;     ///< radius of the handle ring's centre line
  double handle_thickness = 0.1;  ///< radius of the handle's tube
  std::size_t segments = 48;      ///< around the cup and around the handle ring
};

/// \ingroup PkgBlendedShapeScanning
/// The mug: genus 1 (the handle). The handle is a ring in the x-z plane
/// whose centre is `0.3 * handle_radius` outside the cup, at half height; the
/// ring crosses the wall twice, and the part inside the cup is cut away, like
/// a real mug handle joined to the side at two places.
/// \throws std::invalid_argument if a size is not positive, the wall or the
/// bottom is too thick for the cup, the handle ring is closed by its own
/// tube, the ring is too small to pass through the wall or too large for the
/// cup, or the handle reaches the bottom or the top of the cup.
inline CAD_mesh make_mug(const Mug_parameters& p = Mug_parameters())
{
  const std::string who = "make_mug";
  internal::check_sizes(who, p.segments, {{"radius", p.radius}, {"height", p.height},
                              {"wall thickness", p.wall_thickness},
                              {"bottom thickness", p.bottom_thickness},
                              {"handle radius", p.handle_radius},
                              {"handle thickness", p.handle_thickness}});
  using internal::to_string_g;
  const double R = p.radius, H = p.height, t = p.wall_thickness, b = p.bottom_thickness;
  const double Rh = p.handle_radius, r = p.handle_thickness;
  internal::require(t <= 0.5 * R, who,
                    "wall thickness " + to_string_g(t) + " is more than half the radius " + to_string_g(R) +
                      "; use a thinner wall");
  internal::require(b <= 0.5 * H, who,
                    "bottom thickness " + to_string_g(b) + " is more than half the height " + to_string_g(H) +
                      "; use a thinner bottom");
  internal::require(r <= 0.5 * Rh, who,
                    "handle thickness " + to_string_g(r) + " is more than half the handle radius " +
                      to_string_g(Rh) + ": the handle would have no hole; use a thinner or a wider handle");
  // The ring must pass through the wall completely (clean, transverse cuts)...
  internal::require(0.7 * Rh >= 1.1 * (t + r), who,
                    "handle radius " + to_string_g(Rh) + " is too small for the ring to pass through the wall (at least " +
                      to_string_g(1.1 * (t + r) / 0.7) +
                      " = 1.1 x (wall + handle thickness) / 0.7); use a wider handle or a thinner wall");
  // ...without reaching past the axis of the cup...
  internal::require(0.7 * Rh + r <= R, who,
                    "the handle (radius " + to_string_g(Rh) + ", thickness " + to_string_g(r) +
                      ") reaches past the axis of the cup of radius " + to_string_g(R) +
                      "; use a smaller handle or a wider mug");
  // ...and stay between the bottom and the rim.
  internal::require(Rh + r <= 0.45 * H - b, who,
                    "the handle (radius + thickness = " + to_string_g(Rh + r) +
                      ") reaches the bottom or the rim (at most 0.45 x height - bottom = " +
                      to_string_g(0.45 * H - b) + "); use a smaller handle or a taller mug");

  const CAD_mesh body = make_cylinder_mesh(CAD_mesh::Point(0., 0., 0.), R, H, p.segments,
                                           internal::outer_turn);
  // The cavity sticks out of the top so that no face of it is coplanar with the rim.
  const CAD_mesh cavity = make_cylinder_mesh(CAD_mesh::Point(0., 0., b), R - t, H - b + 0.1 * H, p.segments,
                                             internal::inner_turn);
  const CAD_mesh handle = make_torus_mesh(CAD_mesh::Point(R + 0.3 * Rh, 0., 0.5 * H), CAD_kernel::Vector_3(0., 1., 0.),
                                          Rh, r, p.segments, (std::max)(std::size_t(8), p.segments / 3));
  // Union first, then the cavity, which cuts away the inner part of the ring.
  const CAD_mesh solid = internal::boolean(internal::Boolean_operation::Union, body, handle, who, "cup", "handle");
  CAD_mesh result = internal::boolean(internal::Boolean_operation::Difference, solid, cavity, who,
                                      "cup with handle", "cavity");
  internal::check_solid(result, who, 1);
  return result;
}

/// \ingroup PkgBlendedShapeScanning
/// A box with two vertical through-holes of different sizes (Fig. 22), centred
/// at x = -length/4 (the big one) and x = +length/4 (the small one).
struct Two_holed_box_parameters
{
  double box_length = 4.;        ///< along x
  double box_width = 2.;         ///< along y
  double box_height = 1.;        ///< along z (the holes' direction)
  double big_hole_radius = 0.6;    ///< radius of the hole at x = -length/4
  double small_hole_radius = 0.35; ///< radius of the hole at x = +length/4
  std::size_t segments = 40;       ///< per circle
};

/// \ingroup PkgBlendedShapeScanning
/// The two-holed box: genus 2.
/// \throws std::invalid_argument if a size is not positive or a hole does not
/// fit in its half of the box with a wall around it.
inline CAD_mesh make_two_holed_box(const Two_holed_box_parameters& p = Two_holed_box_parameters())
{
  const std::string who = "make_two_holed_box";
  internal::check_sizes(who, p.segments, {{"box length", p.box_length}, {"box width", p.box_width},
                              {"box height", p.box_height}, {"big hole radius", p.big_hole_radius},
                              {"small hole radius", p.small_hole_radius}});
  const double fit = 0.9 * (std::min)(0.25 * p.box_length, 0.5 * p.box_width);
  for(const auto& hole : {std::make_pair("big hole radius", p.big_hole_radius),
                          std::make_pair("small hole radius", p.small_hole_radius)})
    internal::require(hole.second <= fit, who,
                      std::string(hole.first) + " " + internal::to_string_g(hole.second) +
                        " is wider than its half of the box allows (at most " + internal::to_string_g(fit) +
                        " = 0.9 x min(length/4, width/2)); use a smaller hole or a larger box");

  CAD_mesh result = make_box_mesh(CAD_mesh::Point(-0.5 * p.box_length, -0.5 * p.box_width, 0.),
                                  CAD_mesh::Point(0.5 * p.box_length, 0.5 * p.box_width, p.box_height));
  // The drills stick out on both sides: no coplanar faces.
  const double overshoot = 0.1 * p.box_height;
  const double hx[2] = {-0.25 * p.box_length, 0.25 * p.box_length};
  const double hr[2] = {p.big_hole_radius, p.small_hole_radius};
  for(int i = 0; i < 2; ++i)
  {
    const CAD_mesh drill = make_cylinder_mesh(CAD_mesh::Point(hx[i], 0., -overshoot), hr[i],
                                              p.box_height + 2. * overshoot, p.segments,
                                              internal::outer_turn);
    result = internal::boolean(internal::Boolean_operation::Difference, result, drill, who, "box", "hole");
  }
  internal::check_solid(result, who, 2);
  return result;
}

/// \ingroup PkgBlendedShapeScanning
/// The object of the paper's Fig. 24: a box with a vertical through-hole at
/// x = -length/4 and a cylinder standing on the box top at x = +length/4.
struct Box_hole_cylinder_parameters
{
  double box_length = 4.;        ///< along x
  double box_width = 2.;         ///< along y
  double box_height = 1.;        ///< along z
  double hole_radius = 0.5;      ///< radius of the through-hole
  double cylinder_radius = 0.5;  ///< radius of the cylinder
  double cylinder_height = 1.;   ///< height of the cylinder above the box top
  std::size_t segments = 40;     ///< per circle
};

/// \ingroup PkgBlendedShapeScanning
/// The box/hole/cylinder object: genus 1.
/// \throws std::invalid_argument if a size is not positive or the hole or
/// the cylinder does not fit in its half of the box.
inline CAD_mesh make_box_hole_cylinder(const Box_hole_cylinder_parameters& p)
{
  const std::string who = "make_box_hole_cylinder";
  internal::check_sizes(who, p.segments, {{"box length", p.box_length}, {"box width", p.box_width},
                              {"box height", p.box_height}, {"hole radius", p.hole_radius},
                              {"cylinder radius", p.cylinder_radius},
                              {"cylinder height", p.cylinder_height}});
  const double fit = 0.9 * (std::min)(0.25 * p.box_length, 0.5 * p.box_width);
  internal::require(p.hole_radius <= fit, who,
                    "hole radius " + internal::to_string_g(p.hole_radius) +
                      " is wider than its half of the box allows (at most " + internal::to_string_g(fit) +
                      " = 0.9 x min(length/4, width/2)); use a smaller hole or a larger box");
  internal::require(p.cylinder_radius <= fit, who,
                    "cylinder radius " + internal::to_string_g(p.cylinder_radius) +
                      " is wider than its half of the box top allows (at most " + internal::to_string_g(fit) +
                      " = 0.9 x min(length/4, width/2)); use a thinner cylinder or a larger box");

  const CAD_mesh box = make_box_mesh(CAD_mesh::Point(-0.5 * p.box_length, -0.5 * p.box_width, 0.),
                                     CAD_mesh::Point(0.5 * p.box_length, 0.5 * p.box_width, p.box_height));
  const double overshoot = 0.1 * p.box_height;
  const CAD_mesh drill = make_cylinder_mesh(CAD_mesh::Point(-0.25 * p.box_length, 0., -overshoot),
                                            p.hole_radius, p.box_height + 2. * overshoot, p.segments,
                                              internal::outer_turn);
  const double sink = 0.25 * p.box_height;
  const CAD_mesh cylinder = make_cylinder_mesh(CAD_mesh::Point(0.25 * p.box_length, 0., p.box_height - sink),
                                               p.cylinder_radius, p.cylinder_height + sink, p.segments,
                                               internal::outer_turn);
  const CAD_mesh holed = internal::boolean(internal::Boolean_operation::Difference, box, drill, who, "box", "hole");
  CAD_mesh result = internal::boolean(internal::Boolean_operation::Union, holed, cylinder, who,
                                      "holed box", "cylinder");
  internal::check_solid(result, who, 1);
  return result;
}

/// \ingroup PkgBlendedShapeScanning
/// The Fig. 24 family by its two varying parameters (the box is 4 x 2 x 1 with a
/// hole of radius 0.5; the cylinder radius is at most 0.9).
inline CAD_mesh make_box_hole_cylinder(double cylinder_height = 1., double cylinder_radius = 0.5,
                                       std::size_t segments = 40)
{
  Box_hole_cylinder_parameters p;
  p.cylinder_height = cylinder_height;
  p.cylinder_radius = cylinder_radius;
  p.segments = segments;
  return make_box_hole_cylinder(p);
}

/// @}

} // namespace Blended_shapes
} // namespace CGAL

#endif // CGAL_BLENDED_SHAPE_SCANNING_CAD_OBJECTS_H
