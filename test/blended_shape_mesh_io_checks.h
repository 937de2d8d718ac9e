// SPDX-License-Identifier: LGPL-3.0-or-later
// Writing the meshes of a blended shape: the per-component pieces as binary
// and ASCII PLY colored by component, and the unified closed mesh as OFF.
// Every file is read back with CGAL's readers and compared with the
// in-memory mesh (counts, every coordinate bit for bit, every face's
// vertices, colors and components); failures (a missing directory, a
// directory as the path, an empty path, a non-finite vertex, a mesh that
// cannot be built) must throw and leave no file, and must not touch an
// existing one. Both supported kernels.
#ifndef BLENDED_SHAPE_BLENDED_SHAPE_MESH_IO_CHECKS_H
#define BLENDED_SHAPE_BLENDED_SHAPE_MESH_IO_CHECKS_H
// Part of test_blended_shape (one program, one compilation of the blended
// shape for each kernel; CTest runs it as `test_blended_shape_mesh_io`).
#include "test_kernels.h"
#include "test_util.h"
#include "blended_shape_test_util.h"

#include <CGAL/Blended_shape/Blending/Ellipse_blending_region.h>
#include <CGAL/Blended_shape/IO/Blended_shape_mesh_io.h>
#include <CGAL/Blended_shape/Primitives/Superquadric_ellipsoid.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh/IO/OFF.h>
#include <CGAL/Surface_mesh/IO/PLY.h>
#include <CGAL/boost/graph/helpers.h>

#include <Eigen/Core>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <map>
#include <random>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

namespace blended_shape_mesh_io_checks {

namespace BS = CGAL::Blended_shapes;
namespace fs = std::filesystem;

using blended_shape_test::set_parameter;

typedef BS::Ellipse_blending_region Region;

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof(double)) == 0; }

bool contains(const std::string& s, const std::string& fragment) { return s.find(fragment) != std::string::npos; }

std::string file_text(const fs::path& p)
{
  std::ifstream in(p, std::ios::binary);
  std::stringstream buf;
  buf << in.rdbuf();
  return buf.str();
}

// The names of the files in `dir`, sorted.
std::set<std::string> listing(const fs::path& dir)
{
  std::set<std::string> names;
  for(const fs::directory_entry& e : fs::directory_iterator(dir))
    names.insert(e.path().filename().string());
  return names;
}

template <class K>
struct Tester
{
  typedef BS::Blended_shape<K> Shape;
  typedef typename K::Point_3 Point_3;
  typedef CGAL::Surface_mesh<Point_3> Mesh;
  typedef typename Mesh::Vertex_index Vertex_index;
  typedef typename Mesh::Face_index Face_index;

  std::string kernel;
  fs::path dir;

  // A sphere with a split cap and a gradual part half expressed (three
  // components, so three colors), and a sphere with an opened pole-to-pole
  // hole (genus 1) for the closed mesh.
  static Shape three_components()
  {
    Shape s(BS::Superquadric_ellipsoid<K>(1.0, 0.9, 1.1, 0.8, 1.1));
    s.split(0, 0, Region::make_parameters(0.15, -0.1, 0.5, 0.42, 0.3, 0.9, 0.), 0.08);
    s.add_part(0, 1, Region::make_parameters(0., 0.05, 0.35, 0.33, 0., 0.9, 1.), 0.07,
               BS::Superquadric_ellipsoid<K>(0.4, 0.42, 0.6, 0.9, 1.), "superquadric_ellipsoid",
               Eigen::Vector3d(0.02, 0., -0.9), Eigen::Vector4d(1., 0.02, 0., 0.), 1,
               Region::make_parameters(0., 0., 0.8, 0.8, 0., 1., 0.), 0.1);
    set_parameter(s, "b1.h", 0.4);
    return s;
  }

