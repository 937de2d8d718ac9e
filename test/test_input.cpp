// SPDX-License-Identifier: LGPL-3.0-or-later
// Tests of the file input and point checks: every Input_error code, each
// file format, both kernels. Every test writes its own small files into a
// fresh temporary directory, removed at the end.

#include <CGAL/Blended_shape/IO/Input_error.h>
#include <CGAL/Blended_shape/IO/check_points.h>
#include <CGAL/Blended_shape/IO/read_points.h>
#include <CGAL/Blended_shape/IO/read_triangle_mesh.h>

#include "test_util.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/IO/PLY.h>
#include <CGAL/IO/write_ply_points.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/helpers.h>
#include <CGAL/property_map.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

namespace fs = std::filesystem;
namespace BS = CGAL::Blended_shapes;

namespace {

int failures() { return blended_shape_test::failures(); }

// One line per test: SUCCESS if it added no failure.
void report(const std::string& name, int failures_before)
{
  if(failures() == failures_before)
    std::cout << name << ": SUCCESS" << std::endl;
  else
    std::cout << name << ": FAILED" << std::endl;
}

// A fresh directory under the system temporary directory, removed on destruction.
struct Temp_dir
{
  fs::path path;

  Temp_dir()
  {
    std::random_device device;
    const auto ticks = std::chrono::steady_clock::now().time_since_epoch().count();
    path = fs::temp_directory_path() /
           ("blended_shape_test_input_" + std::to_string(ticks) + "_" + std::to_string(device()));
    fs::create_directories(path);
  }
  ~Temp_dir()
  {
    std::error_code ec;
    fs::permissions(path / "locked.xyz", fs::perms::owner_all, ec); // let remove_all delete it
    fs::remove_all(path, ec);
  }
  std::string file(const std::string& name) const { return (path / name).string(); }
};

std::string write_file(const Temp_dir& dir, const std::string& name, const std::string& content)
{
  const std::string filename = dir.file(name);
  std::ofstream out(filename, std::ios::binary);
  out << content;
  return filename;
}

bool contains(const std::string& text, const std::string& part)
{
  return text.find(part) != std::string::npos;
}

// Runs `f`, which must throw an Input_error with `code` whose message contains every `parts`.
void expect_error(BS::Input_error::Code code, const std::function<void()>& f,
                  const std::vector<std::string>& parts, const std::string& context)
{
  try
  {
    f();
    BS_CHECK(false, context << ": no exception, expected " << BS::Input_error::code_name(code));
  }
  catch(const BS::Input_error& e)
  {
    BS_CHECK(e.code() == code, context << ": code " << BS::Input_error::code_name(e.code())
                                    << " instead of " << BS::Input_error::code_name(code)
                                    << " (" << e.what() << ")");
    for(const std::string& part : parts)
      BS_CHECK(contains(e.what(), part), context << ": message lacks '" << part << "': " << e.what());
  }
  catch(const std::exception& e)
  {
    BS_CHECK(false, context << ": unexpected exception: " << e.what());
  }
}

// n distinct points with non-round coordinates, on a helix.
template <class Point_3>
std::vector<Point_3> helix(std::size_t n)
{
  std::vector<Point_3> points;
  for(std::size_t i = 0; i < n; ++i)
  {
    const double t = 0.37 * double(i) + 0.1;
    points.push_back(Point_3(std::cos(t) / 3., std::sin(t) * 1.7, t / 7.));
  }
  return points;
}

template <class Point_3>
std::string xyz_lines(const std::vector<Point_3>& points)
{
  std::ostringstream s;
  s.precision(17);
  for(const Point_3& p : points)
    s << p.x() << ' ' << p.y() << ' ' << p.z() << '\n';
  return s.str();
}

template <class Point_3>
bool same_points(const std::vector<Point_3>& a, const std::vector<Point_3>& b)
{
  if(a.size() != b.size())
    return false;
  for(std::size_t i = 0; i < a.size(); ++i)
    if(a[i].x() != b[i].x() || a[i].y() != b[i].y() || a[i].z() != b[i].z())
      return false;
  return true;
}

// The bytes of `value` as a binary PLY file stores it, in big- or little-endian order.
template <class T>
std::string ply_bytes(T value, bool big_endian)
{
  std::string bytes(sizeof(T), '\0');
  std::memcpy(&bytes[0], &value, sizeof(T));
  const std::uint16_t one = 1;
  unsigned char first_byte;
  std::memcpy(&first_byte, &one, 1);
  if(big_endian == (first_byte == 1)) // the host's order is the other one
    std::reverse(bytes.begin(), bytes.end());
  return bytes;
}

// A binary PLY file of the points (float) with one face of vertices 0, 1, 2
// whose list, of type `list int int`, claims `length` entries.
template <class Point_3>
std::string binary_ply_with_face(const std::vector<Point_3>& points, std::int32_t length, bool big_endian)
{
  std::string ply = std::string("ply\nformat ") + (big_endian ? "binary_big_endian" : "binary_little_endian") +
                    " 1.0\nelement vertex " + std::to_string(points.size()) +
                    "\nproperty float x\nproperty float y\nproperty float z\n"
                    "element face 1\nproperty list int int vertex_indices\nend_header\n";
  for(const Point_3& p : points)
    for(int k = 0; k < 3; ++k)
      ply += ply_bytes(float(CGAL::to_double(p[k])), big_endian);
  ply += ply_bytes(length, big_endian);
  for(std::int32_t v = 0; v < 3; ++v)
    ply += ply_bytes(v, big_endian);
  return ply;
}

// Reads `filename`, expecting the error `code`; also checks `points` is left empty.
template <class Point_3>
void expect_read_error(BS::Input_error::Code code, const std::string& filename,
                       const std::vector<std::string>& parts, const std::string& context)
{
  std::vector<Point_3> points = helix<Point_3>(3); // must be emptied
  expect_error(code, [&] { BS::read_points(filename, points); }, parts, context);
  BS_CHECK(points.empty(), context << ": output not empty after an error");
}

// ---------------------------------------------------------------------------

void test_error_codes()
{
  const int before = failures();
  typedef BS::Input_error E;
  const std::pair<E::Code, const char*> names[] = {
    {E::File_not_found, "file_not_found"},       {E::Unreadable_file, "unreadable_file"},
    {E::Unsupported_format, "unsupported_format"}, {E::Malformed_content, "malformed_content"},
    {E::No_points, "no_points"},                 {E::Too_few_points, "too_few_points"},
    {E::Non_finite_point, "non_finite_point"},   {E::All_points_identical, "all_points_identical"},
    {E::Scale_out_of_range, "scale_out_of_range"}};
  for(const auto& n : names)
  {
    BS_CHECK(std::strcmp(E::code_name(n.first), n.second) == 0, "code_name of " << n.second);
    const E e(n.first, "message");
    BS_CHECK(e.code() == n.first && std::string(e.what()) == "message", "Input_error stores " << n.second);
  }
  BS_CHECK(BS::minimum_number_of_points == 10, "minimum_number_of_points");
  report("Input_error codes", before);
}

template <class K>
void test_file_errors(const Temp_dir& dir, const std::string& kernel)
{
  typedef typename K::Point_3 Point_3;
  const int before = failures();

  const std::string missing = dir.file("missing.xyz");
  expect_read_error<Point_3>(BS::Input_error::File_not_found, missing, {"missing.xyz"}, "missing file");
  expect_read_error<Point_3>(BS::Input_error::File_not_found, "", {"empty"}, "empty file name");

  const std::string directory = dir.file("folder.xyz");
  fs::create_directories(directory);
  expect_read_error<Point_3>(BS::Input_error::Unreadable_file, directory, {"folder.xyz", "directory"},
                             "directory as file");

  // Without read permission; root can read anything, so the check only runs for other users.
  const std::string locked = write_file(dir, "locked.xyz", xyz_lines(helix<Point_3>(12)));
  fs::permissions(locked, fs::perms::none);
  if(std::ifstream(locked).good())
    std::cout << "  (no-permission check skipped: this user can read a file with mode 000)" << std::endl;
  else
    expect_read_error<Point_3>(BS::Input_error::Unreadable_file, locked, {"locked.xyz", "permission"},
                               "no read permission");
  fs::permissions(locked, fs::perms::owner_all);

  const std::string las = write_file(dir, "cloud.las", xyz_lines(helix<Point_3>(12)));
  expect_read_error<Point_3>(BS::Input_error::Unsupported_format, las, {"cloud.las", ".las", ".xyz", ".ply", ".stl"},
                             "unsupported extension");
  const std::string no_extension = write_file(dir, "cloud", xyz_lines(helix<Point_3>(12)));
  expect_read_error<Point_3>(BS::Input_error::Unsupported_format, no_extension, {"no extension"},
                             "no extension");

  report("read_points file errors (" + kernel + ")", before);
}

template <class K>
void test_text_formats(const Temp_dir& dir, const std::string& kernel)
{
  typedef typename K::Point_3 Point_3;
  const int before = failures();
  const std::vector<Point_3> twelve = helix<Point_3>(12);

  // Plain round trip, exact with 17 digits.
  {
    std::vector<Point_3> points;
    const BS::Read_report r = BS::read_points(write_file(dir, "plain.xyz", xyz_lines(twelve)), points);
    BS_CHECK(same_points(points, twelve), "plain .xyz round trip");
    BS_CHECK(r.points_read == 12 && r.non_finite_dropped == 0 && r.format == "xyz", "plain .xyz report");
  }
  // Comments, blank lines, tabs, CRLF, extra columns, upper-case extension: all accepted.
  {
    std::string content = "# exported by a scanner\n\n";
    std::ostringstream s;
    s.precision(17);
    for(const Point_3& p : twelve)
      s << "  " << p.x() << '\t' << p.y() << "  " << p.z() << " 0 0 1 255 128 0\r\n";
    content += s.str() + "   \n# end\n";
    std::vector<Point_3> points;
    const BS::Read_report r = BS::read_points(write_file(dir, "columns.PWN", content), points);
    BS_CHECK(same_points(points, twelve), "comments, CRLF, extra columns");
    BS_CHECK(r.format == "pwn", "format of .PWN is " << r.format);
  }
  // .pts with a count line; the same line in a .xyz is an error on line 1.
  {
    const std::string content = "12\n" + xyz_lines(twelve);
    std::vector<Point_3> points;
    const BS::Read_report r = BS::read_points(write_file(dir, "scan.pts", content), points);
    BS_CHECK(same_points(points, twelve) && r.format == "pts", ".pts count line skipped");
    expect_read_error<Point_3>(BS::Input_error::Malformed_content, write_file(dir, "count.xyz", content),
                               {"line 1", "count.xyz", "only 1 number"}, "count line in .xyz");
  }
  // .txt is the same text format.
  {
    std::vector<Point_3> points;
    const BS::Read_report r = BS::read_points(write_file(dir, "cloud.txt", xyz_lines(twelve)), points);
    BS_CHECK(same_points(points, twelve) && r.format == "txt", ".txt");
  }

  // Malformed content, with the line number.
  {
    const std::string content = "# header\n1 2 3\n4 abc 6\n" + xyz_lines(twelve);
    expect_read_error<Point_3>(BS::Input_error::Malformed_content, write_file(dir, "token.xyz", content),
                               {"line 3", "token.xyz", "'abc' is not a number"}, "non-numeric token");
    const std::string glued = "1 2 3\n1.5x 2 3\n" + xyz_lines(twelve);
    expect_read_error<Point_3>(BS::Input_error::Malformed_content, write_file(dir, "glued.xyz", glued),
                               {"line 2", "'1.5x'"}, "number followed by letters");
    const std::string binary = std::string("1 2 3\n4 \x01\xff") + "z 6\n" + xyz_lines(twelve);
    expect_read_error<Point_3>(BS::Input_error::Malformed_content, write_file(dir, "binary.xyz", binary),
                               {"line 2", "'\\x01\\xffz' is not a number"}, "bytes that are not text");
    const std::string two = xyz_lines(twelve) + "\n1 2\n";
    expect_read_error<Point_3>(BS::Input_error::Malformed_content, write_file(dir, "two.xyz", two),
                               {"line 14", "only 2 numbers"}, "line with 2 numbers");
  }

  // Empty: an empty file, and a file with only comments.
  expect_read_error<Point_3>(BS::Input_error::No_points, write_file(dir, "empty.xyz", ""), {"empty.xyz", "empty"},
                             "empty file");
  expect_read_error<Point_3>(BS::Input_error::No_points, write_file(dir, "comments.xyz", "# nothing\n\n"),
                             {"no points"}, "comments only");

  // 9 points are too few, 10 are enough.
  expect_read_error<Point_3>(BS::Input_error::Too_few_points,
                             write_file(dir, "nine.xyz", xyz_lines(helix<Point_3>(9))),
                             {"nine.xyz", "only 9 points", "at least 10"}, "9 points");
  {
    std::vector<Point_3> points;
    BS::read_points(write_file(dir, "ten.xyz", xyz_lines(helix<Point_3>(10))), points);
    BS_CHECK(points.size() == 10, "10 points accepted");
  }

  // Non-finite points are dropped and counted.
  {
    const std::string bad = "nan 1 2\n0 inf 2\n0 1 -INF\n1e999 0 0\n0 0 NaN\n";
    std::vector<Point_3> points;
    const BS::Read_report r = BS::read_points(write_file(dir, "nan.xyz", bad + xyz_lines(twelve)), points);
    BS_CHECK(r.non_finite_dropped == 5 && r.points_read == 12, "dropped " << r.non_finite_dropped);
    BS_CHECK(same_points(points, twelve), "finite points kept in order");
    expect_read_error<Point_3>(BS::Input_error::Too_few_points,
                               write_file(dir, "nan_few.xyz", bad + xyz_lines(helix<Point_3>(8))),
                               {"only 8 points", "after dropping 5 points with NaN or infinite"},
                               "too few after dropping");
    expect_read_error<Point_3>(BS::Input_error::No_points, write_file(dir, "nan_all.xyz", bad),
                               {"no points", "after dropping 5"}, "all dropped");
  }

  // All identical.
  {
    std::string same;
    for(int i = 0; i < 12; ++i)
      same += "1.5 -2 3\n";
    expect_read_error<Point_3>(BS::Input_error::All_points_identical, write_file(dir, "same.xyz", same),
                               {"same.xyz", "all 12 points", "identical", "1.5 -2 3"}, "identical points");
  }

  report("read_points text formats and errors (" + kernel + ")", before);
}

template <class K>
void test_ply(const Temp_dir& dir, const std::string& kernel)
{
  typedef typename K::Point_3 Point_3;
  const int before = failures();
  const std::vector<Point_3> cloud = helix<Point_3>(40);

  const std::string ascii = dir.file("ascii.ply");
  BS_CHECK(CGAL::IO::write_PLY(ascii, cloud, CGAL::parameters::use_binary_mode(false).stream_precision(17)),
        "write ascii PLY");
  const std::string binary = dir.file("binary.PLY");
  BS_CHECK(CGAL::IO::write_PLY(binary, cloud, CGAL::parameters::use_binary_mode(true)), "write binary PLY");
  for(const std::string& filename : {ascii, binary})
  {
    std::vector<Point_3> points;
    const BS::Read_report r = BS::read_points(filename, points);
    BS_CHECK(same_points(points, cloud), "PLY round trip " << filename);
    BS_CHECK(r.format == "ply" && r.points_read == 40, "PLY report " << filename);
  }

  // Binary PLY can hold NaN: dropped like in text.
  {
    std::vector<Point_3> with_nan = cloud;
    const double nan = std::numeric_limits<double>::quiet_NaN();
    with_nan.insert(with_nan.begin() + 5, Point_3(nan, 0., 0.));
    const std::string filename = dir.file("nan.ply");
    BS_CHECK(CGAL::IO::write_PLY(filename, with_nan, CGAL::parameters::use_binary_mode(true)), "write NaN PLY");
    std::vector<Point_3> points;
    const BS::Read_report r = BS::read_points(filename, points);
    BS_CHECK(r.non_finite_dropped == 1 && same_points(points, cloud), "PLY NaN dropped");
  }

  // A PLY with faces gives its vertices.
  {
    const std::vector<std::vector<std::size_t> > faces = {{0, 1, 2}, {2, 3, 4, 5}};
    const std::string filename = dir.file("mesh.ply");
    BS_CHECK(CGAL::IO::write_PLY(filename, cloud, faces, CGAL::parameters::use_binary_mode(true)),
          "write PLY mesh");
    std::vector<Point_3> points;
    BS::read_points(filename, points);
    BS_CHECK(same_points(points, cloud), "vertices of a PLY mesh");
  }

  // Broken PLY files.
  expect_read_error<Point_3>(BS::Input_error::Malformed_content,
                             write_file(dir, "garbage.ply", "this is not a ply file\n1 2 3\n"),
                             {"garbage.ply", "not a PLY file"}, "PLY garbage");
  const std::string header = "ply\nformat ascii 1.0\nelement vertex 12\n";
  expect_read_error<Point_3>(BS::Input_error::Malformed_content,
                             write_file(dir, "truncated.ply", header +
                                        "property float x\nproperty float y\nproperty float z\n"
                                        "end_header\n1 2 3\n4 5 6\n"),
                             {"truncated.ply"}, "PLY truncated");
  expect_read_error<Point_3>(BS::Input_error::Malformed_content,
                             write_file(dir, "integer.ply", header +
                                        "property int x\nproperty int y\nproperty int z\n"
                                        "end_header\n1 2 3\n"),
                             {"integer.ply", "have coordinate x of type int"}, "PLY with integer coordinates");
  expect_read_error<Point_3>(BS::Input_error::Malformed_content,
                             write_file(dir, "no_z.ply", header +
                                        "property float x\nproperty float y\nend_header\n1 2\n"),
                             {"no_z.ply", "lack an x, y or z"}, "PLY without z");

  // Corrupt list lengths are refused before CGAL's reader allocates them
  // (2^31 - 1 entries took it 8 GB and 38 s; a test would run out of memory).
  {
    std::vector<Point_3> small(cloud.begin(), cloud.begin() + 12);
    for(Point_3& p : small) // exactly floats, to compare
      p = Point_3(float(CGAL::to_double(p.x())), float(CGAL::to_double(p.y())), float(CGAL::to_double(p.z())));
    for(const bool big_endian : {false, true})
    {
      const std::string name = big_endian ? "big.ply" : "little.ply";
      std::vector<Point_3> points;
      BS::read_points(write_file(dir, name, binary_ply_with_face(small, 3, big_endian)), points);
      BS_CHECK(same_points(points, small), "binary PLY with a face, " << name);
    }
    expect_read_error<Point_3>(BS::Input_error::Malformed_content,
                               write_file(dir, "long_list.ply", binary_ply_with_face(small, 2147483647, false)),
                               {"long_list.ply", "'vertex_indices' of face 0", "claims 2147483647 entries"},
                               "PLY list length past the file");
    expect_read_error<Point_3>(BS::Input_error::Malformed_content,
                               write_file(dir, "negative_list.ply", binary_ply_with_face(small, -3, true)),
                               {"negative_list.ply", "negative length"}, "PLY negative list length");
    std::string cut = binary_ply_with_face(small, 3, false);
    cut.resize(cut.size() - 30); // inside the points
    expect_read_error<Point_3>(BS::Input_error::Malformed_content, write_file(dir, "cut.ply", cut),
                               {"cut.ply", "ends inside vertex 10", "of the 12"}, "PLY binary truncated");
    const std::string ascii_face = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
                                   "property float y\nproperty float z\nelement face 1\n"
                                   "property list int int vertex_indices\nend_header\n"
                                   "0 0 0\n1 0 0\n0 1 0\n";
    expect_read_error<Point_3>(BS::Input_error::Malformed_content,
                               write_file(dir, "long_ascii.ply", ascii_face + "2147483647 0 1 2\n"),
                               {"long_ascii.ply", "claims 2147483647 entries"}, "PLY ascii list length");
    expect_read_error<Point_3>(BS::Input_error::Malformed_content,
                               write_file(dir, "word_ascii.ply", ascii_face + "three 0 1 2\n"),
                               {"word_ascii.ply", "the length 'three'"}, "PLY ascii list length not a count");
    expect_read_error<Point_3>(BS::Input_error::Malformed_content,
                               write_file(dir, "type.ply", "ply\nformat ascii 1.0\nelement vertex 1\n"
                                                           "property float x\nproperty float y\n"
                                                           "property float z\nproperty quad w\nend_header\n"
                                                           "0 0 0 0\n"),
                               {"type.ply", "unknown type 'quad'"}, "PLY unknown type");
  }

  report("read_points PLY ascii/binary (" + kernel + ")", before);
}

template <class K>
void test_mesh_vertices(const Temp_dir& dir, const std::string& kernel)
{
  typedef typename K::Point_3 Point_3;
  const int before = failures();
  const std::vector<Point_3> twelve = helix<Point_3>(12);

  std::ostringstream off, obj;
  off.precision(17);
  obj.precision(17);
  off << "OFF\n12 2 0\n\n";
  for(const Point_3& p : twelve)
  {
    off << p << '\n';
    obj << "v " << p << '\n';
  }
  off << "3 0 1 2\n4 3 4 5 6\n";
  obj << "f 1 2 3\nf 4 5 6 7\n";
  for(const auto& [name, content, format] :
      {std::make_tuple("mesh.off", off.str(), "off"), std::make_tuple("mesh.Obj", obj.str(), "obj")})
  {
    std::vector<Point_3> points;
    const BS::Read_report r = BS::read_points(write_file(dir, name, content), points);
    BS_CHECK(same_points(points, twelve) && r.format == format, "vertices of " << name);
  }

  // ASCII STL: each triangle repeats its vertices, which are welded back, in
  // the order of their first occurrence.
  auto strip_stl = [](const std::vector<Point_3>& points) {
    std::ostringstream stl;
    stl.precision(17);
    stl << "solid strip\n";
    for(std::size_t i = 0; i + 2 < points.size(); ++i)
    {
      stl << "facet normal 0 0 1\nouter loop\n";
      for(std::size_t v = i; v < i + 3; ++v)
        stl << "vertex " << points[v] << '\n';
      stl << "endloop\nendfacet\n";
    }
    stl << "endsolid strip\n";
    return stl.str();
  };
  {
    std::vector<Point_3> points;
    const BS::Read_report r = BS::read_points(write_file(dir, "strip.stl", strip_stl(twelve)), points);
    BS_CHECK(same_points(points, twelve) && r.format == "stl", "welded STL strip: " << points.size());
  }
  // 6 welded points are too few (12 unwelded would pass).
  expect_read_error<Point_3>(BS::Input_error::Too_few_points,
                             write_file(dir, "six.stl", strip_stl(helix<Point_3>(6))),
                             {"only 6 points"}, "STL welded");

  expect_read_error<Point_3>(BS::Input_error::Malformed_content,
                             write_file(dir, "truncated.off", "OFF\n12 0 0\n1 2 3\n4 5\n"),
                             {"truncated.off", "not a valid OFF file"}, "truncated OFF");

  // The weld itself (CGAL 5.5's STL reader already merges, the OFF reader does not).
  {
    const Point_3 a(1, 2, 3), b(-1, 0, 0.5), c(1, 2, 3.5);
    std::vector<Point_3> points = {c, a, c, b, a, a};
    const std::vector<std::size_t> index = BS::internal::weld_exact_duplicates(points);
    BS_CHECK(same_points(points, std::vector<Point_3>{c, a, b}), "weld keeps first occurrences in order");
    BS_CHECK((index == std::vector<std::size_t>{0, 1, 0, 2, 1, 1}), "weld index map");
  }

  // The bundled files.
  {
    std::vector<Point_3> points;
    const BS::Read_report r = BS::read_points(BLENDED_SHAPE_DATA_DIR "/scans/pcl_mug_scan.xyz", points);
    BS_CHECK(r.points_read == 16234 && points.size() == 16234 && r.non_finite_dropped == 0,
          "mug scan: " << r.points_read << " points");
  }
  {
    std::vector<Point_3> points;
    const BS::Read_report r =
      BS::read_points(BLENDED_SHAPE_DATA_DIR "/meshes/trimesh_plate_holes.STL", points);
    BS_CHECK(r.points_read == 618 && points.size() == 618 && r.format == "stl",
          "plate STL: " << r.points_read << " welded points");
  }
  {
    std::vector<Point_3> points;
    BS::read_points(BLENDED_SHAPE_DATA_DIR "/meshes/cgal_hole.off", points);
    BS_CHECK(points.size() == 20, "hole.off: " << points.size() << " vertices");
  }

  report("read_points OFF/OBJ/STL vertices and bundled data (" + kernel + ")", before);
}

template <class K>
void test_check_points(const std::string& kernel)
{
  typedef typename K::Point_3 Point_3;
  typedef std::pair<Point_3, int> Tagged;
  typedef CGAL::First_of_pair_property_map<Tagged> Tag_map;
  const int before = failures();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();

  // Each case is checked with the identity map and with a pair map.
  auto check_both = [&](const std::vector<Point_3>& points, bool ok, BS::Input_error::Code code,
                        const std::vector<std::string>& parts, const std::string& context) {
    std::vector<Tagged> tagged;
    for(const Point_3& p : points)
      tagged.push_back(Tagged(p, int(tagged.size())));
    if(ok)
    {
      try
      {
        BS::check_points(points);
        BS::check_points(tagged, Tag_map());
      }
      catch(const std::exception& e)
      {
        BS_CHECK(false, context << ": unexpected " << e.what());
      }
      return;
    }
    expect_error(code, [&] { BS::check_points(points); }, parts, context + " (identity map)");
    expect_error(code, [&] { BS::check_points(tagged, Tag_map()); }, parts, context + " (pair map)");
  };

  std::vector<Point_3> good = helix<Point_3>(10);
  check_both(good, true, BS::Input_error::No_points, {}, "10 points");

  check_both({}, false, BS::Input_error::No_points, {"check_points", "no points"}, "empty");
  check_both(helix<Point_3>(9), false, BS::Input_error::Too_few_points, {"only 9 points"}, "9 points");

  std::vector<Point_3> with_nan = good;
  with_nan[5] = Point_3(0., nan, 1.);
  check_both(with_nan, false, BS::Input_error::Non_finite_point, {"point 5 ", "nan"}, "NaN");
  std::vector<Point_3> with_inf = good;
  with_inf[7] = Point_3(0., 1., -inf);
  with_inf[8] = Point_3(nan, 1., 1.);
  check_both(with_inf, false, BS::Input_error::Non_finite_point, {"point 7 ", "inf"}, "first of two bad");
  // In memory, a bad point is an error even when the count is also too small.
  std::vector<Point_3> few_with_nan(3, Point_3(nan, 0., 0.));
  check_both(few_with_nan, false, BS::Input_error::Non_finite_point, {"point 0 "}, "NaN before count");

  check_both(std::vector<Point_3>(11, Point_3(1., 2., 3.)), false, BS::Input_error::All_points_identical,
             {"all 11 points", "identical", "1 2 3"}, "identical");
  std::vector<Point_3> one_differs(11, Point_3(1., 2., 3.));
  one_differs.back() = Point_3(1., 2., 3.0000000001);
  check_both(one_differs, true, BS::Input_error::No_points, {}, "one point differs");

  // Collinear points are not an error here.
  std::vector<Point_3> line;
  for(int i = 0; i < 12; ++i)
    line.push_back(Point_3(i, 2 * i, 0));
  check_both(line, true, BS::Input_error::No_points, {}, "collinear");

  report("check_points (" + kernel + ")", before);
}

// V - E + F = 2 - 2g for a closed connected surface.
template <class Mesh>
long genus(const Mesh& mesh)
{
  const long chi = long(num_vertices(mesh)) - long(num_edges(mesh)) + long(num_faces(mesh));
  return (2 - chi) / 2;
}

template <class K>
void test_read_triangle_mesh(const Temp_dir& dir, const std::string& kernel)
{
  typedef typename K::Point_3 Point_3;
  typedef CGAL::Surface_mesh<Point_3> Mesh;
  const int before = failures();

  {
    Mesh mesh;
    BS::read_triangle_mesh(BLENDED_SHAPE_DATA_DIR "/meshes/cgal_hole.off", mesh);
    BS_CHECK(num_vertices(mesh) == 20, "hole.off vertices " << num_vertices(mesh));
    BS_CHECK(CGAL::is_closed(mesh) && CGAL::is_triangle_mesh(mesh) && genus(mesh) == 1,
          "hole.off closed triangulated genus 1 (genus " << genus(mesh) << ")");
  }
  {
    Mesh mesh;
    BS::read_triangle_mesh(BLENDED_SHAPE_DATA_DIR "/meshes/trimesh_plate_holes.STL", mesh);
    BS_CHECK(num_vertices(mesh) == 618 && num_faces(mesh) == 1252, "plate STL V/F " << num_vertices(mesh)
                                                                  << "/" << num_faces(mesh));
    BS_CHECK(CGAL::is_closed(mesh) && genus(mesh) == 5, "plate STL closed genus 5 (" << genus(mesh) << ")");
  }

  // A cube of quads that repeats its corners, plus a face that collapses after
  // welding and a repeated face: 8 vertices, 12 triangles, closed, genus 0.
  {
    const char* corners[8] = {"0 0 0", "1 0 0", "1 1 0", "0 1 0", "0 0 1", "1 0 1", "1 1 1", "0 1 1"};
    const int quads[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4},
                             {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
    std::ostringstream off;
    off << "OFF\n" << 6 * 4 + 3 << " 8 0\n";
    for(const auto& q : quads)
      for(int v : q)
        off << corners[v] << '\n';
    off << "0 0 0\n0 0 0\n1 1 1\n"; // collapses: two copies of corner 0
    for(int f = 0; f < 6; ++f)
      off << "4 " << 4 * f << ' ' << 4 * f + 1 << ' ' << 4 * f + 2 << ' ' << 4 * f + 3 << '\n';
    off << "3 24 25 26\n";
    off << "4 0 1 2 3\n"; // the first quad again
    Mesh mesh;
    BS::read_triangle_mesh(write_file(dir, "cube.OFF", off.str()), mesh);
    BS_CHECK(num_vertices(mesh) == 8 && num_faces(mesh) == 12, "welded cube V/F " << num_vertices(mesh)
                                                              << "/" << num_faces(mesh));
    BS_CHECK(CGAL::is_closed(mesh) && genus(mesh) == 0, "welded cube closed genus 0");
  }

  // Errors, and the output mesh is untouched by them.
  Mesh mesh;
  BS::read_triangle_mesh(BLENDED_SHAPE_DATA_DIR "/meshes/cgal_hole.off", mesh);
  const std::size_t faces_before = num_faces(mesh);
  auto expect_mesh_error = [&](BS::Input_error::Code code, const std::string& filename,
                               const std::vector<std::string>& parts, const std::string& context) {
    expect_error(code, [&] { BS::read_triangle_mesh(filename, mesh); }, parts, context);
    BS_CHECK(num_vertices(mesh) == 20 && num_faces(mesh) == faces_before, context << ": mesh modified by a failed read");
  };
  expect_mesh_error(BS::Input_error::File_not_found, dir.file("missing.off"), {"missing.off"}, "missing mesh");
  const std::string directory = dir.file("folder.off");
  fs::create_directories(directory);
  expect_mesh_error(BS::Input_error::Unreadable_file, directory, {"directory"}, "directory as mesh");
  expect_mesh_error(BS::Input_error::Unsupported_format, write_file(dir, "mesh.xyz", "1 2 3\n"),
                    {".xyz", ".off, .obj, .ply, .stl"}, "points as mesh");
  expect_mesh_error(BS::Input_error::No_points, write_file(dir, "empty.obj", ""),
                    {"mesh has no faces"}, "empty mesh file");
  expect_mesh_error(BS::Input_error::No_points,
                    write_file(dir, "points_only.off", "OFF\n3 0 0\n0 0 0\n1 0 0\n0 1 0\n"),
                    {"points_only.off", "mesh has no faces"}, "OFF without faces");
  expect_mesh_error(BS::Input_error::No_points,
                    write_file(dir, "flat.off", "OFF\n4 1 0\n0 0 0\n1 0 0\n0 0 0\n0 1 0\n3 0 1 2\n"),
                    {"degenerate", "mesh has no faces"}, "only degenerate faces");
  expect_mesh_error(BS::Input_error::Malformed_content,
                    write_file(dir, "bad.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 zero\n3 0 1 2\n"),
                    {"bad.off", "not a valid OFF file"}, "malformed OFF");
  expect_mesh_error(BS::Input_error::Malformed_content,
                    write_file(dir, "index.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n"),
                    {"index.obj"}, "face index out of range");
  {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const std::vector<Point_3> points = {Point_3(0, 0, 0), Point_3(1, 0, 0), Point_3(0, nan, 0),
                                         Point_3(0, 0, 1)};
    const std::vector<std::vector<std::size_t> > faces = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}};
    const std::string filename = dir.file("nan.ply");
    BS_CHECK(CGAL::IO::write_PLY(filename, points, faces, CGAL::parameters::use_binary_mode(true)),
          "write NaN mesh");
    expect_mesh_error(BS::Input_error::Non_finite_point, filename, {"nan.ply", "vertex 2 "}, "NaN vertex");
  }
  expect_mesh_error(BS::Input_error::Malformed_content,
                    write_file(dir, "long_list_mesh.ply",
                               binary_ply_with_face(std::vector<Point_3>{Point_3(0, 0, 0), Point_3(1, 0, 0),
                                                                         Point_3(0, 1, 0)},
                                                    2147483647, true)),
                    {"long_list_mesh.ply", "claims 2147483647 entries"}, "PLY mesh list length past the file");

  report("read_triangle_mesh (" + kernel + ")", before);
}

template <class K>
void test_kernel(const Temp_dir& dir, const std::string& kernel)
{
  test_file_errors<K>(dir, kernel);
  test_text_formats<K>(dir, kernel);
  test_ply<K>(dir, kernel);
  test_mesh_vertices<K>(dir, kernel);
  test_check_points<K>(kernel);
  test_read_triangle_mesh<K>(dir, kernel);
}

} // namespace

int main()
{
  test_error_codes();
  {
    Temp_dir dir;
#ifndef BLENDED_SHAPE_ONE_KERNEL // sanitizer builds: Epick only (see test/CMakeLists.txt)
    test_kernel<CGAL::Simple_cartesian<double> >(dir, "Simple_cartesian<double>");
#endif
  }
  {
    Temp_dir dir;
    test_kernel<CGAL::Exact_predicates_inexact_constructions_kernel>(dir, "Epick");
  }
  if(failures() != 0)
    std::cerr << failures() << " check(s) failed" << std::endl;
  return blended_shape_test::exit_code();
}
