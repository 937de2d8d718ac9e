// SPDX-License-Identifier: LGPL-3.0-or-later
// Tests of the range scan simulator (both kernels), the CAD test objects and
// the two command-line tools built on them. Geometric claims are checked
// against brute force over all triangles; randomness against its statistics.

#include <CGAL/Blended_shape/Scanning/CAD_objects.h>
#include <CGAL/Blended_shape/Scanning/Range_scan_simulator.h>

#include "test_kernels.h"
#include "test_util.h"
#include "tool_test_util.h"

#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/IO/read_points.h>
#include <CGAL/Polygon_mesh_processing/connected_components.h>
#include <CGAL/Polygon_mesh_processing/manifoldness.h>
#include <CGAL/Polygon_mesh_processing/orientation.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/helpers.h>
#include <CGAL/property_map.h>

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <limits>
#include <map>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace fs = std::filesystem;
namespace BS = CGAL::Blended_shapes;
namespace PMP = CGAL::Polygon_mesh_processing;

typedef CGAL::Simple_cartesian<double> SC;
typedef CGAL::Exact_predicates_inexact_constructions_kernel EPICK;

namespace {

int failures() { return blended_shape_test::failures(); }

void report(const std::string& name, int failures_before)
{
  std::cout << name << (failures() == failures_before ? ": SUCCESS" : ": FAILED") << std::endl;
}

template <class K>
std::string kernel_name()
{
  return std::is_same<K, SC>::value ? "Simple_cartesian<double>" : "Epick";
}

// ---------------------------------------------------------------- meshes

template <class K>
using Mesh = CGAL::Surface_mesh<typename K::Point_3>;

// A geodesic sphere: each icosahedron face split into frequency^2 triangles,
// vertices pushed onto the sphere. A vertex is keyed by its barycentric
// weights on the icosahedron vertices, so shared edges are welded exactly.
template <class K>
Mesh<K> make_icosphere(double radius, int frequency)
{
  const double t = (1. + std::sqrt(5.)) / 2.;
  const std::array<std::array<double, 3>, 12> ico = {{{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0},
                                                      {0, -1, t}, {0, 1, t}, {0, -1, -t}, {0, 1, -t},
                                                      {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}}};
  const int faces[20][3] = {{0, 11, 5}, {0, 5, 1}, {0, 1, 7}, {0, 7, 10}, {0, 10, 11},
                            {1, 5, 9}, {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                            {3, 9, 4}, {3, 4, 2}, {3, 2, 6}, {3, 6, 8}, {3, 8, 9},
                            {4, 9, 5}, {2, 4, 11}, {6, 2, 10}, {8, 6, 7}, {9, 8, 1}};
  Mesh<K> m;
  typedef typename Mesh<K>::Vertex_index V;
  std::map<std::vector<std::pair<int, int>>, V> index;
  auto vertex = [&](const int c[3], int i, int j) {
    const int w[3] = {frequency - i - j, i, j};
    std::vector<std::pair<int, int>> key;
    for(int k = 0; k < 3; ++k)
      if(w[k] > 0)
        key.emplace_back(c[k], w[k]);
    std::sort(key.begin(), key.end());
    auto it = index.find(key);
    if(it != index.end())
      return it->second;
    double p[3] = {0, 0, 0};
    for(const auto& kw : key) // same order for every face: identical rounding
      for(int d = 0; d < 3; ++d)
        p[d] += double(kw.second) * ico[std::size_t(kw.first)][std::size_t(d)];
    const double n = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
    const V v = m.add_vertex(typename K::Point_3(radius * p[0] / n, radius * p[1] / n, radius * p[2] / n));
    index.emplace(key, v);
    return v;
  };
  for(const auto& f : faces)
    for(int i = 0; i < frequency; ++i)
      for(int j = 0; i + j < frequency; ++j)
      {
        m.add_face(vertex(f, i, j), vertex(f, i + 1, j), vertex(f, i, j + 1));
        if(i + j + 2 <= frequency)
          m.add_face(vertex(f, i + 1, j), vertex(f, i + 1, j + 1), vertex(f, i, j + 1));
      }
  return m;
}

// A CAD object (Epick points) in another kernel.
template <class K>
Mesh<K> convert(const BS::CAD_mesh& in)
{
  Mesh<K> out;
  std::map<BS::CAD_mesh::Vertex_index, typename Mesh<K>::Vertex_index> v;
  for(auto u : in.vertices())
  {
    const auto& p = in.point(u);
    v[u] = out.add_vertex(typename K::Point_3(p.x(), p.y(), p.z()));
  }
  for(auto f : in.faces())
  {
    std::vector<typename Mesh<K>::Vertex_index> poly;
    for(auto u : CGAL::vertices_around_face(in.halfedge(f), in))
      poly.push_back(v[u]);
    out.add_face(poly);
  }
  return out;
}

// Two triangles: the square [-1, 1]^2 at z = 0.
template <class K>
Mesh<K> make_square()
{
  Mesh<K> m;
  auto a = m.add_vertex(typename K::Point_3(-1, -1, 0)), b = m.add_vertex(typename K::Point_3(1, -1, 0));
  auto c = m.add_vertex(typename K::Point_3(1, 1, 0)), d = m.add_vertex(typename K::Point_3(-1, 1, 0));
  m.add_face(a, b, c);
  m.add_face(a, c, d);
  return m;
}

template <class K>
double bbox_diagonal(const Mesh<K>& m)
{
  CGAL::Bbox_3 b;
  for(auto v : m.vertices())
    b += m.point(v).bbox();
  return std::sqrt(CGAL::square(b.xmax() - b.xmin()) + CGAL::square(b.ymax() - b.ymin()) +
                   CGAL::square(b.zmax() - b.zmin()));
}

template <class K>
std::vector<typename K::Triangle_3> triangles(const Mesh<K>& m)
{
  std::vector<typename K::Triangle_3> t;
  for(auto f : m.faces())
  {
    auto h = m.halfedge(f);
    t.emplace_back(m.point(m.source(h)), m.point(m.target(h)), m.point(m.target(m.next(h))));
  }
  return t;
}

template <class K>
struct Distance_tree
{
  typedef CGAL::AABB_face_graph_triangle_primitive<Mesh<K>> Primitive;
  typedef CGAL::AABB_tree<CGAL::AABB_traits<K, Primitive>> Tree;
  Tree tree;
  explicit Distance_tree(const Mesh<K>& m) : tree(faces(m).first, faces(m).second, m)
  {
    tree.accelerate_distance_queries();
  }
  double distance(const typename K::Point_3& p) const
  {
    return std::sqrt(CGAL::to_double(tree.squared_distance(p)));
  }
};

template <class K>
typename K::Vector_3 unit(const typename K::Vector_3& v)
{
  return v / std::sqrt(CGAL::to_double(v.squared_length()));
}

// ---------------------------------------------------------------- simulator tests

// Noise-free samples lie on the mesh (AABB and brute force agree), and the
// segment from each sample to the eye crosses no triangle (first hit only).
template <class K>
void test_points_on_mesh_and_visible(const std::string& what, const Mesh<K>& mesh,
                                     const typename K::Point_3& eye)
{
  const int before = failures();
  const double diag = bbox_diagonal<K>(mesh);
  BS::Range_scan_simulator<Mesh<K>> simulator(mesh);
  const auto samples =
    simulator.scan(BS::Camera<K>::perspective(eye, typename K::Point_3(0, 0, 0.5), typename K::Vector_3(0, 0, 1),
                                              45., 48, 40));
  BS_CHECK(samples.size() > 300, what << ": only " << samples.size() << " samples");

  const Distance_tree<K> tree(mesh);
  const auto tri = triangles<K>(mesh);
  double worst_aabb = 0., worst_brute = 0.;
  std::size_t hidden = 0, bad_normals = 0;
  for(const auto& s : samples)
  {
    worst_aabb = (std::max)(worst_aabb, tree.distance(s.point));
    double best = std::numeric_limits<double>::infinity();
    for(const auto& t : tri)
      best = (std::min)(best, CGAL::to_double(CGAL::squared_distance(s.point, t)));
    worst_brute = (std::max)(worst_brute, std::sqrt(best));

    const typename K::Vector_3 to_eye = unit<K>(eye - s.point);
    const typename K::Point_3 start = s.point + 1e-9 * diag * to_eye;
    const typename K::Segment_3 seg(start, eye);
    for(const auto& t : tri)
      if(CGAL::do_intersect(seg, t))
      {
        ++hidden;
        break;
      }
    const double n_len = std::sqrt(CGAL::to_double(s.normal.squared_length()));
    if(std::abs(n_len - 1.) > 1e-12 || CGAL::to_double(s.normal * to_eye) < 0.)
      ++bad_normals;
  }
  BS_CHECK(worst_aabb < 1e-9 * diag, what << ": a sample is " << worst_aabb << " from the mesh (AABB)");
  BS_CHECK(worst_brute < 1e-9 * diag, what << ": a sample is " << worst_brute << " from the mesh (brute force)");
  BS_CHECK(hidden == 0, what << ": " << hidden << " samples are hidden from the eye");
  BS_CHECK(bad_normals == 0, what << ": " << bad_normals << " normals are not unit or face away from the eye");
  report("points_on_mesh_and_visible<" + kernel_name<K>() + "> " + what, before);
}

// A sphere seen from far away: about half of it is covered, none of the far half.
template <class K>
void test_sphere_half_covered(bool orthographic)
{
  const int before = failures();
  const std::string name = std::string("sphere_half_covered<") + kernel_name<K>() + "> " +
                           (orthographic ? "orthographic" : "perspective");
  const double R = 1.;
  const Mesh<K> sphere = make_icosphere<K>(R, 10);
  BS_CHECK(sphere.number_of_faces() == 2000, "icosphere has " << sphere.number_of_faces() << " faces");
  const typename K::Vector_3 d = unit<K>(typename K::Vector_3(0.3, -0.5, 0.8)); // towards the eye
  const typename K::Point_3 o(0, 0, 0);
  const auto camera =
    orthographic ? BS::Camera<K>::orthographic(o + 3. * R * d, o, typename K::Vector_3(0, 0, 1), 2.2 * R, 160, 160)
                 : BS::Camera<K>::perspective(o + 100. * R * d, o,
                                              typename K::Vector_3(0, 0, 1),
                                              2.2 * std::asin(1. / 100.) * 180. / M_PI, 160, 160);
  const auto samples = BS::simulate_range_scan(sphere, camera);
  BS_CHECK(samples.size() > 10000, name << ": only " << samples.size() << " samples");

  double longest_edge = 0.;
  for(auto e : sphere.edges())
    longest_edge = (std::max)(longest_edge, std::sqrt(CGAL::to_double(CGAL::squared_distance(
                                              sphere.point(sphere.source(e.halfedge())),
                                              sphere.point(sphere.target(e.halfedge()))))));
  std::size_t far = 0;
  for(const auto& s : samples)
    if(CGAL::to_double((s.point - o) * d) < -longest_edge)
      ++far;
  BS_CHECK(far == 0, name << ": " << far << " samples on the far hemisphere");

  std::size_t facing = 0, covered = 0;
  const double near = 0.05 * R;
  for(auto v : sphere.vertices())
  {
    const typename K::Vector_3 n = unit<K>(sphere.point(v) - o);
    if(CGAL::to_double(n * d) < 0.2) // near the silhouette the sampling is too sparse
      continue;
    ++facing;
    for(const auto& s : samples)
      if(CGAL::to_double(CGAL::squared_distance(s.point, sphere.point(v))) < near * near)
      {
        ++covered;
        break;
      }
  }
  BS_CHECK(facing > 300, name << ": only " << facing << " vertices face the eye");
  BS_CHECK(double(covered) > 0.9 * double(facing),
           name << ": only " << covered << " of " << facing << " facing vertices have a sample nearby");
  report(name, before);
}

// The pixel grid: row 0 is at the top (along up), columns go right.
template <class K>
void test_image_orientation()
{
  const int before = failures();
  const Mesh<K> sphere = make_icosphere<K>(1., 6);
  const auto camera = BS::Camera<K>::perspective(typename K::Point_3(5, 0, 0), typename K::Point_3(0, 0, 0),
                                                 typename K::Vector_3(0, 0, 1), 30., 40, 30);
  const auto samples = BS::simulate_range_scan(sphere, camera);
  BS_CHECK(!samples.empty(), "no sample");
  // Looking along -x with z up, the right of the image is +y.
  double z_top = 0., z_bottom = 0., y_left = 0., y_right = 0.;
  std::size_t top = 0, bottom = 0, left = 0, right = 0;
  for(const auto& s : samples)
  {
    BS_CHECK(s.row < 30 && s.column < 40 && s.view == 0, "bad pixel " << s.row << ' ' << s.column);
    const double y = CGAL::to_double(s.point.y()), z = CGAL::to_double(s.point.z());
    if(s.row < 15) { z_top += z; ++top; } else { z_bottom += z; ++bottom; }
    if(s.column < 20) { y_left += y; ++left; } else { y_right += y; ++right; }
  }
  BS_CHECK(top > 0 && bottom > 0 && z_top / double(top) > 0.2 && z_bottom / double(bottom) < -0.2,
           "rows do not go down along -up");
  BS_CHECK(left > 0 && right > 0 && y_left / double(left) < -0.2 && y_right / double(right) > 0.2,
           "columns do not go right");
  report("image_orientation<" + kernel_name<K>() + ">", before);
}

// Range noise: RMS distance to a plane seen head-on is sigma; on a sphere,
// the displacement from the noise-free sample of the same pixel is along the
// ray with RMS sigma; seeds reproduce.
template <class K>
void test_noise()
{
  const int before = failures();
  typedef typename K::Point_3 P;
  typedef typename K::Vector_3 V;
  const double sigma = 0.01;
  BS::Scan_options noisy;
  noisy.noise_sigma = sigma;
  noisy.random_seed = 7;

  const Mesh<K> square = make_square<K>();
  const auto top = BS::Camera<K>::orthographic(P(0, 0, 5), P(0, 0, 0), V(0, 1, 0), 1.8, 64, 64);
  const auto plane_samples = BS::simulate_range_scan(square, top, noisy);
  BS_CHECK(plane_samples.size() == 64 * 64, "the square gives " << plane_samples.size() << " samples");
  const Distance_tree<K> square_tree(square);
  double sum2 = 0., sum = 0.;
  for(const auto& s : plane_samples)
  {
    const double dist = square_tree.distance(s.point);
    sum2 += dist * dist;
    sum += CGAL::to_double(s.point.z());
  }
  const double n = double(plane_samples.size());
  const double rms = std::sqrt(sum2 / n);
  BS_CHECK(std::abs(rms - sigma) < 0.2 * sigma, "plane: RMS distance " << rms << " for sigma " << sigma);
  BS_CHECK(std::abs(sum / n) < 0.1 * sigma, "plane: mean depth error " << sum / n << " is biased");

  const Mesh<K> sphere = make_icosphere<K>(1., 10);
  const P eye(2, 3, 1.5);
  const auto camera = BS::Camera<K>::perspective(eye, P(0, 0, 0), V(0, 0, 1), 40., 80, 80);
  BS::Range_scan_simulator<Mesh<K>> simulator(sphere);
  const auto clean = simulator.scan(camera);
  const auto a = simulator.scan(camera, noisy);
  const auto b = simulator.scan(camera, noisy);
  BS::Scan_options other = noisy;
  other.random_seed = 8;
  const auto c = simulator.scan(camera, other);
  BS_CHECK(a.size() == clean.size() && b.size() == a.size() && c.size() == a.size(),
           "noise changed the number of samples");
  if(a.size() == clean.size() && b.size() == a.size() && c.size() == a.size())
  {
    double s2 = 0., worst_side = 0.;
    std::size_t same_ab = 0, same_ac = 0;
    for(std::size_t i = 0; i < a.size(); ++i)
    {
      BS_CHECK(a[i].row == clean[i].row && a[i].column == clean[i].column, "pixel order changed");
      const V disp = a[i].point - clean[i].point;
      const V ray = unit<K>(clean[i].point - eye);
      s2 += CGAL::to_double(disp.squared_length());
      worst_side = (std::max)(worst_side, std::sqrt(CGAL::to_double(CGAL::cross_product(disp, ray).squared_length())));
      same_ab += (a[i].point == b[i].point && a[i].normal == b[i].normal) ? 1 : 0;
      same_ac += (a[i].point == c[i].point) ? 1 : 0;
    }
    const double rms_disp = std::sqrt(s2 / double(a.size()));
    BS_CHECK(a.size() > 2000, "only " << a.size() << " sphere samples");
    BS_CHECK(std::abs(rms_disp - sigma) < 0.2 * sigma, "sphere: RMS displacement " << rms_disp);
    BS_CHECK(worst_side < 1e-12, "sphere: noise moved a sample " << worst_side << " across its ray");
    BS_CHECK(same_ab == a.size(), "same seed: " << a.size() - same_ab << " samples differ");
    BS_CHECK(same_ac < a.size() / 100, "different seeds: " << same_ac << " samples are identical");
  }
  report("noise<" + kernel_name<K>() + ">", before);
}

// Dropout keeps about 1 - p of the pixels, a subset of the noise-free scan.
template <class K>
void test_dropout()
{
  const int before = failures();
  typedef typename K::Point_3 P;
  const Mesh<K> sphere = make_icosphere<K>(1., 10);
  const auto camera = BS::Camera<K>::perspective(P(0, 4, 1), P(0, 0, 0), typename K::Vector_3(0, 0, 1), 35., 70, 70);
  BS::Range_scan_simulator<Mesh<K>> simulator(sphere);
  const auto all = simulator.scan(camera);
  BS::Scan_options half;
  half.dropout_probability = 0.5;
  half.random_seed = 3;
  const auto kept = simulator.scan(camera, half);
  const double fraction = double(kept.size()) / double(all.size());
  BS_CHECK(all.size() > 2000, "only " << all.size() << " samples");
  BS_CHECK(fraction > 0.45 && fraction < 0.55, "dropout 0.5 kept a fraction " << fraction);
  std::map<std::pair<std::size_t, std::size_t>, std::size_t> pixel;
  for(std::size_t i = 0; i < all.size(); ++i)
    pixel[std::make_pair(all[i].row, all[i].column)] = i;
  std::size_t foreign = 0;
  for(const auto& s : kept)
  {
    auto it = pixel.find(std::make_pair(s.row, s.column));
    if(it == pixel.end() || !(all[it->second].point == s.point))
      ++foreign;
  }
  BS_CHECK(foreign == 0, foreign << " kept samples are not samples of the full scan");
  BS::Scan_options none;
  none.dropout_probability = 1.;
  BS_CHECK(simulator.scan(camera, none).empty(), "dropout 1 kept samples");
  report("dropout<" + kernel_name<K>() + ">", before);
}

// A multi-view scan is the union of the single views (noise and dropout included).
template <class K>
void test_multi_view()
{
  const int before = failures();
  typedef typename K::Point_3 P;
  typedef typename K::Vector_3 V;
  const Mesh<K> mesh = convert<K>(BS::make_two_holed_box());
  std::vector<BS::Camera<K>> cameras = {
    BS::Camera<K>::perspective(P(5, 3, 4), P(0, 0, 0.5), V(0, 0, 1), 40., 50, 40),
    BS::Camera<K>::orthographic(P(-4, -2, 3), P(0, 0, 0.5), V(0, 0, 1), 5., 40, 40),
    BS::Camera<K>::perspective(P(0, 0, 6), P(0, 0, 0), V(0, 1, 0), 50., 30, 60)};
  BS::Scan_options options;
  options.noise_sigma = 0.003;
  options.dropout_probability = 0.2;
  options.random_seed = 42;
  BS::Range_scan_simulator<Mesh<K>> simulator(mesh);
  const auto merged = simulator.scan(cameras, options);
  std::vector<BS::Range_sample<K>> expected;
  for(std::size_t k = 0; k < cameras.size(); ++k)
  {
    const auto one = simulator.scan(cameras[k], options, k);
    BS_CHECK(!one.empty(), "view " << k << " sees nothing");
    for(const auto& s : one)
      BS_CHECK(s.view == k, "view index " << s.view << " in view " << k);
    expected.insert(expected.end(), one.begin(), one.end());
  }
  BS_CHECK(merged.size() == expected.size(),
           "merged " << merged.size() << " samples, the views " << expected.size());
  std::size_t differ = 0;
  for(std::size_t i = 0; i < (std::min)(merged.size(), expected.size()); ++i)
    if(!(merged[i].point == expected[i].point) || merged[i].view != expected[i].view ||
       merged[i].row != expected[i].row || merged[i].column != expected[i].column)
      ++differ;
  BS_CHECK(differ == 0, differ << " merged samples differ from the single views");
  // The free function agrees with the class.
  const auto free_merged = BS::simulate_range_scan(mesh, cameras, options);
  BS_CHECK(free_merged.size() == merged.size(), "simulate_range_scan disagrees with the simulator");
  report("multi_view_union<" + kernel_name<K>() + ">", before);
}

// The default camera sees the whole object, which fills a good part of the image.
template <class K>
void test_default_camera()
{
  const int before = failures();
  const Mesh<K> mesh = convert<K>(BS::make_box_cylinder());
  const BS::Camera<K> camera = BS::default_camera_for(mesh);
  camera.validate();
  BS_CHECK(camera.width == 200 && camera.height == 200 && camera.field_of_view_degrees == 40. &&
             camera.projection == BS::Projection::Perspective,
           "unexpected default camera settings");
  const auto samples = BS::simulate_range_scan(mesh, camera);
  std::size_t border = 0;
  std::size_t min_row = 200, max_row = 0, min_col = 200, max_col = 0;
  for(const auto& s : samples)
  {
    if(s.row == 0 || s.column == 0 || s.row == 199 || s.column == 199)
      ++border;
    min_row = (std::min)(min_row, s.row);
    max_row = (std::max)(max_row, s.row);
    min_col = (std::min)(min_col, s.column);
    max_col = (std::max)(max_col, s.column);
  }
  BS_CHECK(samples.size() > 5000, "the default view gives only " << samples.size() << " samples");
  BS_CHECK(border == 0, "the object touches the image border: it is not entirely in view");
  BS_CHECK(max_row - min_row > 80 || max_col - min_col > 80, "the object is tiny in the default view");
  report("default_camera<" + kernel_name<K>() + ">", before);
}

template <class F>
bool throws_invalid_argument(F&& f)
{
  try
  {
    f();
  }
  catch(const std::invalid_argument& e)
  {
    return std::string(e.what()).size() > 20; // a message that explains
  }
  catch(...)
  {
    return false;
  }
  return false;
}

template <class K>
void test_bad_cameras()
{
  const int before = failures();
  typedef typename K::Point_3 P;
  typedef typename K::Vector_3 V;
  typedef BS::Camera<K> C;
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  const Mesh<K> sphere = make_icosphere<K>(1., 3);
  BS::Range_scan_simulator<Mesh<K>> simulator(sphere);
  const C good = C::perspective(P(3, 0, 0), P(0, 0, 0), V(0, 0, 1), 40., 20, 20);
  BS_CHECK(!simulator.scan(good).empty(), "the good camera sees nothing");

  std::vector<std::pair<std::string, C>> bad;
  C c = good; c.eye = P(0, 0, 0); bad.emplace_back("eye == target", c);
  c = good; c.up = V(-2, 0, 0); bad.emplace_back("up parallel to view", c);
  c = good; c.up = V(0, 0, 0); bad.emplace_back("null up", c);
  c = good; c.field_of_view_degrees = 0.; bad.emplace_back("fov 0", c);
  c = good; c.field_of_view_degrees = 180.; bad.emplace_back("fov 180", c);
  c = good; c.field_of_view_degrees = -10.; bad.emplace_back("fov -10", c);
  c = good; c.field_of_view_degrees = nan; bad.emplace_back("fov NaN", c);
  c = good; c.width = 0; bad.emplace_back("width 0", c);
  c = good; c.height = 0; bad.emplace_back("height 0", c);
  c = good; c.width = 20000; c.height = 20000; bad.emplace_back("4e8 pixels", c);
  c = good; c.width = std::size_t(-1); c.height = std::size_t(-1); bad.emplace_back("overflowing size", c);
  c = good; c.eye = P(nan, 0, 0); bad.emplace_back("NaN eye", c);
  c = good; c.target = P(0, inf, 0); bad.emplace_back("infinite target", c);
  c = good; c.up = V(0, 0, nan); bad.emplace_back("NaN up", c);
  c = good; c.eye = P(1e200, 0, 0); bad.emplace_back("eye beyond 1e150", c); // (its distance overflows)
  c = C::orthographic(P(3, 0, 0), P(0, 0, 0), V(0, 0, 1), 0., 20, 20); bad.emplace_back("view height 0", c);
  c = C::orthographic(P(3, 0, 0), P(0, 0, 0), V(0, 0, 1), -1., 20, 20); bad.emplace_back("view height -1", c);
  c = C::orthographic(P(3, 0, 0), P(0, 0, 0), V(0, 0, 1), inf, 20, 20); bad.emplace_back("view height inf", c);
  for(const auto& b : bad)
  {
    BS_CHECK(throws_invalid_argument([&] { b.second.validate(); }), "validate() accepts " << b.first);
    BS_CHECK(throws_invalid_argument([&] { simulator.scan(b.second); }), "scan() accepts " << b.first);
    BS_CHECK(throws_invalid_argument([&] { simulator.scan(std::vector<C>{good, b.second}); }),
             "multi-view scan() accepts " << b.first);
  }

  BS::Scan_options o;
  o.noise_sigma = -1.;
  BS_CHECK(throws_invalid_argument([&] { simulator.scan(good, o); }), "negative sigma accepted");
  o.noise_sigma = nan;
  BS_CHECK(throws_invalid_argument([&] { simulator.scan(good, o); }), "NaN sigma accepted");
  o = BS::Scan_options();
  o.dropout_probability = 1.5;
  BS_CHECK(throws_invalid_argument([&] { simulator.scan(good, o); }), "dropout 1.5 accepted");
  o.dropout_probability = nan;
  BS_CHECK(throws_invalid_argument([&] { simulator.scan(good, o); }), "NaN dropout accepted");
  o = BS::Scan_options();
  o.noise_sigma = 1e308; // finite, but it carries samples past the largest double
  BS_CHECK(throws_invalid_argument([&] { simulator.scan(good, o); }), "a noise that overflows the samples accepted");

  const Mesh<K> empty;
  BS_CHECK(throws_invalid_argument([&] { BS::Range_scan_simulator<Mesh<K>> s(empty); }), "empty mesh accepted");
  BS_CHECK(throws_invalid_argument([&] { BS::simulate_range_scan(empty, good); }), "empty mesh accepted");
  BS_CHECK(throws_invalid_argument([&] { BS::default_camera_for(empty); }), "default camera of an empty mesh");
  Mesh<K> quad;
  quad.add_face(quad.add_vertex(P(0, 0, 0)), quad.add_vertex(P(1, 0, 0)), quad.add_vertex(P(1, 1, 0)),
                quad.add_vertex(P(0, 1, 0)));
  BS_CHECK(throws_invalid_argument([&] { BS::Range_scan_simulator<Mesh<K>> s(quad); }), "quad mesh accepted");
  Mesh<K> far_out = sphere; // where squared distances overflow
  for(auto v : far_out.vertices())
    far_out.point(v) = P(1e155 * far_out.point(v).x(), far_out.point(v).y(), far_out.point(v).z());
  BS_CHECK(throws_invalid_argument([&] { BS::Range_scan_simulator<Mesh<K>> s(far_out); }), "a mesh at 1e155 accepted");
  BS_CHECK(throws_invalid_argument([&] { BS::default_camera_for(far_out); }), "default camera of a mesh at 1e155");
  Mesh<K> line; // one face with three distinct collinear corners: no surface at all
  line.add_face(line.add_vertex(P(0, 0, 0)), line.add_vertex(P(1, 1, 1)), line.add_vertex(P(2, 2, 2)));
  BS_CHECK(throws_invalid_argument([&] { BS::Range_scan_simulator<Mesh<K>> s(line); }),
           "a mesh of collinear faces only accepted");
  report("bad_cameras<" + kernel_name<K>() + ">", before);
}

// A face with collinear corners is not scanned: with one added to the
// square, every sample still lies on the square, and the same pixels hit.
template <class K>
void test_degenerate_faces()
{
  const int before = failures();
  typedef typename K::Point_3 P;
  typedef typename K::Vector_3 V;
  const Mesh<K> square = make_square<K>();
  Mesh<K> with_sliver = square;
  with_sliver.add_face(with_sliver.add_vertex(P(-0.5, -0.5, 0.25)), with_sliver.add_vertex(P(0, 0, 0.5)),
                       with_sliver.add_vertex(P(0.5, 0.5, 0.75)));
  const Distance_tree<K> tree(square);
  for(const auto& eye_up : {std::make_pair(P(0.3, 0.2, 5), V(0, 1, 0)), std::make_pair(P(3, -2, 4), V(0, 0, 1)),
                            std::make_pair(P(-4, 0.1, 1), V(0, 0, 1))})
  {
    const P eye = eye_up.first;
    const auto camera = BS::Camera<K>::perspective(eye, P(0, 0, 0), eye_up.second, 40., 48, 48);
    const auto plain = BS::simulate_range_scan(square, camera);
    const auto samples = BS::simulate_range_scan(with_sliver, camera);
    double worst = 0.;
    for(const auto& s : samples)
      worst = (std::max)(worst, tree.distance(s.point));
    BS_CHECK(samples.size() == plain.size() && !samples.empty(),
             "eye " << eye << ": " << samples.size() << " samples with the collinear face, " << plain.size() << " without");
    BS_CHECK(worst < 1e-12, "eye " << eye << ": a sample lies " << worst << " off the square");
  }
  report("degenerate_faces<" + kernel_name<K>() + ">", before);
}

// ---------------------------------------------------------------- writing

template <class K>
void test_writers(const Temp_dir& dir)
{
  const int before = failures();
  typedef typename K::Point_3 P;
  typedef typename K::Vector_3 V;
  const Mesh<K> sphere = make_icosphere<K>(1., 4);
  const auto samples = BS::simulate_range_scan(
    sphere, BS::Camera<K>::perspective(P(0, 3, 0), P(0, 0, 0), V(0, 0, 1), 50., 30, 30));
  BS_CHECK(!samples.empty(), "no samples to write");
  const std::string k = kernel_name<K>().substr(0, 4);

  for(const std::string ext : {"xyz", "ply", "PLY"})
    for(bool normals : {false, true})
    {
      const std::string file = dir / (k + "_scan_" + std::to_string(normals) + "." + ext);
      BS::write_range_scan(file, samples, normals);
      typedef std::pair<EPICK::Point_3, EPICK::Vector_3> PN;
      std::vector<PN> read;
      const bool ok = CGAL::IO::read_points(file, std::back_inserter(read),
                                            CGAL::parameters::point_map(CGAL::First_of_pair_property_map<PN>())
                                              .normal_map(CGAL::Second_of_pair_property_map<PN>()));
      BS_CHECK(ok && read.size() == samples.size(), file << ": read " << read.size() << " of " << samples.size());
      std::size_t differ = 0;
      for(std::size_t i = 0; ok && i < (std::min)(read.size(), samples.size()); ++i)
      {
        const auto& p = samples[i].point;
        if(read[i].first != EPICK::Point_3(CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z())))
          ++differ;
        if(normals && CGAL::to_double(read[i].second.x()) != CGAL::to_double(samples[i].normal.x()))
          ++differ;
      }
      BS_CHECK(differ == 0, file << ": " << differ << " values did not round-trip");
    }

  const std::size_t files = dir.number_of_files();
  BS_CHECK(throws_invalid_argument([&] { BS::write_range_scan(dir / "scan.txt", samples); }),
           "the .txt extension was accepted");
  bool runtime = false;
  try
  {
    BS::write_range_scan(dir / "no_such_dir/scan.xyz", samples);
  }
  catch(const std::runtime_error&)
  {
    runtime = true;
  }
  BS_CHECK(runtime, "writing into a missing directory did not throw std::runtime_error");
  // A writer that fails half-way leaves neither the file nor its temporary.
  bool rethrown = false;
  try
  {
    BS::internal::write_file_atomically(dir / "half.xyz", [](std::ostream& out) {
      out << "1 2 3\n";
      throw std::logic_error("interrupted");
    });
  }
  catch(const std::logic_error&)
  {
    rethrown = true;
  }
  BS_CHECK(rethrown, "the writer's exception was not rethrown");
  BS_CHECK(dir.number_of_files() == files, "a failed write left a file behind");
  // A symbolic link is written through: its target gets the text, the link
  // stays a link. A directory is refused; a device is written in place.
  {
    namespace fs = std::filesystem;
    const fs::path target = dir / "link_target.txt", link = dir / "link.txt";
    std::error_code ec;
    fs::remove(link, ec);
    fs::create_symlink(target.filename(), link); // relative, as `ln -s` makes it
    BS::internal::write_file_atomically(link.string(), [](std::ostream& out) { out << "through\n"; });
    std::ifstream in(target);
    std::string text;
    std::getline(in, text);
    BS_CHECK(fs::is_symlink(fs::symlink_status(link)), "the symbolic link was replaced by a file");
    BS_CHECK(text == "through", "the link's target holds '" << text << "'");
    bool refused = false;
    try
    {
      BS::internal::write_file_atomically(dir.path.string(), [](std::ostream& out) { out << 1; });
    }
    catch(const std::runtime_error& e)
    {
      refused = std::string(e.what()).find("is a directory") != std::string::npos;
    }
    BS_CHECK(refused, "a directory as output file was not refused with a clear message");
    if(fs::exists("/dev/null"))
    {
      BS::internal::write_file_atomically("/dev/null", [](std::ostream& out) { out << "nothing\n"; });
      BS_CHECK(fs::is_character_file("/dev/null"), "writing /dev/null replaced the device");
    }
    fs::remove(link, ec);
    fs::remove(target, ec);
  }
  report("writers<" + kernel_name<K>() + ">", before);
}

// Ended by a signal while it writes, a program that asked for it
// (remove_partial_files_on_termination_signals(), as the tools do) leaves
// no temporary file behind, and still dies of that signal. Without the
// handlers the temporary stays: the check can fail.
void test_partial_files_on_signals(const Temp_dir& dir)
{
  const int before = failures();
  const std::size_t files = dir.number_of_files();
  // the status of a child that writes and is signalled half-way
  const auto killed_while_writing = [&](int signal_number, bool handlers) {
    std::cout.flush();
    std::cerr.flush();
    const pid_t child = fork();
    if(child == 0)
    {
      if(handlers)
        BS::internal::remove_partial_files_on_termination_signals();
      BS::internal::write_file_atomically(dir / "killed.xyz", [&](std::ostream& out) {
        out << "1 2 3\n" << std::flush;
        std::raise(signal_number);
      });
      std::_Exit(0); // not reached: the signal ends the child
    }
    int status = 0;
    return (child > 0 && waitpid(child, &status, 0) == child) ? status : -1;
  };
  for(const int signal_number : {SIGTERM, SIGINT})
  {
    const int status = killed_while_writing(signal_number, true);
    BS_CHECK(status != -1 && WIFSIGNALED(status) && WTERMSIG(status) == signal_number,
             "signal " << signal_number << ": the writer did not die of it (status " << status << ")");
    BS_CHECK(dir.number_of_files() == files,
             "signal " << signal_number << " left " << dir.number_of_files() - files << " file(s) behind");
  }
  const int status = killed_while_writing(SIGTERM, false);
  BS_CHECK(status != -1 && WIFSIGNALED(status), "without handlers: the writer did not die of the signal");
  BS_CHECK(dir.number_of_files() == files + 1,
           "without handlers the temporary file should stay (the check above could not fail): "
             << dir.number_of_files() - files << " new files");
  for(const auto& entry : std::filesystem::directory_iterator(dir.path))
    if(entry.path().filename().string().find("killed.xyz.partial-") == 0)
      std::filesystem::remove(entry.path());
  report("partial files on signals", before);
}

// ---------------------------------------------------------------- CAD objects

// Checks of its own, independent of the library's post-conditions.
void check_cad_object(const std::string& what, const BS::CAD_mesh& m, int genus)
{
  BS_CHECK(m.number_of_faces() > 0 && !m.has_garbage(), what << ": empty mesh or garbage");
  BS_CHECK(CGAL::is_closed(m), what << ": not closed");
  BS_CHECK(CGAL::is_triangle_mesh(m), what << ": not a triangle mesh");
  BS::CAD_mesh copy = m;
  BS_CHECK(PMP::duplicate_non_manifold_vertices(copy) == 0, what << ": non-manifold vertices");
  BS_CHECK(!PMP::does_self_intersect(m), what << ": self-intersections");
  BS_CHECK(PMP::is_outward_oriented(m), what << ": not outward oriented");
  BS_CHECK(PMP::does_bound_a_volume(m), what << ": does not bound a volume");
  auto fcc = copy.add_property_map<BS::CAD_mesh::Face_index, std::size_t>("f:cc_test", 0).first;
  const std::size_t components = PMP::connected_components(copy, fcc);
  BS_CHECK(components == 1, what << ": " << components << " connected components");
  const long chi = long(m.number_of_vertices()) - long(m.number_of_edges()) + long(m.number_of_faces());
  BS_CHECK(chi == 2 - 2 * genus, what << ": Euler characteristic " << chi << ", expected genus " << genus);
}

void test_cad_objects()
{
  const int before = failures();
  check_cad_object("box_cylinder default", BS::make_box_cylinder(), 0);
  {
    BS::Box_cylinder_parameters p;
    p.cylinder_radius = 0.9;
    p.cylinder_height = 0.2;
    p.segments = 32;
    check_cad_object("box_cylinder wide and low", BS::make_box_cylinder(p), 0);
    p.box_length = 3.;
    p.cylinder_radius = 0.3;
    p.cylinder_height = 3.;
    check_cad_object("box_cylinder thin and tall", BS::make_box_cylinder(p), 0);
  }
  check_cad_object("mug default", BS::make_mug(), 1);
  {
    BS::Mug_parameters p;
    p.wall_thickness = 0.05;
    p.handle_thickness = 0.2;
    p.handle_radius = 0.5;
    p.segments = 32;
    check_cad_object("mug thin wall, thick handle", BS::make_mug(p), 1);
    p = BS::Mug_parameters();
    p.radius = 0.6;
    p.height = 1.6;
    p.wall_thickness = 0.15;
    p.bottom_thickness = 0.2;
    p.handle_radius = 0.4;
    p.handle_thickness = 0.05;
    check_cad_object("mug small", BS::make_mug(p), 1);
  }
  check_cad_object("two_holed_box default", BS::make_two_holed_box(), 2);
  {
    BS::Two_holed_box_parameters p;
    p.big_hole_radius = p.small_hole_radius = 0.9;
    p.segments = 32;
    check_cad_object("two_holed_box equal big holes", BS::make_two_holed_box(p), 2);
    p.box_height = 3.;
    p.big_hole_radius = 0.2;
    p.small_hole_radius = 0.1;
    check_cad_object("two_holed_box tall, small holes", BS::make_two_holed_box(p), 2);
  }
  for(double h : {0.2, 1.0, 2.5})
    for(double r : {0.15, 0.5, 0.9})
      check_cad_object("box_hole_cylinder h=" + std::to_string(h) + " r=" + std::to_string(r),
                       BS::make_box_hole_cylinder(h, r), 1);
  report("cad_objects", before);
}

// The box and the cylinder as two overlapping solids
// (internal::box_cylinder_overlapping_solids(), which test_fitting scans
// instead of make_box_cylinder() so as not to compile the corefinement) look like their
// union: the default camera is the same (the same bounding box), and every
// ray meets the same surface first, up to rounding where the union's
// triangles are split along the box's top.
void test_box_cylinder_solids_scan_like_the_union()
{
  const int before = failures();
  const BS::CAD_mesh object = BS::make_box_cylinder();
  const BS::CAD_mesh solids = BS::internal::box_cylinder_overlapping_solids(BS::Box_cylinder_parameters(), "box/cylinder");
  const auto of_union = BS::simulate_range_scan(object, BS::default_camera_for(object));
  const auto of_solids = BS::simulate_range_scan(solids, BS::default_camera_for(solids));
  BS_CHECK(of_union.size() == of_solids.size() && of_union.size() > 10000,
           "box/cylinder: " << of_union.size() << " samples of the union, " << of_solids.size() << " of the two solids");
  double farthest = 0.;
  for(std::size_t i = 0; i < (std::min)(of_union.size(), of_solids.size()); ++i)
    farthest = (std::max)(farthest, std::sqrt(CGAL::squared_distance(of_union[i].point, of_solids[i].point)));
  BS_CHECK(farthest <= 1e-12, "box/cylinder: the two solids' samples are up to " << farthest << " from the union's");
  report("box_cylinder_solids", before);
}

void test_bad_cad_parameters()
{
  const int before = failures();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  auto bad = [](const std::string& what, const std::function<void()>& f) {
    BS_CHECK(throws_invalid_argument(f), what << " was accepted");
  };
  bad("box_cylinder radius wider than the box", [] {
    BS::Box_cylinder_parameters p;
    p.cylinder_radius = 1.5;
    BS::make_box_cylinder(p);
  });
  bad("box_cylinder negative height", [] {
    BS::Box_cylinder_parameters p;
    p.cylinder_height = -1.;
    BS::make_box_cylinder(p);
  });
  bad("box_cylinder NaN box", [nan] {
    BS::Box_cylinder_parameters p;
    p.box_width = nan;
    BS::make_box_cylinder(p);
  });
  bad("box_cylinder 2 segments", [] {
    BS::Box_cylinder_parameters p;
    p.segments = 2;
    BS::make_box_cylinder(p);
  });
  bad("mug wall thicker than half the radius", [] {
    BS::Mug_parameters p;
    p.wall_thickness = 0.6;
    BS::make_mug(p);
  });
  bad("mug handle without hole", [] {
    BS::Mug_parameters p;
    p.handle_thickness = 0.3;
    BS::make_mug(p);
  });
  bad("mug handle taller than the mug", [] {
    BS::Mug_parameters p;
    p.handle_radius = 0.9;
    BS::make_mug(p);
  });
  bad("mug handle too small to pass the wall", [] {
    BS::Mug_parameters p;
    p.handle_radius = 0.3;
    BS::make_mug(p);
  });
  bad("mug handle past the cup axis", [] {
    BS::Mug_parameters p;
    p.radius = 0.3;
    p.wall_thickness = 0.05;
    p.handle_radius = 0.5;
    p.handle_thickness = 0.05;
    BS::make_mug(p);
  });
  bad("mug zero bottom", [] {
    BS::Mug_parameters p;
    p.bottom_thickness = 0.;
    BS::make_mug(p);
  });
  bad("two_holed_box hole wider than the box", [] {
    BS::Two_holed_box_parameters p;
    p.big_hole_radius = 1.2;
    BS::make_two_holed_box(p);
  });
  bad("two_holed_box tiny hole", [] {
    BS::Two_holed_box_parameters p;
    p.small_hole_radius = 1e-6;
    BS::make_two_holed_box(p);
  });
  bad("box_hole_cylinder radius 1", [] { BS::make_box_hole_cylinder(1., 1.); });
  bad("box_hole_cylinder radius 0", [] { BS::make_box_hole_cylinder(1., 0.); });
  bad("box_hole_cylinder height -1", [] { BS::make_box_hole_cylinder(-1., 0.5); });
  bad("box_hole_cylinder height NaN", [nan] { BS::make_box_hole_cylinder(nan, 0.5); });
  bad("box_hole_cylinder hole wider than the box", [] {
    BS::Box_hole_cylinder_parameters p;
    p.hole_radius = 1.;
    BS::make_box_hole_cylinder(p);
  });
  report("bad_cad_parameters", before);
}

// ---------------------------------------------------------------- command-line tools


#ifdef BLENDED_SCAN_EXE // (where the tools are built: not in sanitizer builds by default, see test/CMakeLists.txt)
void test_tools(const Temp_dir& dir)
{
  const int before = failures();
  const std::string scan = quote(BLENDED_SCAN_EXE), make = quote(BLENDED_MAKE_OBJECT_EXE);
  std::string err;

  BS_CHECK(run(scan + " --help", dir) == 0, "blended_scan --help");
  BS_CHECK(run(make + " --help", dir) == 0, "blended_make_object --help");

  const std::string mesh = dir / "object.off";
  BS_CHECK(run(make + " box_hole_cylinder --cylinder-height 0.8 --cylinder-radius 0.4 -o " + quote(mesh), dir, &err) == 0,
           "blended_make_object failed: " << err);
  BS_CHECK(fs::exists(mesh), "no mesh written");

  // Failures: expected exit code, message prefix, and no output file.
  const std::string out = dir / "out.xyz";
  const std::string garbage = dir / "garbage.off";
  std::ofstream(garbage) << "this is not an OFF file\n";
  const std::vector<std::pair<std::string, int>> scan_failures = {
    {scan, 2},
    {scan + " " + quote(mesh), 2},                                   // no -o
    {scan + " " + quote(mesh) + " -o", 2},                           // missing value
    {scan + " " + quote(mesh) + " -o " + quote(out) + " --bogus", 2},
    {scan + " " + quote(mesh) + " -o " + quote(out) + " --fov abc", 2},
    {scan + " " + quote(mesh) + " -o " + quote(out) + " --width 12x", 2},
    {scan + " " + quote(mesh) + " -o " + quote(out) + " --eye 1,2", 2},
    {scan + " " + quote(mesh) + " -o " + quote(out) + " --noise nan", 2},
    {scan + " " + quote(mesh) + " -o " + quote(dir / "out.txt"), 2},
    {scan + " " + quote(mesh) + " " + quote(mesh) + " -o " + quote(out), 2},
    {scan + " " + quote(dir / "missing.off") + " -o " + quote(out), 1},
    {scan + " " + quote(garbage) + " -o " + quote(out), 1},
    {scan + " " + quote(dir.path.string()) + " -o " + quote(out), 1},  // a directory
    {scan + " " + quote(mesh) + " -o " + quote(out) + " --fov 200", 1},
    {scan + " " + quote(mesh) + " -o " + quote(out) + " --eye 0,0,0.5 --target 0,0,0.5", 1},
    {scan + " " + quote(mesh) + " -o " + quote(out) + " --dropout 1", 1},          // empty result
    {scan + " " + quote(mesh) + " -o " + quote(out) + " --eye 0,0,50 --target 0,0,100 --up 0,1,0", 1}, // looks away
    {scan + " " + quote(mesh) + " -o " + quote(dir / "no_dir/out.xyz"), 1}};
  for(const auto& c : scan_failures)
  {
    const int code = run(c.first, dir, &err);
    BS_CHECK(code == c.second, c.first << ": exit code " << code << ", expected " << c.second);
    BS_CHECK(err.rfind("blended_scan", 0) == 0, c.first << ": stderr does not start with the tool name: " << err);
    BS_CHECK(!fs::exists(out) && !fs::exists(dir / "out.txt"), c.first << ": left an output file");
  }
  const std::string obj = dir / "made.off";
  const std::vector<std::pair<std::string, int>> make_failures = {
    {make, 2},
    {make + " -o " + quote(obj), 2},
    {make + " teapot -o " + quote(obj), 2},
    {make + " mug", 2},
    {make + " mug -o " + quote(obj) + " --cylinder-radius 0.5", 2}, // flag of another object
    {make + " box_hole_cylinder -o " + quote(obj) + " --cylinder-radius", 2},
    {make + " box_hole_cylinder -o " + quote(obj) + " --cylinder-radius 0.5.5", 2},
    {make + " box_hole_cylinder -o " + quote(obj) + " --segments -3", 2},
    {make + " box_hole_cylinder -o " + quote(dir / "made.xyz"), 2},
    {make + " box_hole_cylinder -o " + quote(obj) + " --cylinder-radius 5", 1},
    {make + " mug -o " + quote(obj) + " --wall 0.9", 1},
    {make + " two_holed_box -o " + quote(obj) + " --hole-radii 0.5,1.5", 1},
    {make + " box_cylinder -o " + quote(dir / "no_dir/made.off"), 1}};
  for(const auto& c : make_failures)
  {
    const int code = run(c.first, dir, &err);
    BS_CHECK(code == c.second, c.first << ": exit code " << code << ", expected " << c.second);
    BS_CHECK(err.rfind("blended_make_object", 0) == 0,
             c.first << ": stderr does not start with the tool name: " << err);
    BS_CHECK(!fs::exists(obj) && !fs::exists(dir / "made.xyz"), c.first << ": left an output file");
  }
  // One row of pixels: the vertical field of view spreads a few rays over a
  // wide angle, which the message says (it only said that no ray hit).
  BS_CHECK(run(scan + " " + quote(mesh) + " -o " + quote(out) + " --width 200 --height 1 --fov 90", dir, &err) == 1 &&
             err.find("is vertical") != std::string::npos && err.find("--height") != std::string::npos,
           "blended_scan with one row of pixels: " << err);
  // Only the mesh and the garbage file: no temporary left anywhere.
  BS_CHECK(dir.number_of_files() == 2, "the failed runs left " << dir.number_of_files() - 2 << " files");
  // An output that is the input, refused before anything is read or written.
  const std::string mesh_ply = dir / "copy.ply";
  BS_CHECK(run(make + " box_cylinder --segments 8 -o " + quote(mesh_ply), dir, &err) == 0, "a PLY mesh: " << err);
  const auto size_before = fs::file_size(mesh_ply);
  BS_CHECK(run(scan + " " + quote(mesh_ply) + " -o " + quote(mesh_ply), dir, &err) == 2 &&
             err.find("same file") != std::string::npos,
           "blended_scan with its input as output: " << err);
  BS_CHECK(fs::file_size(mesh_ply) == size_before, "blended_scan overwrote its input");
  fs::remove(mesh_ply);

  // Good runs: a readable .xyz, a .ply with normals, every object name.
  BS_CHECK(run(scan + " " + quote(mesh) + " -o " + quote(out) + " --width 60 --height 50 --noise 0.001 --seed 5", dir,
               &err) == 0,
           "good scan failed: " << err);
  // a subnormal noise is a (tiny) number, not an error
  BS_CHECK(run(scan + " " + quote(mesh) + " -o " + quote(out) + " --width 20 --height 20 --noise 1e-320", dir, &err) == 0,
           "--noise 1e-320: " << err);
  BS_CHECK(run(scan + " " + quote(mesh) + " -o " + quote(out) + " --width 60 --height 50 --noise 0.001 --seed 5", dir,
               &err) == 0,
           "good scan failed: " << err);
  std::ifstream xyz(out);
  std::string line;
  std::size_t lines = 0, bad_lines = 0;
  while(std::getline(xyz, line))
  {
    std::istringstream s(line);
    double x, y, z;
    std::string rest;
    if(!(s >> x >> y >> z) || (s >> rest) || !std::isfinite(x + y + z))
      ++bad_lines;
    ++lines;
  }
  BS_CHECK(lines > 500 && bad_lines == 0, out << ": " << lines << " lines, " << bad_lines << " bad");
  const std::string ply = dir / "out.ply";
  BS_CHECK(run(scan + " " + quote(mesh) + " -o " + quote(ply) +
                 " --normals --orthographic 5 --eye 1,-2,6 --target 0,0,0.5 --up 0,1,0 --dropout 0.3",
               dir, &err) == 0,
           "good orthographic scan failed: " << err);
  std::vector<std::pair<EPICK::Point_3, EPICK::Vector_3>> points;
  typedef std::pair<EPICK::Point_3, EPICK::Vector_3> PN;
  BS_CHECK(CGAL::IO::read_points(ply, std::back_inserter(points),
                                 CGAL::parameters::point_map(CGAL::First_of_pair_property_map<PN>())
                                   .normal_map(CGAL::Second_of_pair_property_map<PN>())) &&
             points.size() > 100,
           ply << " is not a readable point cloud");
  for(const char* name : {"box_cylinder", "mug", "two_holed_box", "box_hole_cylinder"})
  {
    const std::string file = dir / (std::string(name) + ".off");
    BS_CHECK(run(make + " " + name + " --segments 24 -o " + quote(file), dir, &err) == 0,
             name << " failed: " << err);
    BS::CAD_mesh m;
    BS_CHECK(CGAL::IO::read_polygon_mesh(file, m) && CGAL::is_closed(m) && m.number_of_faces() > 0,
             file << " is not a closed mesh");
  }
  report("command_line_tools", before);
}
#endif

// The checks that take a kernel, with `K`.
template <class K>
void run_kernel(const BS::CAD_mesh& box_cylinder, const BS::CAD_mesh& holed, const Temp_dir& dir)
{
  typedef typename K::Point_3 Point;
  test_points_on_mesh_and_visible<K>("box_cylinder", convert<K>(box_cylinder), Point(3.5, 2.5, 3.));
  test_points_on_mesh_and_visible<K>("two_holed_box", convert<K>(holed), Point(2., -3., 4.));
  test_sphere_half_covered<K>(true);
  test_sphere_half_covered<K>(false);
  test_image_orientation<K>();
  test_noise<K>();
  test_dropout<K>();
  test_multi_view<K>();
  test_default_camera<K>();
  test_bad_cameras<K>();
  test_degenerate_faces<K>();
  test_writers<K>(dir);
}

} // namespace

int main()
{
  {
    BS::Box_cylinder_parameters box_cylinder;
    box_cylinder.segments = 16;
    BS::Two_holed_box_parameters holed;
    holed.segments = 16;
    const BS::CAD_mesh box_cylinder_mesh = BS::make_box_cylinder(box_cylinder), holed_mesh = BS::make_two_holed_box(holed);
    Temp_dir dir("blended_test_scanning");
    blended_shape_test::for_each_kernel([&](auto kernel, const char*) {
      run_kernel<decltype(kernel)>(box_cylinder_mesh, holed_mesh, dir);
    });
    test_partial_files_on_signals(dir);
  }
  test_cad_objects();
  test_box_cylinder_solids_scan_like_the_union();
  test_bad_cad_parameters();
#ifdef BLENDED_SCAN_EXE
  {
    Temp_dir dir("blended_test_scanning");
    test_tools(dir);
  }
#endif
  return blended_shape_test::exit_code();
}