  static Shape torus_like()
  {
    Shape s(BS::Superquadric_ellipsoid<K>(1., 1., 1., 1., 1.));
    s.add_hole(BS::Shape_point(0, BS::Chart_point(0, 0.05, 0.)), BS::Shape_point(0, BS::Chart_point(1, 0., 0.05)), 0.3,
               0.08, 0.1);
    set_parameter(s, "b0.h", 0.);
    set_parameter(s, "b1.h", 0.);
    s.switch_hole_to_tube(0);
    set_parameter(s, "c1.a4", 1.3);
    set_parameter(s, "c1.a5", 1.25);
    return s;
  }

  bool read_ply(const fs::path& p, Mesh& m)
  {
    std::ifstream in(p, std::ios::binary);
    return in && CGAL::IO::read_PLY(in, m);
  }

  // `read` has the vertices and faces of `ref` in the same order, each
  // coordinate bit for bit.
  void check_same_mesh(const Mesh& ref, const Mesh& read, const std::string& what)
  {
    BS_CHECK(read.number_of_vertices() == ref.number_of_vertices(),
             what << ": " << read.number_of_vertices() << " vertices, expected " << ref.number_of_vertices());
    BS_CHECK(read.number_of_faces() == ref.number_of_faces(),
             what << ": " << read.number_of_faces() << " faces, expected " << ref.number_of_faces());
    if(read.number_of_vertices() != ref.number_of_vertices() || read.number_of_faces() != ref.number_of_faces())
      return;
    // The writers number the vertices in iteration order; the readers keep it.
    std::vector<Point_3> ref_points, read_points;
    for(Vertex_index v : ref.vertices())
      ref_points.push_back(ref.point(v));
    for(Vertex_index v : read.vertices())
      read_points.push_back(read.point(v));
    std::size_t bad = 0;
    for(std::size_t i = 0; i < ref_points.size(); ++i)
      for(int c = 0; c < 3; ++c)
        bad += same_bits(CGAL::to_double(ref_points[i][c]), CGAL::to_double(read_points[i][c])) ? 0 : 1;
    BS_CHECK(bad == 0, what << ": " << bad << " coordinates differ from the mesh in memory");
    // Faces: the same corners, in the same order (so the same orientation).
    std::size_t bad_faces = 0;
    auto f_ref = ref.faces().begin();
    for(Face_index f : read.faces())
    {
      std::vector<Point_3> a, b;
      for(Vertex_index v : CGAL::vertices_around_face(read.halfedge(f), read))
        a.push_back(read.point(v));
      for(Vertex_index v : CGAL::vertices_around_face(ref.halfedge(*f_ref), ref))
        b.push_back(ref.point(v));
      bad_faces += (a == b) ? 0 : 1;
      ++f_ref;
    }
    BS_CHECK(bad_faces == 0, what << ": " << bad_faces << " faces differ from the mesh in memory");
  }

