// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_BLENDED_SHAPE_SCANNING_RANGE_SCAN_SIMULATOR_H
#define CGAL_BLENDED_SHAPE_SCANNING_RANGE_SCAN_SIMULATOR_H

#include <CGAL/Blended_shape/IO/Input_error.h>
#include <CGAL/Blended_shape/internal/write_file_atomically.h>

#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Kernel_traits.h>
#include <CGAL/boost/graph/helpers.h>
#include <CGAL/boost/graph/iterator.h>
#include <CGAL/boost/graph/properties.h>
#include <CGAL/number_utils.h>

#include <boost/variant/get.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <iomanip>
#include <limits>
#include <ostream>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace CGAL {
namespace Blended_shapes {

/// \ingroup PkgBlendedShapeScanning
/// How a Camera maps pixels to rays.
enum class Projection
{
  Perspective, ///< all rays start at the eye; `field_of_view_degrees` is the vertical angle
  Orthographic ///< parallel rays along the view direction; `view_height` is the vertical extent
};

/*!
\ingroup PkgBlendedShapeScanning

A pinhole (or parallel) range camera: the virtual scanner of the paper's
sec. 6 ("a CAD utility which simulates the scanning process on a polygon mesh").

The image has `width` x `height` pixels; pixel (row 0, column 0) is the top left
one, rows go down along `-up`, columns go right. Each pixel casts one ray
through its centre. With `Projection::Orthographic` the rays start on the plane
through `eye` orthogonal to the view direction, so only surfaces in front of
that plane are seen.

Use validate() (or the simulator, which calls it) to check a camera.

\tparam GeomTraits a CGAL kernel.
*/
template <class GeomTraits>
struct Camera
{
  typedef typename GeomTraits::Point_3 Point_3;   ///< the point type
  typedef typename GeomTraits::Vector_3 Vector_3; ///< the vector type

  Point_3 eye = Point_3(0, 0, 1);    ///< the camera position (orthographic: a point of the ray plane)
  Point_3 target = Point_3(0, 0, 0); ///< the point looked at: the view direction is `target - eye`
  Vector_3 up = Vector_3(0, 1, 0); ///< need not be orthogonal to the view direction
  Projection projection = Projection::Perspective; ///< perspective or parallel rays
  double field_of_view_degrees = 40.; ///< perspective only, in (0, 180)
  double view_height = 1.;            ///< orthographic only, world units, > 0
  std::size_t width = 200;  ///< image width in pixels (columns)
  std::size_t height = 200; ///< image height in pixels (rows)

  /// The largest accepted `width * height`: beyond it a scan would exhaust memory.
  static constexpr double maximum_number_of_pixels = 1e8;

  /// A perspective camera at `eye` looking at `target`.
  static Camera perspective(const Point_3& eye, const Point_3& target, const Vector_3& up,
                            double field_of_view_degrees, std::size_t width, std::size_t height)
  {
    Camera c;
    c.eye = eye;
    c.target = target;
    c.up = up;
    c.projection = Projection::Perspective;
    c.field_of_view_degrees = field_of_view_degrees;
    c.width = width;
    c.height = height;
    return c;
  }

  /// An orthographic camera: parallel rays from the plane through `eye`, toward `target`.
  static Camera orthographic(const Point_3& eye, const Point_3& target, const Vector_3& up,
                             double view_height, std::size_t width, std::size_t height)
  {
    Camera c = perspective(eye, target, up, 40., width, height);
    c.projection = Projection::Orthographic;
    c.view_height = view_height;
    return c;
  }

  /// \throws std::invalid_argument saying what is wrong: numbers that are not finite
  /// or beyond `maximum_coordinate_magnitude`,
  /// `eye == target`, `up` null or parallel to the view direction, a field of
  /// view outside (0, 180) degrees, a non-positive view height, zero pixels or
  /// more than `maximum_number_of_pixels`.
  void validate() const;
};

/// \ingroup PkgBlendedShapeScanning
/// Options of a scan. The noise and the dropout are drawn from a
/// `std::mt19937_64` seeded from `random_seed` and the view index, with the
/// same number of draws for every pixel, so a scan is reproducible on every
/// platform and each view's noise does not depend on the other views.
struct Scan_options
{
  double noise_sigma = 0.;          ///< standard deviation of the range noise along the ray, world units
  double dropout_probability = 0.;  ///< probability that a hit pixel returns no sample, in [0, 1]
  std::uint64_t random_seed = 0;    ///< seed of the noise and the dropout