  void test_pieces_ply()
  {
    const Shape s = three_components();
    const BS::Blended_shape_pieces<K> pieces(s, 8);
    const Mesh merged = pieces.merged_mesh();
    BS_CHECK(merged.number_of_faces() > 0, kernel << ": no pieces");
    for(bool binary : {true, false})
    {
      const std::string what = kernel + (binary ? ", binary PLY" : ", ASCII PLY");
      const fs::path file = dir / (binary ? "pieces_binary.ply" : "pieces_ascii.ply");
      try
      {
        BS::write_blended_shape_pieces_ply(file.string(), pieces, CGAL::parameters::use_binary_mode(binary));
      }
      catch(const std::exception& e)
      {
        BS_CHECK(false, what << ": writing threw: " << e.what());
        continue;
      }
      const std::string text = file_text(file);
      BS_CHECK(contains(text, binary ? "format binary_little_endian 1.0" : "format ascii 1.0"),
               what << ": wrong format line");
      BS_CHECK(contains(text, "property uchar red") && contains(text, "property int component"),
               what << ": the header lacks the face color or component");
      Mesh read;
      BS_CHECK(read_ply(file, read), what << ": CGAL::IO::read_PLY failed");
      check_same_mesh(merged, read, what);
      // Colors and components, face by face.
      auto color = read.template property_map<Face_index, CGAL::IO::Color>("f:color");
      auto comp = read.template property_map<Face_index, int>("f:component");
      BS_CHECK(color.second, what << ": no face colors read back");
      BS_CHECK(comp.second, what << ": no face components read back");
      if(!color.second || !comp.second || read.number_of_faces() != merged.number_of_faces())
        continue;
      auto ref_color = merged.template property_map<Face_index, CGAL::IO::Color>("f:color").first;
      auto ref_comp = merged.template property_map<Face_index, int>("f:component").first;
      std::map<int, CGAL::IO::Color> by_component;
      std::size_t bad = 0;
      auto f_ref = merged.faces().begin();
      for(Face_index f : read.faces())
      {
        const CGAL::IO::Color c = color.first[f];
        const int k = comp.first[f];
        bad += (c == ref_color[*f_ref] && k == ref_comp[*f_ref]) ? 0 : 1;
        bad += (c == BS::Blended_shape_pieces<K>::component_color(std::size_t(k))) ? 0 : 1;
        auto it = by_component.emplace(k, c).first;
        bad += (it->second == c) ? 0 : 1;
        ++f_ref;
      }
      BS_CHECK(bad == 0, what << ": " << bad << " face colors or components differ");
      BS_CHECK(by_component.size() == s.number_of_components(),
               what << ": faces of " << by_component.size() << " components, expected " << s.number_of_components());
      std::set<std::tuple<int, int, int>> distinct;
      for(const auto& kc : by_component)
        distinct.insert(std::make_tuple(int(kc.second.red()), int(kc.second.green()), int(kc.second.blue())));
      BS_CHECK(distinct.size() == by_component.size(), what << ": two components share a color");
    }
    BS_CHECK(file_text(dir / "pieces_binary.ply").size() < file_text(dir / "pieces_ascii.ply").size(),
             kernel << ": the binary PLY is not smaller than the ASCII one");
  }

  void test_unified_off()
  {
    const Shape s = torus_like();
    const Mesh m = BS::make_unified_mesh(s, 10, 3);
    const fs::path file = dir / "unified.off";
    try
    {
      BS::write_unified_mesh_off(file.string(), m);
    }
    catch(const std::exception& e)
    {
      BS_CHECK(false, kernel << ": writing the OFF file threw: " << e.what());
      return;
    }
    Mesh read;
    {
      std::ifstream in(file);
      BS_CHECK(in && CGAL::IO::read_OFF(in, read), kernel << ": CGAL::IO::read_OFF failed");
    }
    check_same_mesh(m, read, kernel + ", OFF");
    const long chi = long(read.number_of_vertices()) - long(read.number_of_edges()) + long(read.number_of_faces());
    BS_CHECK(CGAL::is_closed(read) && chi == 0, kernel << ": the OFF mesh is not a closed genus-1 mesh (chi " << chi << ")");
    // The overload that builds the mesh writes the same file.
    const fs::path file2 = dir / "unified_from_shape.off";
    try
    {
      BS::write_unified_mesh_off(file2.string(), s, 10, 3);
      BS_CHECK(file_text(file2) == file_text(file), kernel << ": the two OFF overloads write different files");
    }
    catch(const std::exception& e)
    {
      BS_CHECK(false, kernel << ": write_unified_mesh_off(path, shape) threw: " << e.what());
    }
  }

  // `write` must throw an exception of type E whose message contains
  // `fragment`, and leave the directory as it was (no file, no temporary).
  template <class E, class F>
  void expect_failure(const std::string& what, const std::string& fragment, F write)
  {
    const std::set<std::string> before = listing(dir);
    bool threw = false;
    try
    {
      write();
    }
    catch(const E& e)
    {
      threw = true;
      BS_CHECK(contains(e.what(), fragment), kernel << ": " << what << ": message lacks '" << fragment << "': " << e.what());
      std::cout << "  " << what << ": " << e.what() << std::endl;
    }
    catch(const std::exception& e)
    {
      threw = true;
      BS_CHECK(false, kernel << ": " << what << ": wrong exception type: " << e.what());
    }
    BS_CHECK(threw, kernel << ": " << what << ": no exception");
    BS_CHECK(listing(dir) == before, kernel << ": " << what << ": the directory changed");
  }

  void test_failures()
  {
    const Shape s = three_components();
    const BS::Blended_shape_pieces<K> pieces(s, 6);
    const Mesh m = BS::make_unified_mesh(torus_like(), 10, 3);
    const std::string missing = (dir / "no_such_dir" / "mesh").string();
    expect_failure<std::runtime_error>("PLY into a missing directory", "no_such_dir",
                                       [&] { BS::write_blended_shape_pieces_ply(missing + ".ply", pieces); });
    expect_failure<std::runtime_error>("OFF into a missing directory", "no_such_dir",
                                       [&] { BS::write_unified_mesh_off(missing + ".off", m); });
    expect_failure<std::runtime_error>("OFF of a shape into a missing directory", "writable",
                                       [&] { BS::write_unified_mesh_off(missing + ".off", s, 8, 2); });
    BS_CHECK(!fs::exists(dir / "no_such_dir"), kernel << ": a missing directory was created");
    // A directory as the output path: the rename fails, the temporary goes.
    fs::create_directory(dir / "a_directory.ply");
    fs::create_directory(dir / "a_directory.ply" / "inside");
    expect_failure<std::runtime_error>("PLY onto a directory", "a_directory.ply",
                                       [&] { BS::write_blended_shape_pieces_ply((dir / "a_directory.ply").string(), pieces); });
    expect_failure<std::invalid_argument>("PLY with an empty path", "empty",
                                          [&] { BS::write_blended_shape_pieces_ply("", pieces); });
    expect_failure<std::invalid_argument>("OFF with an empty path", "empty",
                                          [&] { BS::write_unified_mesh_off("", m); });
    // An existing file survives a failed write untouched.
    const fs::path kept = dir / "kept.off";
    BS::write_unified_mesh_off(kept.string(), m);
    const std::string old_text = file_text(kept);
    Mesh bad = m;
    bad.point(*bad.vertices().begin()) = Point_3(std::numeric_limits<double>::quiet_NaN(), 0., 0.);
    expect_failure<std::invalid_argument>("OFF with a NaN vertex", "non-finite",
                                          [&] { BS::write_unified_mesh_off(kept.string(), bad); });
    BS_CHECK(file_text(kept) == old_text, kernel << ": a failed write changed the existing file");
    // A mesh that cannot be built: nothing is written.
    expect_failure<std::invalid_argument>("OFF of a shape at resolution 1", "resolution",
                                          [&] { BS::write_unified_mesh_off((dir / "never.off").string(), s, 1, 2); });
  }

  void run()
  {
    std::cout << "kernel " << kernel << std::endl;
    dir = fs::temp_directory_path() /
          ("blended_shape_mesh_io_" + kernel + "_" + std::to_string(std::random_device()()));
    fs::create_directories(dir);
    try
    {
      test_pieces_ply();
      test_unified_off();
      test_failures();
    }
    catch(const std::exception& e)
    {
      BS_CHECK(false, kernel << ": unexpected exception: " << e.what());
    }
    std::error_code ec;
    fs::remove_all(dir, ec);
  }
};

// Every check of this part.
void run_all()
{
  blended_shape_test::for_each_kernel([](auto kernel, const char* name) { Tester<decltype(kernel)>{name, {}}.run(); });
}

} // namespace blended_shape_mesh_io_checks

#endif // BLENDED_SHAPE_BLENDED_SHAPE_MESH_IO_CHECKS_H