  /// Checks the options.
  /// \throws std::invalid_argument if `noise_sigma` is negative or not finite,
  /// or if `dropout_probability` is not in [0, 1].
  void validate() const
  {
    if(!(std::isfinite(noise_sigma) && noise_sigma >= 0.))
    {
      std::ostringstream msg;
      msg << "Scan_options: noise sigma " << noise_sigma
          << " is not a finite non-negative number; use 0 for noise-free range data";
      throw std::invalid_argument(msg.str());
    }
    if(!(dropout_probability >= 0. && dropout_probability <= 1.))
    {
      std::ostringstream msg;
      msg << "Scan_options: dropout probability " << dropout_probability
          << " is not in [0, 1]; use 0 to keep every hit pixel";
      throw std::invalid_argument(msg.str());
    }
  }
};

/// \ingroup PkgBlendedShapeScanning
/// One range measurement.
template <class GeomTraits>
struct Range_sample
{
  typename GeomTraits::Point_3 point;    ///< the measured point (first hit of the pixel's ray, plus noise)
  typename GeomTraits::Vector_3 normal; ///< unit normal of the hit face, facing the camera
  std::size_t view = 0;                 ///< index of the camera in a multi-view scan
  std::size_t row = 0;                  ///< pixel row, 0 at the top
  std::size_t column = 0;               ///< pixel column, 0 at the left
};

namespace internal {

struct Vec3
{
  double x, y, z;
};
inline Vec3 operator+(const Vec3& a, const Vec3& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline Vec3 operator-(const Vec3& a, const Vec3& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline Vec3 operator*(double s, const Vec3& a) { return {s * a.x, s * a.y, s * a.z}; }
inline double dot(const Vec3& a, const Vec3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline Vec3 cross(const Vec3& a, const Vec3& b)
{
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline double norm(const Vec3& a) { return std::sqrt(dot(a, a)); }
inline bool is_finite(const Vec3& a)
{
  return std::isfinite(a.x) && std::isfinite(a.y) && std::isfinite(a.z);
}
// Finite, and small enough that squared distances do not overflow (the
// limit of the points, maximum_coordinate_magnitude).
inline bool in_range(const Vec3& a)
{
  return are_coordinates_in_range(a.x, a.y, a.z);
}

template <class P>
Vec3 to_vec3(const P& p)
{
  return {CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z())};
}

inline std::string to_string(const Vec3& a)
{
  std::ostringstream s;
  s << '(' << a.x << ", " << a.y << ", " << a.z << ')';
  return s.str();
}

inline std::string out_of_range_vertex_message(const std::string& who)
{
  return who + ": the mesh has a vertex with a coordinate that is " + out_of_range_coordinate_words() +
         "; fix the mesh, or express it in a larger unit";
}

// The orthonormal frame and image-plane extent of a validated camera.
struct Camera_frame
{
  Vec3 eye, forward, right, up;
  double half_width, half_height;
  bool perspective;
};

template <class GeomTraits>
Camera_frame camera_frame(const Camera<GeomTraits>& c)
{
  const Vec3 eye = to_vec3(c.eye), target = to_vec3(c.target), up = to_vec3(c.up);
  auto fail = [](const std::string& what) {
    throw std::invalid_argument("Camera: " + what);
  };
  if(!in_range(eye) || !in_range(target) || !in_range(up))
  {
    std::ostringstream limit;
    limit << maximum_coordinate_magnitude;
    fail("eye " + to_string(eye) + ", target " + to_string(target) + " or up " + to_string(up) +
         " has a coordinate that is " + out_of_range_coordinate_words() + "; give finite numbers at most " +
         limit.str());
  }
  const Vec3 view = target - eye;
  const double distance = norm(view);
  if(!(distance > 0.))
    fail("eye and target are the same point " + to_string(eye) +
         "; put the eye away from the target it looks at");
  const double up_length = norm(up);
  if(!(up_length > 0.))
    fail("the up vector is null; give a direction such as 0,0,1");

  Camera_frame f;
  f.eye = eye;
  f.forward = (1. / distance) * view;
  const Vec3 side = cross(f.forward, (1. / up_length) * up);
  const double sine = norm(side); // sine of the angle between up and the view direction
  if(!(sine > 1e-9))
    fail("the up vector " + to_string(up) + " is parallel to the view direction " +
         to_string(f.forward) + "; choose an up vector across the view direction");
  f.right = (1. / sine) * side;
  f.up = cross(f.right, f.forward);

  if(c.width == 0 || c.height == 0)
    fail("the image has " + std::to_string(c.width) + " x " + std::to_string(c.height) +
         " pixels; width and height must be at least 1");
  if(double(c.width) * double(c.height) > Camera<GeomTraits>::maximum_number_of_pixels)
    fail("the image has " + std::to_string(c.width) + " x " + std::to_string(c.height) +
         " pixels, more than the limit of 1e8; use a smaller resolution or several views");

  const double aspect = double(c.width) / double(c.height);
  if(c.projection == Projection::Perspective)
  {
    if(!(c.field_of_view_degrees > 0. && c.field_of_view_degrees < 180.))
    {
      std::ostringstream msg;
      msg << "the field of view " << c.field_of_view_degrees
          << " degrees is not in (0, 180); use for example 40";
      fail(msg.str());
    }
    f.half_height = std::tan(0.5 * c.field_of_view_degrees * M_PI / 180.);
    f.perspective = true;
  }
  else
  {
    if(!(std::isfinite(c.view_height) && c.view_height > 0.))
    {
      std::ostringstream msg;
      msg << "the orthographic view height " << c.view_height
          << " is not a positive finite number; give the vertical extent of the view in world units";
      fail(msg.str());
    }
    f.half_height = 0.5 * c.view_height;
    f.perspective = false;
  }
  f.half_width = f.half_height * aspect;
  return f;
}

// splitmix64: spreads (seed, view) over the whole state so that nearby seeds
// and views give unrelated streams.
inline std::uint64_t mix_seed(std::uint64_t x)
{
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

// A uniform double in [0, 1) from the top 53 bits: the same on every platform,
// unlike std::uniform_real_distribution.
inline double uniform01(std::mt19937_64& rng) { return double(rng() >> 11) * 0x1.0p-53; }

} // namespace internal

template <class GeomTraits>
void Camera<GeomTraits>::validate() const
{
  internal::camera_frame(*this);
}

/*!
\ingroup PkgBlendedShapeScanning

Simulates a range scanner on a triangle mesh: one ray per pixel, the first hit
only, through an AABB tree built once in the constructor (so many views of the
same mesh are cheap). The mesh must outlive the simulator and not change.

Every sample lies on the mesh up to rounding when `noise_sigma` is 0; the range
noise moves it along its ray, so it models the depth error of a scanner.

\tparam TriangleMesh a model of `FaceListGraph` with triangle faces (e.g. `CGAL::Surface_mesh`).
\tparam GeomTraits the kernel of the mesh points (deduced).
*/
template <class TriangleMesh,
          class GeomTraits = typename Kernel_traits<typename boost::property_traits<
            typename boost::property_map<TriangleMesh, vertex_point_t>::const_type>::value_type>::Kernel>
class Range_scan_simulator
{
public:
  typedef GeomTraits Geom_traits;                     ///< the kernel
  typedef typename Geom_traits::Point_3 Point_3;       ///< the point type
  typedef typename Geom_traits::Vector_3 Vector_3;     ///< the vector type
  typedef typename Geom_traits::Ray_3 Ray_3;           ///< the ray type
  typedef typename Geom_traits::Segment_3 Segment_3;   ///< the segment type
  typedef Blended_shapes::Camera<Geom_traits> Camera;  ///< the camera type
  typedef Range_sample<Geom_traits> Sample;            ///< one range measurement

private:
  typedef AABB_face_graph_triangle_primitive<TriangleMesh> Primitive;
  typedef AABB_traits<Geom_traits, Primitive> Traits;
  typedef AABB_tree<Traits> Tree;
  typedef typename boost::graph_traits<TriangleMesh>::face_descriptor face_descriptor;
  typedef typename boost::graph_traits<TriangleMesh>::halfedge_descriptor halfedge_descriptor;

public:
  /// Faces with collinear corners (no area) are not scanned.
  /// \throws std::invalid_argument if the mesh has no face, a non-triangle
  /// face, a vertex coordinate that is not finite or beyond
  /// `maximum_coordinate_magnitude`, or only faces with collinear corners.
  explicit Range_scan_simulator(const TriangleMesh& mesh)
    : m_mesh(mesh)
  {
    if(faces(mesh).first == faces(mesh).second)
      throw std::invalid_argument(
        "Range_scan_simulator: the mesh has no face; there is nothing to scan (check the mesh file)");
    if(!is_triangle_mesh(mesh))
      throw std::invalid_argument(
        "Range_scan_simulator: the mesh has non-triangle faces; triangulate it first "
        "(CGAL::Polygon_mesh_processing::triangulate_faces)");
    for(auto v : vertices(mesh))
      if(!internal::in_range(internal::to_vec3(get(vertex_point, mesh, v))))
        throw std::invalid_argument(internal::out_of_range_vertex_message("Range_scan_simulator"));
    // A face with collinear corners has no area and no plane: a ray cannot
    // see it (the faces around it cover what it spans), and intersecting a
    // ray with it is undefined (CGAL's precondition), so it is left out.
    std::vector<face_descriptor> seen;
    const auto collinear = Geom_traits().collinear_3_object();
    for(face_descriptor f : faces(mesh))
    {
      const halfedge_descriptor h = halfedge(f, mesh);
      if(!collinear(get(vertex_point, mesh, source(h, mesh)), get(vertex_point, mesh, target(h, mesh)),
                    get(vertex_point, mesh, target(next(h, mesh), mesh))))
        seen.push_back(f);
    }
    if(seen.empty())
      throw std::invalid_argument(
        "Range_scan_simulator: every face of the mesh is degenerate (collinear corners, no area); "
        "there is no surface to scan (check the mesh file)");
    m_tree.insert(seen.begin(), seen.end(), mesh);
    m_tree.build();
  }

  /// Scans from one camera; `view_index` is stored in the samples and selects
  /// the random stream, so that scan(cameras) equals the concatenation of
  /// scan(cameras[k], options, k).
  /// \throws std::invalid_argument for a bad camera or bad options.
  std::vector<Sample> scan(const Camera& camera, const Scan_options& options = Scan_options(),
                           std::size_t view_index = 0) const
  {
    const internal::Camera_frame f = internal::camera_frame(camera);
    options.validate();
    std::mt19937_64 rng(internal::mix_seed(internal::mix_seed(options.random_seed) ^ view_index));

    std::vector<Sample> samples;
    for(std::size_t row = 0; row < camera.height; ++row)
    {
      const double y = (1. - 2. * (double(row) + 0.5) / double(camera.height)) * f.half_height;
      for(std::size_t column = 0; column < camera.width; ++column)
      {
        // Three draws per pixel whether it hits or not: the noise of a pixel
        // does not depend on what the other pixels saw.
        const double u_drop = internal::uniform01(rng);
        const double u1 = internal::uniform01(rng);
        const double u2 = internal::uniform01(rng);

        const double x = (2. * (double(column) + 0.5) / double(camera.width) - 1.) * f.half_width;
        internal::Vec3 origin = f.eye, direction = f.forward;
        if(f.perspective)
          direction = f.forward + x * f.right + y * f.up;
        else
          origin = f.eye + x * f.right + y * f.up;

        Sample s;
        if(!cast(origin, direction, s))
          continue;
        if(options.dropout_probability > 0. && u_drop < options.dropout_probability)
          continue;
        if(options.noise_sigma > 0.)
        {
          // Box-Muller; 1 - u1 is in (0, 1] so the logarithm is finite.
          const double g = std::sqrt(-2. * std::log(1. - u1)) * std::cos(2. * M_PI * u2);
          const internal::Vec3 d = (options.noise_sigma * g / internal::norm(direction)) * direction;
          s.point = s.point + Vector_3(d.x, d.y, d.z);
          if(!internal::is_finite(internal::to_vec3(s.point)))
          {
            std::ostringstream msg;
            msg << "Range_scan_simulator: noise sigma " << options.noise_sigma
                << " moves a sample past the largest finite coordinate; give a noise on the scale of the mesh";
            throw std::invalid_argument(msg.str());
          }
        }
        s.view = view_index;
        s.row = row;
        s.column = column;
        samples.push_back(s);
      }
    }
    return samples;
  }

  /// Scans from each camera in turn and merges the samples; view `k` uses
  /// `cameras[k]` and the random stream of view index `k`.
  std::vector<Sample> scan(const std::vector<Camera>& cameras,
                           const Scan_options& options = Scan_options()) const
  {
    for(const Camera& c : cameras) // fail before any work
      c.validate();
    std::vector<Sample> all;
    for(std::size_t k = 0; k < cameras.size(); ++k)
    {
      std::vector<Sample> view = scan(cameras[k], options, k);
      all.insert(all.end(), view.begin(), view.end());
    }
    return all;
  }

  /// The scanned mesh.
  const TriangleMesh& mesh() const { return m_mesh; }

private:
  // First hit of the ray; fills the point and the camera-facing unit normal.
  bool cast(const internal::Vec3& o, const internal::Vec3& d, Sample& s) const
  {
    const Ray_3 ray(Point_3(o.x, o.y, o.z), Vector_3(d.x, d.y, d.z));
    const auto hit = m_tree.first_intersection(ray);
    if(!hit)
      return false;
    if(const Point_3* p = boost::get<Point_3>(&hit->first))
      s.point = *p;
    else
    {
      // The ray lies in the triangle's plane: the nearest end of the overlap is the hit.
      const Segment_3& seg = boost::get<Segment_3>(hit->first);
      const internal::Vec3 a = internal::to_vec3(seg.source()), b = internal::to_vec3(seg.target());
      s.point = internal::dot(a - o, d) <= internal::dot(b - o, d) ? seg.source() : seg.target();
    }

    const halfedge_descriptor h = halfedge(hit->second, m_mesh);
    const internal::Vec3 p0 = internal::to_vec3(get(vertex_point, m_mesh, source(h, m_mesh)));
    const internal::Vec3 p1 = internal::to_vec3(get(vertex_point, m_mesh, target(h, m_mesh)));
    const internal::Vec3 p2 =
      internal::to_vec3(get(vertex_point, m_mesh, target(next(h, m_mesh), m_mesh)));
    internal::Vec3 n = internal::cross(p1 - p0, p2 - p0);
    const double len = internal::norm(n);
    if(len > 0.)
      n = ((internal::dot(n, d) > 0. ? -1. : 1.) / len) * n;
    else // a degenerate face has no normal: face the camera
      n = (-1. / internal::norm(d)) * d;
    s.normal = Vector_3(n.x, n.y, n.z);
    return true;
  }

  const TriangleMesh& m_mesh;
  Tree m_tree;
};

/// \ingroup PkgBlendedShapeScanning
/// One-call scan of `mesh` from `camera` (builds the AABB tree each call).
/// \throws std::invalid_argument for an empty mesh, a bad camera or bad options.
template <class TriangleMesh, class GeomTraits>
std::vector<Range_sample<GeomTraits>>
simulate_range_scan(const TriangleMesh& mesh, const Camera<GeomTraits>& camera,
                    const Scan_options& options = Scan_options())
{
  camera.validate(); // before the tree is built
  return Range_scan_simulator<TriangleMesh, GeomTraits>(mesh).scan(camera, options, 0);
}

/// \ingroup PkgBlendedShapeScanning
/// One-call multi-view scan: the merged samples of every camera (see Range_scan_simulator::scan()).
template <class TriangleMesh, class GeomTraits>
std::vector<Range_sample<GeomTraits>>
simulate_range_scan(const TriangleMesh& mesh, const std::vector<Camera<GeomTraits>>& cameras,
                    const Scan_options& options = Scan_options())
{
  for(const auto& c : cameras)
    c.validate();
  return Range_scan_simulator<TriangleMesh, GeomTraits>(mesh).scan(cameras, options);
}

/*!
\ingroup PkgBlendedShapeScanning

A single perspective view of the whole mesh: the eye looks at the centre of
the bounding box from the direction (1, 0.6, 0.8), at the distance where the
box's bounding sphere just fits a 40 degree field of view; z is up; 200 x 200 pixels.

\throws std::invalid_argument if the mesh has no vertex, a coordinate that is not
finite or beyond `maximum_coordinate_magnitude`, or all its vertices at one point.
*/
template <class TriangleMesh>
Camera<typename Kernel_traits<typename boost::property_traits<
  typename boost::property_map<TriangleMesh, vertex_point_t>::const_type>::value_type>::Kernel>
default_camera_for(const TriangleMesh& mesh)
{
  typedef typename Kernel_traits<typename boost::property_traits<
    typename boost::property_map<TriangleMesh, vertex_point_t>::const_type>::value_type>::Kernel K;
  if(vertices(mesh).first == vertices(mesh).second)
    throw std::invalid_argument(
      "default_camera_for: the mesh has no vertex; there is nothing to look at");
  const double inf = std::numeric_limits<double>::infinity();
  internal::Vec3 lo{inf, inf, inf}, hi{-inf, -inf, -inf};
  for(auto v : vertices(mesh))
  {
    const internal::Vec3 p = internal::to_vec3(get(vertex_point, mesh, v));
    if(!internal::in_range(p))
      throw std::invalid_argument(internal::out_of_range_vertex_message("default_camera_for"));
    lo = {(std::min)(lo.x, p.x), (std::min)(lo.y, p.y), (std::min)(lo.z, p.z)};
    hi = {(std::max)(hi.x, p.x), (std::max)(hi.y, p.y), (std::max)(hi.z, p.z)};
  }
  const internal::Vec3 center = 0.5 * (lo + hi);
  const double radius = 0.5 * internal::norm(hi - lo);
  if(!(radius > 0.))
    throw std::invalid_argument(
      "default_camera_for: all vertices of the mesh are at one point; there is no surface to look at");

  const double fov = 40.;
  const internal::Vec3 dir{1., 0.6, 0.8};
  const double distance = radius / std::sin(0.5 * fov * M_PI / 180.);
  const internal::Vec3 eye = center + (distance / internal::norm(dir)) * dir;
  return Camera<K>::perspective(typename K::Point_3(eye.x, eye.y, eye.z),
                                typename K::Point_3(center.x, center.y, center.z),
                                typename K::Vector_3(0, 0, 1), fov, 200, 200);
}

/// \name Writing range scans
/// @{

/// \ingroup PkgBlendedShapeScanning
/// Writes one sample per line, `x y z` (and `nx ny nz` if `with_normals`),
/// with enough digits to read the same doubles back.
template <class GeomTraits>
void write_range_scan_xyz(std::ostream& out, const std::vector<Range_sample<GeomTraits>>& samples,
                          bool with_normals = false)
{
  out << std::setprecision(std::numeric_limits<double>::max_digits10);
  // Adding +0 turns -0 into 0, which reads better and compares equal anyway.
  auto value = [](const auto& x) { return CGAL::to_double(x) + 0.; };
  for(const auto& s : samples)
  {
    out << value(s.point.x()) << ' ' << value(s.point.y()) << ' ' << value(s.point.z());
    if(with_normals)
      out << ' ' << value(s.normal.x()) << ' ' << value(s.normal.y()) << ' ' << value(s.normal.z());
    out << '\n';
  }
}

/// \ingroup PkgBlendedShapeScanning
/// Writes an ASCII PLY point cloud with double properties `x y z` (and `nx ny nz`).
template <class GeomTraits>
void write_range_scan_ply(std::ostream& out, const std::vector<Range_sample<GeomTraits>>& samples,
                          bool with_normals = false)
{
  out << "ply\nformat ascii 1.0\ncomment simulated range scan\n"
      << "element vertex " << samples.size() << '\n'
      << "property double x\nproperty double y\nproperty double z\n";
  if(with_normals)
    out << "property double nx\nproperty double ny\nproperty double nz\n";
  out << "end_header\n";
  write_range_scan_xyz(out, samples, with_normals);
}

/// \ingroup PkgBlendedShapeScanning
/// Writes `samples` to `filename` as `.xyz` or `.ply` (chosen by the
/// extension, case-insensitive), through a temporary file renamed at the end:
/// on failure no file, and no half-written file, is left.
/// \throws std::invalid_argument for another extension;
///         std::runtime_error if the file cannot be written.
template <class GeomTraits>
void write_range_scan(const std::string& filename,
                      const std::vector<Range_sample<GeomTraits>>& samples,
                      bool with_normals = false)
{
  const std::size_t dot = filename.find_last_of('.');
  std::string ext = dot == std::string::npos ? std::string() : filename.substr(dot + 1);
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return char(std::tolower(c)); });
  if(ext != "xyz" && ext != "ply")
    throw std::invalid_argument("write_range_scan: '" + filename +
                                "' has neither the .xyz nor the .ply extension; use one of them");
  internal::write_file_atomically(filename, [&](std::ostream& out) {
    if(ext == "ply")
      write_range_scan_ply(out, samples, with_normals);
    else
      write_range_scan_xyz(out, samples, with_normals);
  });
}

/// @}

} // namespace Blended_shapes
} // namespace CGAL

#endif // CGAL_BLENDED_SHAPE_SCANNING_RANGE_SCAN_SIMULATOR_H
