// SPDX-License-Identifier: LGPL-3.0-or-later
// Saving and loading whole blended shapes as JSON: the JSON layer (numbers
// read back bit for bit, strict syntax, positions in errors, depth limit),
// round trips of models built through the API (sphere; split; part; hole
// switched to its tube and opened; all of them together) compared bit for
// bit (parameters, structure, evaluated points, the written text), the file
// functions, and corrupt or truncated inputs, which must throw Input_error
// with a useful message, with both supported kernels.
#ifndef BLENDED_SHAPE_BLENDED_SHAPE_IO_CHECKS_H
#define BLENDED_SHAPE_BLENDED_SHAPE_IO_CHECKS_H
// Part of test_blended_shape (one program, one compilation of the blended
// shape for each kernel; CTest runs it as `test_blended_shape_io`).
#include "test_util.h"

#include <CGAL/Blended_shape/Blending/Blended_shape.h>
#include <CGAL/Blended_shape/IO/Blended_shape_io.h>
#include <CGAL/Blended_shape/IO/internal/json_text.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Simple_cartesian.h>

#include <Eigen/Core>

#include <cfloat>
#include <clocale>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <limits>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <typeinfo>
#include <utility>
#include <vector>

namespace blended_shape_io_checks {

namespace BS = CGAL::Blended_shapes;
namespace json = CGAL::Blended_shapes::internal; // the JSON layer: json_text.h

std::mt19937_64 rng(20240917);
double uniform(double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng); }

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof(double)) == 0; }

template <class V>
bool same_bits(const V& a, const V& b)
{
  if(a.size() != b.size())
    return false;
  for(Eigen::Index i = 0; i < a.size(); ++i)
    if(!same_bits(a[i], b[i]))
      return false;
  return true;
}

bool contains(const std::string& s, const std::string& fragment) { return s.find(fragment) != std::string::npos; }

// ---------------------------------------------------------------------------
// The JSON layer.

double parse_number_text(const std::string& t)
{
  const json::Json v = json::parse_json(t);
  if(!v.is_number())
    throw std::logic_error("not a number");
  return v.get<double>();
}

void check_number_round_trip(double x)
{
  const std::string t = json::json_number_text(x);
  const double y = parse_number_text(t);
  BS_CHECK(same_bits(x, y), "number " << t << " does not read back bit for bit");
  // 17 significant digits read back too.
  std::ostringstream s;
  s.imbue(std::locale::classic());
  s.precision(17);
  s << x;
  const std::string t17 = s.str();
  const double z = parse_number_text(t17);
  BS_CHECK(same_bits(x, z), "number " << t17 << " (17 digits) does not read back bit for bit");
}

template <class F>
std::string parse_error_of(F f)
{
  try
  {
    f();
  }
  catch(const json::Json_syntax_error& e)
  {
    return e.what();
  }
  return std::string();
}

void test_json()
{
  // Numbers: special values, and random bit patterns.
  for(double x : {0., -0., 1., -1., 0.1, 1. / 3., 2. / 3., M_PI, 1e-300, -1e300, DBL_MAX, -DBL_MAX, DBL_MIN,
                  std::numeric_limits<double>::denorm_min(), 5e-324, 123456789012345678., 1e21, 1e22, 9007199254740993.})
    check_number_round_trip(x);
  BS_CHECK(std::signbit(parse_number_text(json::json_number_text(-0.))), "-0 loses its sign: " << json::json_number_text(-0.));
  BS_CHECK(json::json_number_text(-0.) == "-0", "-0 is written " << json::json_number_text(-0.));
  std::uniform_int_distribution<std::uint64_t> bits;
  for(int k = 0; k < 20000; ++k)
  {
    const std::uint64_t b = bits(rng);
    double x;
    std::memcpy(&x, &b, sizeof(x));
    if(std::isfinite(x))
      check_number_round_trip(x);
  }
  for(int k = 0; k < 2000; ++k)
    check_number_round_trip(uniform(-10., 10.));
  BS_CHECK(parse_number_text("1E+2") == 100., "1E+2");
  BS_CHECK(parse_number_text("-0.0e-0") == 0. && std::signbit(parse_number_text("-0.0e-0")), "-0.0e-0");

  // The same under a locale with a decimal comma, if the system has one.
  for(const char* name : {"de_DE.UTF-8", "fr_FR.UTF-8", "de_DE", "fr_FR"})
    if(std::setlocale(LC_ALL, name))
    {
      check_number_round_trip(0.1);
      check_number_round_trip(-1234.5678);
      BS_CHECK(json::json_number_text(0.5) == "0.5", "locale " << name << " changes the output: " << json::json_number_text(0.5));
      std::setlocale(LC_ALL, "C");
      break;
    }

  // Invalid numbers and literals.
  for(const char* bad : {"01", "1.", ".5", "+1", "-", "1e", "1e+", "0x10", "NaN", "nan", "Infinity", "-Infinity", "inf",
                         "1e400", "-1e400", "tru", "nul", "'a'", "[1,]", "{\"a\":1,}", "[1 2]", "{\"a\" 1}",
                         "{1: 2}", "\"abc", "\"a\\qb\"", "\"a\tb\"", "\"\\u12\"", "\"\\ud800\"", "\"\\udc00\"", "[",
                         "{", "{\"a\":", "1 2", "[] []", "{\"a\":1,\"a\":2}", "/*c*/1"})
  {
    const std::string e = parse_error_of([&] { json::parse_json(bad); });
    BS_CHECK(!e.empty(), "'" << bad << "' parses");
    BS_CHECK(contains(e, "line 1, column "), "no position in the error for '" << bad << "': " << e);
  }
  BS_CHECK(contains(parse_error_of([] { json::parse_json("[NaN]"); }), "NaN and Infinity are not JSON"), "NaN message");
  BS_CHECK(contains(parse_error_of([] { json::parse_json("{\"a\":1,\"a\":2}"); }), "duplicate member name \"a\""),
           "duplicate key message");
  BS_CHECK(contains(parse_error_of([] { json::parse_json("1e999"); }), "out of the range of a double"), "overflow message");
  BS_CHECK(contains(parse_error_of([] { json::parse_json("[1 2]"); }), "expected ',' or ']'"), "array message");
  {
    const std::string e = parse_error_of([] { json::parse_json("{\n  \"a\": [1,\n   x]}"); });
    BS_CHECK(contains(e, "line 3, column 4") && contains(e, "expected a JSON value"), "position: " << e);
  }
  {
    const std::string e = parse_error_of([] { json::parse_json(""); });
    BS_CHECK(contains(e, "end of input"), "empty: " << e);
  }
  // Depth: 64 levels are fine, 65 are not; 10000 do not crash.
  {
    std::string ok = std::string(64, '[') + std::string(64, ']');
    BS_CHECK(parse_error_of([&] { json::parse_json(ok); }).empty(), "64 levels are refused");
    std::string deep = std::string(65, '[') + std::string(65, ']');
    BS_CHECK(contains(parse_error_of([&] { json::parse_json(deep); }), "nested deeper than 64"), "65 levels");
    std::string very = std::string(10000, '[') + std::string(10000, ']');
    BS_CHECK(contains(parse_error_of([&] { json::parse_json(very); }), "nested deeper than 64"), "10000 levels");
    std::string objects;
    for(int i = 0; i < 10000; ++i)
      objects += "{\"a\":";
    BS_CHECK(contains(parse_error_of([&] { json::parse_json(objects); }), "nested deeper than 64"), "10000 objects");
  }
  // Size limit.
  {
    json::Json_limits small;
    small.max_size = 10;
    BS_CHECK(contains(parse_error_of([&] { json::parse_json("[1, 2, 3, 4, 5]", small); }), "larger than 10 bytes"),
             "size limit");
  }
  // Strings: escapes, UTF-8, round trip through the writer.
  {
    const json::Json v = json::parse_json("[\"a\\\"b\\\\c\\/d\\b\\f\\n\\r\\t\\u00e9\\ud83d\\ude00\\u0001\"]");
    BS_CHECK(v.size() == 1 && v[0].get<std::string>() == "a\"b\\c/d\b\f\n\r\t\xC3\xA9\xF0\x9F\x98\x80\x01",
             "string escapes");
    std::ostringstream s;
    json::write_json(s, v);
    const json::Json w = json::parse_json(s.str());
    BS_CHECK(w[0].get<std::string>() == v[0].get<std::string>(), "string round trip: " << s.str());
  }
  // The writer: structure, order of members, non-finite numbers refused.
  {
    json::Json o = json::Json::object();
    o["z"] = -0.;
    o["a"] = json::Json::array();
    o["m"] = json::Json::array({true, nullptr, 0.1});
    std::ostringstream s;
    json::write_json(s, o);
    BS_CHECK(s.str() == "{\"z\": -0, \"a\": [], \"m\": [true, null, 0.1]}\n", "writer output: " << s.str());
    json::Json big = json::Json::object(), numbers = json::Json::array();
    for(int i = 0; i < 9; ++i)
      numbers.push_back(double(i));
    big["n"] = numbers;
    big["s"] = "x";
    std::ostringstream f;
    json::write_json(f, big);
    BS_CHECK(f.str() == "{\n  \"n\": [0, 1, 2, 3, 4, 5, 6, 7, 8],\n  \"s\": \"x\"\n}\n", "writer output: " << f.str());
    json::Json n = json::Json::array({std::nan("")});
    bool threw = false;
    try
    {
      std::ostringstream t;
      json::write_json(t, n);
    }
    catch(const std::invalid_argument&)
    {
      threw = true;
    }
    BS_CHECK(threw, "NaN is written");
    // Byte order mark, surrounding white space.
    BS_CHECK(json::parse_json("\xEF\xBB\xBF \r\n\t[1]\n ").size() == 1, "BOM and white space");
  }
}

// ---------------------------------------------------------------------------
// Models.

template <class K>
struct Io_tests
{
  typedef BS::Blended_shape<K> Shape;
  typedef typename Shape::Ellipsoid Ellipsoid;
  typedef typename Shape::Toroid Toroid;
  typedef typename Shape::Hole Hole;
  typedef BS::Ellipse_blending_region Region;

  std::string kernel;

  static Ellipsoid random_sphere()
  {
    return Ellipsoid(uniform(0.9, 1.1), uniform(0.9, 1.1), uniform(0.9, 1.1), uniform(0.85, 1.15),
                     uniform(0.85, 1.15), uniform(0.18, 0.27));
  }

  static Region::Parameter_vector region(double u, double v, double r, double h = 0.)
  {
    return Region::make_parameters(u + uniform(-0.02, 0.02), v + uniform(-0.02, 0.02), r * uniform(0.9, 1.1),
                                   r * uniform(0.7, 0.9), uniform(-1., 1.), uniform(0.6, 0.95), h);
  }

  static void set_parameter(Shape& s, std::size_t i, double x)
  {
    Eigen::VectorXd q = s.parameters();
    q[Eigen::Index(i)] = x;
    s.set_parameters(q);
  }

  static Shape sphere() { return Shape(random_sphere()); }

  static void add_split(Shape& s, std::size_t c, std::size_t chart, double u, double v)
  {
    const std::size_t b = s.split(c, chart, region(u, v, 0.22), uniform(0.04, 0.06));
    const std::size_t k = s.blend(b).added_component();
    Eigen::VectorXd q = s.parameters();
    const Eigen::Index o = Eigen::Index(s.component_offset(k)), so = Eigen::Index(s.shape_offset(k));
    for(int i = 0; i < 3; ++i)
      q[o + i] += uniform(-0.1, 0.1); // translation
    for(int i = 0; i < 4; ++i)
      q[o + 3 + i] += uniform(-0.05, 0.05); // quaternion
    for(int i = 0; i < 3; ++i)
      q[so + i] *= uniform(0.8, 1.25); // a1, a2, a3
    q[so + 3] = uniform(0.5, 1.5);       // e1
    q[so + 4] = uniform(0.5, 1.5);       // e2
    s.set_parameters(q);
  }

  static void add_part(Shape& s, std::size_t c, std::size_t chart, double u, double v)
  {
    const Toroid part(uniform(0.3, 0.4), uniform(0.3, 0.4), uniform(0.1, 0.15), uniform(2., 3.), uniform(2., 3.),
                      uniform(0.7, 1.2), uniform(0.7, 1.2));
    const Eigen::Vector3d t(uniform(0.8, 1.), uniform(-0.1, 0.1), uniform(0.2, 0.4));
    const Eigen::Vector4d q(uniform(0.8, 1.), uniform(-0.2, 0.2), uniform(-0.2, 0.2), uniform(-0.2, 0.2));
    const std::size_t b = s.add_part(c, chart, region(u, v, 0.2), uniform(0.04, 0.06), part, "superquadric_toroid",
                                     t, q, 0, region(3.1, 3.2, 0.5), uniform(0.08, 0.12));
    set_parameter(s, s.blend_offset(b) + Region::H, 0.3);
  }

  static std::size_t add_hole(Shape& s, const BS::Shape_point& first, const BS::Shape_point& second)
  {
    const std::size_t h = s.add_hole(first, second, uniform(0.14, 0.17), uniform(0.04, 0.05), uniform(0.08, 0.12));
    const typename Shape::Hole_record r = s.holes()[h];
    Eigen::VectorXd q = s.parameters();
    for(std::size_t e = 0; e < 2; ++e)
      q[Eigen::Index(s.blend_offset(r.blends[e]) + Region::H)] = 0.;
    s.set_parameters(q);
    s.switch_hole_to_tube(h);
    q = s.parameters();
    q[Eigen::Index(s.shape_offset(r.component) + Hole::A4)] = 1.4;
    q[Eigen::Index(s.shape_offset(r.component) + Hole::A5)] = 1.4;
    s.set_parameters(q);
    return h;
  }

  static Shape model(int which)
  {
    Shape s = sphere();
    switch(which)
    {
    case 0: break;
    case 1: add_split(s, 0, 0, 0.3, -0.2); break;
    case 2: add_part(s, 0, 1, 0.2, 0.25); break;
    case 3:
      add_hole(s, BS::Shape_point(0, BS::Chart_point(0, 0.12, 0.08)), BS::Shape_point(0, BS::Chart_point(1, -0.1, 0.15)));
      break;
    default:
    {
      // Everything together, with a second level: a split of the finished part.
      add_split(s, 0, 0, 0.5, 0.05);
      add_part(s, 0, 1, 0.5, 0.05);
      const std::size_t b = s.number_of_blends() - 1;
      set_parameter(s, s.blend_offset(b) + Region::H, 0.);
      s.finish_gradual_blend(b);
      add_hole(s, BS::Shape_point(0, BS::Chart_point(0, -0.5, 0.1)), BS::Shape_point(0, BS::Chart_point(1, -0.5, -0.1)));
      const std::size_t part = s.blend(b).added_component();
      s.split(part, 0, region(3.1, 3.2, 0.15), 0.05); // inside the part's retained ellipse
      // A second, still closed hole between the split piece and the root.
      s.add_hole(BS::Shape_point(1, BS::Chart_point(0, 0.5, 0.05)),
                 BS::Shape_point(0, BS::Chart_point(1, 0.05, -0.6)), 0.05, 0.015);
      break;
    }
    }
    return s;
  }

  static const char* model_name(int which)
  {
    static const char* names[] = {"sphere", "sphere + split", "sphere + part", "sphere + hole", "all"};
    return names[which];
  }

  static std::string to_text(const Shape& s)
  {
    std::ostringstream out;
    BS::write_blended_shape_json(out, s);
    return out.str();
  }

  static Shape from_text(const std::string& t)
  {
    std::istringstream in(t);
    return BS::read_blended_shape_json<K>(in);
  }

  static bool same_region(const Region& a, const Region& b)
  {
    return a.chart() == b.chart() && a.kind() == b.kind() && a.retained_side() == b.retained_side() &&
           same_bits(a.half_width(), b.half_width()) && a.number_of_segments() == b.number_of_segments() &&
           a.region().thetas().size() == b.region().thetas().size() &&
           std::memcmp(a.region().thetas().data(), b.region().thetas().data(),
                       sizeof(double) * a.region().thetas().size()) == 0 &&
           same_bits(a.parameters(), b.parameters());
  }

  // Everything that defines the model, bit for bit.
  static void check_same(const Shape& a, const Shape& b, const std::string& what)
  {
    BS_CHECK(a.number_of_components() == b.number_of_components(), what << ": components");
    BS_CHECK(a.number_of_blends() == b.number_of_blends(), what << ": blends");
    BS_CHECK(a.holes().size() == b.holes().size(), what << ": holes");
    BS_CHECK(a.number_of_parameters() == b.number_of_parameters(), what << ": parameters");
    if(a.number_of_components() != b.number_of_components() || a.number_of_blends() != b.number_of_blends() ||
       a.holes().size() != b.holes().size() || a.number_of_parameters() != b.number_of_parameters())
      return;
    const Eigen::VectorXd pa = a.parameters(), pb = b.parameters();
    BS_CHECK(std::memcmp(pa.data(), pb.data(), sizeof(double) * std::size_t(pa.size())) == 0,
             what << ": parameters differ");
    for(std::size_t i = 0; i < a.number_of_parameters(); ++i)
    {
      BS_CHECK(a.is_fixed_parameter(i) == b.is_fixed_parameter(i), what << ": fixed parameter " << i);
      BS_CHECK(a.parameter_name(i) == b.parameter_name(i), what << ": parameter name " << i);
    }
    for(std::size_t c = 0; c < a.number_of_components(); ++c)
    {
      const auto& ka = a.component(c);
      const auto& kb = b.component(c);
      BS_CHECK(ka.shape().type_name() == kb.shape().type_name(), what << ": type of component " << c);
      BS_CHECK(ka.shape().number_of_charts() == kb.shape().number_of_charts(), what << ": charts of " << c);
      BS_CHECK(same_bits(ka.translation(), kb.translation()) && same_bits(ka.quaternion(), kb.quaternion()),
               what << ": placement of " << c);
      BS_CHECK(same_bits(ka.shape().parameters(), kb.shape().parameters()), what << ": shape of " << c);
      const Ellipsoid* ea = ka.shape().template primitive<Ellipsoid>();
      const Ellipsoid* eb = kb.shape().template primitive<Ellipsoid>();
      BS_CHECK(bool(ea) == bool(eb), what << ": ellipsoid " << c);
      if(ea && eb)
        BS_CHECK(same_bits(ea->chart_margin(), eb->chart_margin()), what << ": chart margin of " << c);
      BS_CHECK(bool(ka.shape().template primitive<Toroid>()) == bool(kb.shape().template primitive<Toroid>()),
               what << ": toroid " << c);
      const Hole* ha = ka.shape().template primitive<Hole>();
      const Hole* hb = kb.shape().template primitive<Hole>();
      BS_CHECK(bool(ha) == bool(hb), what << ": hole component " << c);
      if(ha && hb)
        BS_CHECK(ha->domain() == hb->domain(), what << ": hole domain of " << c);
    }
    for(std::size_t i = 0; i < a.number_of_blends(); ++i)
    {
      const BS::Blend& x = a.blend(i);
      const BS::Blend& y = b.blend(i);
      BS_CHECK(x.kind() == y.kind() && x.base_component() == y.base_component() &&
                 x.added_component() == y.added_component() && x.hole() == y.hole() &&
                 x.is_gradual() == y.is_gradual(),
               what << ": blend " << i);
      BS_CHECK(same_region(x.base_region(), y.base_region()), what << ": base region of blend " << i);
      const BS::Added_side& sx = x.added_side();
      const BS::Added_side& sy = y.added_side();
      BS_CHECK(sx.kind() == sy.kind(), what << ": added side of blend " << i);
      if(sx.kind() != sy.kind())
        continue;
      if(sx.kind() == BS::Added_side::Ellipse)
        BS_CHECK(same_region(sx.ellipse_region(), sy.ellipse_region()), what << ": added region of blend " << i);
      else
        BS_CHECK(sx.end() == sy.end() && same_bits(sx.delta(), sy.delta()) && same_bits(sx.phase(), sy.phase()),
                 what << ": hole end of blend " << i);
    }
    for(std::size_t h = 0; h < a.holes().size(); ++h)
      BS_CHECK(a.holes()[h].component == b.holes()[h].component && a.holes()[h].blends == b.holes()[h].blends,
               what << ": hole " << h);
    BS_CHECK(a.genus() == b.genus(), what << ": genus");

    // Evaluated points, bit for bit, at random shape points.
    int on_surface = 0;
    for(int k = 0; k < 400; ++k)
    {
      const std::size_t c = std::size_t(std::uniform_int_distribution<int>(0, int(a.number_of_components()) - 1)(rng));
      const BS::Component_shape& s = a.component(c).shape();
      const std::size_t chart =
        std::size_t(std::uniform_int_distribution<int>(0, int(s.number_of_charts()) - 1)(rng));
      const BS::Chart_domain d = s.chart_domain(chart);
      double x, y;
      if(d.kind == BS::Chart_kind::Disk)
      {
        const double r = d.radius * std::sqrt(uniform(0., 1.)), t = uniform(0., 2. * M_PI);
        x = r * std::cos(t);
        y = r * std::sin(t);
      }
      else
      {
        x = uniform(0., 2. * M_PI);
        y = uniform(d.y_min, d.y_max);
      }
      const BS::Shape_point p(c, BS::Chart_point(chart, x, y));
      on_surface += a.is_on_surface(p) ? 1 : 0;
      BS_CHECK(a.is_on_surface(p) == b.is_on_surface(p), what << ": is_on_surface differs");
      const typename K::Point_3 xa = a.point(p), xb = b.point(p);
      BS_CHECK(same_bits(CGAL::to_double(xa.x()), CGAL::to_double(xb.x())) &&
                 same_bits(CGAL::to_double(xa.y()), CGAL::to_double(xb.y())) &&
                 same_bits(CGAL::to_double(xa.z()), CGAL::to_double(xb.z())),
               what << ": point() differs at component " << c << " chart " << chart << " (" << x << ", " << y
                    << "): " << xa << " vs " << xb);
    }
    BS_CHECK(on_surface > 0, what << ": no random point on the surface");
  }

  void test_round_trips()
  {
    for(int which = 0; which < 5; ++which)
    {
      const std::string what = kernel + ", " + model_name(which);
      Shape s = sphere();
      try
      {
        s = model(which);
      }
      catch(const std::exception& e)
      {
        BS_CHECK(false, what << ": building the model failed: " << e.what());
        continue;
      }
      std::string text;
      try
      {
        text = to_text(s);
        const Shape t = from_text(text);
        check_same(s, t, what);
        const std::string again = to_text(t);
        BS_CHECK(again == text, what << ": the second write differs from the first");
        // A copy of the copy: still the same.
        check_same(s, from_text(again), what + " (twice)");
      }
      catch(const std::exception& e)
      {
        BS_CHECK(false, what << ": round trip failed: " << e.what() << "\n" << text);
      }
      if(std::getenv("BLENDED_SHAPE_IO_VERBOSE"))
        std::cout << what << ":\n" << text;
      if(which == 4)
      {
        BS_CHECK(s.number_of_components() == 6 && s.number_of_blends() == 7 && s.holes().size() == 2 &&
                   s.genus() == 1,
                 what << ": unexpected structure");
        test_files(s, text);
        test_corrupt(text);
#ifdef BLENDED_SHAPE_REDUCED_TESTS
        int rounds = 300;
#else
        int rounds = 3000;
#endif
        if(const char* r = std::getenv("BLENDED_SHAPE_IO_FUZZ_ROUNDS"))
          rounds = std::atoi(r);
        test_fuzz(text, rounds);
      }
      if(which == 3)
        test_hole_errors(text);
    }
  }

  // The file functions: atomic writes, missing files, directories.
  void test_files(const Shape& s, const std::string& text)
  {
    namespace fs = std::filesystem;
    const fs::path dir = fs::temp_directory_path() / ("blended_shape_io_" + kernel + "_" +
                                                      std::to_string(std::random_device()()));
    fs::create_directories(dir);
    const std::string file = (dir / "model.json").string();
    try
    {
      BS::write_blended_shape(file, s);
      std::ifstream in(file, std::ios::binary);
      std::stringstream buf;
      buf << in.rdbuf();
      BS_CHECK(buf.str() == text, kernel << ": the file differs from the stream output");
      const Shape t = BS::read_blended_shape<K>(file);
      check_same(s, t, kernel + ", file");
      // Overwriting works, and leaves only the model in the directory.
      BS::write_blended_shape(file, t);
      int n = 0;
      for(const fs::directory_entry& e : fs::directory_iterator(dir))
        n += (e.path().filename() == "model.json") ? 1 : 100;
      BS_CHECK(n == 1, kernel << ": stray files next to the model");
    }
    catch(const std::exception& e)
    {
      BS_CHECK(false, kernel << ": file round trip failed: " << e.what());
    }
    expect_file_error((dir / "no_such_model.json").string(), BS::Input_error::File_not_found, "no such file");
    expect_file_error("", BS::Input_error::File_not_found, "empty file name");
    expect_file_error(dir.string(), BS::Input_error::Unreadable_file, "is a directory");
    {
      std::ofstream(dir / "empty.json").close();
      expect_file_error((dir / "empty.json").string(), BS::Input_error::Malformed_content, "empty");
      std::ofstream(dir / "bad.json") << text.substr(0, text.size() / 2);
      expect_file_error((dir / "bad.json").string(), BS::Input_error::Malformed_content, "bad.json': not valid JSON");
    }
    // A failed write leaves nothing behind.
    bool threw = false;
    try
    {
      BS::write_blended_shape((dir / "no_such_dir" / "model.json").string(), s);
    }
    catch(const std::runtime_error&)
    {
      threw = true;
    }
    BS_CHECK(threw && !fs::exists(dir / "no_such_dir"), kernel << ": writing into a missing directory");
    std::error_code ec;
    fs::remove_all(dir, ec);
  }

  void expect_file_error(const std::string& file, BS::Input_error::Code code, const std::string& fragment)
  {
    try
    {
      BS::read_blended_shape<K>(file);
      BS_CHECK(false, kernel << ": reading '" << file << "' does not throw");
    }
    catch(const BS::Input_error& e)
    {
      BS_CHECK(e.code() == code, kernel << ": '" << file << "': code " << BS::Input_error::code_name(e.code()));
      BS_CHECK(contains(e.what(), fragment), kernel << ": '" << file << "': message lacks '" << fragment
                                                      << "': " << e.what());
    }
    catch(const std::exception& e)
    {
      BS_CHECK(false, kernel << ": reading '" << file << "' throws something else than Input_error: " << e.what());
    }
  }

  // `text` must fail to load with a message containing every fragment.
  void expect_error(const std::string& text, const std::vector<std::string>& fragments, const std::string& label,
                    BS::Input_error::Code code = BS::Input_error::Malformed_content)
  {
    try
    {
      from_text(text);
      BS_CHECK(false, kernel << ": " << label << ": loads without error");
    }
    catch(const BS::Input_error& e)
    {
      if(std::getenv("BLENDED_SHAPE_IO_VERBOSE"))
        std::cout << label << ":\n    " << e.what() << std::endl;
      BS_CHECK(e.code() == code, kernel << ": " << label << ": code " << BS::Input_error::code_name(e.code()) << ": "
                                        << e.what());
      for(const std::string& f : fragments)
        BS_CHECK(contains(e.what(), f), kernel << ": " << label << ": message lacks '" << f << "': " << e.what());
    }
    catch(const std::exception& e)
    {
      BS_CHECK(false, kernel << ": " << label << ": throws something else than Input_error: " << e.what());
    }
  }

  // `text` with the `n`-th occurrence of `from` replaced by `to`.
  std::string replaced(const std::string& text, const std::string& from, const std::string& to, int n = 0)
  {
    std::size_t p = text.find(from);
    for(int k = 0; k < n && p != std::string::npos; ++k)
      p = text.find(from, p + 1);
    BS_CHECK(p != std::string::npos, kernel << ": test setup: '" << from << "' not in the model text");
    if(p == std::string::npos)
      return text;
    return text.substr(0, p) + to + text.substr(p + from.size());
  }

  // `text` with the value of the `n`-th scalar member `key` replaced by `value`.
  std::string with_value(const std::string& text, const std::string& key, const std::string& value, int n = 0)
  {
    const std::string k = "\"" + key + "\": ";
    std::size_t p = text.find(k);
    for(int i = 0; i < n && p != std::string::npos; ++i)
      p = text.find(k, p + 1);
    BS_CHECK(p != std::string::npos, kernel << ": test setup: '" << key << "' not in the model text");
    if(p == std::string::npos)
      return text;
    p += k.size();
    std::size_t e;
    if(text[p] == '{' || text[p] == '[')
    {
      // A container: up to the matching bracket (model texts have no brackets in strings).
      int depth = 0;
      for(e = p;; ++e)
      {
        depth += (text[e] == '{' || text[e] == '[') ? 1 : (text[e] == '}' || text[e] == ']') ? -1 : 0;
        if(depth == 0)
          break;
      }
      ++e;
    }
    else
      e = text.find_first_of(",}]\n", p);
    return text.substr(0, p) + value + text.substr(e);
  }

  // `text` without the (whole) line holding the `n`-th occurrence of `needle`.
  std::string without_line(const std::string& text, const std::string& needle, int n = 0)
  {
    std::size_t p = text.find(needle);
    for(int i = 0; i < n && p != std::string::npos; ++i)
      p = text.find(needle, p + 1);
    BS_CHECK(p != std::string::npos, kernel << ": test setup: '" << needle << "' not in the model text");
    if(p == std::string::npos)
      return text;
    const std::size_t b = text.rfind('\n', p) + 1, e = text.find('\n', p);
    return text.substr(0, b) + text.substr(e + 1);
  }

  // `text` with element `i` of the array after the `n`-th `"key": [` replaced by `value`.
  std::string with_element(const std::string& text, const std::string& key, std::size_t i, const std::string& value,
                           int n = 0)
  {
    const std::string k = "\"" + key + "\": [";
    std::size_t p = text.find(k);
    for(int j = 0; j < n && p != std::string::npos; ++j)
      p = text.find(k, p + 1);
    BS_CHECK(p != std::string::npos, kernel << ": test setup: '" << key << "' not in the model text");
    if(p == std::string::npos)
      return text;
    p += k.size();
    for(std::size_t j = 0; j < i; ++j)
      p = text.find(',', p) + 2;
    const std::size_t e = text.find_first_of(",]", p);
    return text.substr(0, p) + value + text.substr(e);
  }

  void test_corrupt(const std::string& text)
  {
    const auto M = BS::Input_error::Malformed_content;
    (void)M;
    const auto U = BS::Input_error::Unsupported_format;
    // Syntax.
    expect_error("", {"read_blended_shape_json", "empty"}, "empty input");
    expect_error(" \n\t\n", {"empty"}, "white space only");
    int truncations = 0;
    for(std::size_t n = 0; n < text.size(); n += 7)
    {
      const std::string t = text.substr(0, n);
      if(t.find_first_not_of(" \n") == std::string::npos || text.find_first_not_of(" \n", n) == std::string::npos)
        continue; // empty (covered above), or only the final white space cut
      ++truncations;
      expect_error(t, {"not valid JSON", "end of input", "line "}, "truncated at byte " + std::to_string(n));
    }
    BS_CHECK(truncations > 100, kernel << ": only " << truncations << " truncations");
    expect_error(text + "x", {"after the JSON document"}, "garbage after the document");
    expect_error(text + "{}", {"after the JSON document"}, "a second document");
    expect_error(std::string(10000, '[') + std::string(10000, ']'), {"nested deeper than 64"}, "deep nesting");
    expect_error(replaced(text, "\"hierarchy\": [", "\"hierarchy\": [" + std::string(10000, '[')),
                 {"nested deeper than 64"}, "deep nesting inside the model");
    expect_error(with_value(text, "a1", "NaN"), {"not valid JSON", "NaN and Infinity are not JSON numbers"},
                 "bare NaN");
    expect_error(with_value(text, "a1", "-Infinity"), {"NaN and Infinity"}, "bare -Infinity");
    expect_error(with_value(text, "a1", "1e999"), {"out of the range of a double"}, "overflow");
    expect_error(replaced(text, "\"version\"", "\"format\": \"blended_shape\",\n  \"version\""),
                 {"duplicate member name \"format\""}, "duplicate key");
    expect_error(replaced(text, "\"chart_margin\"", "\"chart_margin\\q\""), {"not valid JSON", "escape"},
                 "bad escape");
    // The format.
    expect_error("[1, 2]", {"expected a JSON object", "not a blended shape model"}, "an array", U);
    expect_error("{\"type\": \"FeatureCollection\"}", {"missing field \"format\"", "not a blended shape model"},
                 "no format", U);
    expect_error(with_value(text, "format", "\"mesh\""), {"format: expected \"blended_shape\"", "\"mesh\""},
                 "wrong format", U);
    expect_error(with_value(text, "version", "1"), {"version: expected 2", "found a number 1"}, "older version", U);
    expect_error(with_value(text, "version", "3"), {"version: expected 2", "found a number 3"}, "newer version", U);
    expect_error(with_value(text, "version", "\"2\""), {"version: expected 2", "found a string"},
                 "version as a string", U);
    expect_error(replaced(text, "\"blends\": [", "\"colour\": \"red\",\n  \"blends\": ["),
                 {"unknown field \"colour\"", "format, version, components"}, "unknown top-level field", M);
    expect_error(with_value(text, "components", "[]"), {"components: expected at least one component"},
                 "no component");
    {
      std::string many = "[";
      for(int i = 0; i < 1001; ++i)
        many += (i ? ", " : "") + std::string("{}");
      expect_error(with_value(text, "components", many + "]"), {"components: 1001 components; at most 1000"},
                   "too many components");
    }
    // Components.
    expect_error(with_value(text, "type", "\"superquadric_hyperboloid\""),
                 {"components[0].type", "unknown component type \"superquadric_hyperboloid\"",
                  "superquadric_ellipsoid, superquadric_toroid and hole_component"},
                 "unknown type");
    expect_error(without_line(text, "\"chart_margin\""), {"components[0]: missing field \"chart_margin\""},
                 "missing chart margin");
    expect_error(with_value(text, "chart_margin", "1.5"), {"components[0].chart_margin", "(0, 1)"},
                 "chart margin out of bounds");
    expect_error(with_value(text, "e1", "3.5"), {"components[0].parameters.e1", "out of bounds", "[0.01, 2]"},
                 "parameter out of bounds");
    expect_error(with_value(text, "a2", "-0.5"), {"components[0].parameters.a2", "out of bounds"},
                 "negative semi-axis");
    expect_error(with_value(text, "a2", "true"), {"components[0].parameters.a2", "expected a number, found a boolean"},
                 "wrong type");
    expect_error(replaced(text, "\"a2\"", "\"b2\""), {"components[0].parameters", "unknown parameter \"b2\"",
                                                      "a1, a2, a3, e1, e2"},
                 "unknown parameter");
    expect_error(with_value(text, "parameters", "[1, 1, 1, 1]"),
                 {"components[0].parameters", "expected an array of 5 numbers, found 4 elements"},
                 "parameters as a short array");
    {
      // Parameters as an array in order are accepted too.
      const json::Json doc = json::parse_json(text);
      const json::Json& q = doc.at("components")[0].at("parameters");
      std::string a = "[";
      for(auto it = q.begin(); it != q.end(); ++it)
        a += (it != q.begin() ? ", " : "") + json::json_number_text(it->get<double>());
      a += "]";
      try
      {
        BS_CHECK(to_text(from_text(with_value(text, "parameters", a))) == text, kernel << ": parameters as an array");
      }
      catch(const std::exception& e)
      {
        BS_CHECK(false, kernel << ": parameters as an array: " << e.what());
      }
    }
    expect_error(with_element(text, "translation", 1, "0.5"), {"the root component (component 0) is not placed"},
                 "root translated");
    expect_error(with_value(text, "translation", "\"here\"", 1), {"components[1].translation",
                                                                  "expected an array of 3 numbers, found a string"},
                 "translation as a string");
    expect_error(with_value(text, "quaternion", "[0, 0, 0, 0]", 1), {"components[1].quaternion", "nonzero"},
                 "zero quaternion");
    expect_error(without_line(text, "\"translation\"", 1), {"components[1]: missing field \"translation\""},
                 "missing translation");
    // Blends.
    expect_error(with_value(text, "added_component", "9"),
                 {"blends[0].added_component", "component index 9 is out of range", "6 components"},
                 "component index out of range");
    expect_error(with_value(text, "base_component", "-1"), {"blends[0].base_component", "non-negative integer"},
                 "negative index");
    expect_error(with_value(text, "base_component", "0.5"), {"blends[0].base_component", "non-negative integer"},
                 "fractional index");
    expect_error(with_value(text, "added_component", "0"), {"blends[0].added_component", "root"}, "root added");
    expect_error(without_line(text, "\"base_component\"", 0), {"blends[0]: missing field \"base_component\""},
                 "missing field");
    expect_error(with_value(text, "segments", "\"8\""), {"blends[0].region.segments", "expected a number, found a string"},
                 "segments as a string");
    expect_error(with_value(text, "segments", "3"), {"blends[0].region.segments", "from 4 to 4096"}, "3 segments");
    expect_error(with_value(text, "segments", "1e15"), {"blends[0].region.segments", "from 4 to 4096"},
                 "huge segment count");
    expect_error(with_value(text, "kind", "\"merge\""), {"blends[0].kind", "unknown blend kind \"merge\""},
                 "unknown blend kind");
    expect_error(with_value(text, "chart", "2"), {"blends[0].region.chart", "chart index 2 is out of range: component 0 has 2 charts (0 to 1)"},
                 "chart out of range");
    expect_error(with_value(text, "half_width", "-0.05"), {"blends[0].region.half_width", "must be positive"},
                 "negative half-width");
    expect_error(with_value(text, "core_stretch", "-2"), {"blends[0].core_stretch", "expected a positive number"},
                 "negative core stretch");
    expect_error(with_value(text, "core_stretch", "0"), {"blends[0].core_stretch", "expected a positive number"},
                 "zero core stretch");
    expect_error(with_value(text, "half_width", "0.9"), {"blends[0].region", "Blending_region"},
                 "half-width too large for the ellipse");
    expect_error(with_element(text, "parameters", 2, "-0.25"),
                 {"blends[0].region.parameters[2] (e_1)", "out of bounds"}, "region parameter out of bounds");
    expect_error(with_element(text, "parameters", 6, "1.5"), {"blends[0].region.parameters[6] (h)", "out of bounds"},
                 "h out of bounds");
    expect_error(with_element(text, "parameters", 6, "0.5"), {"blends[0].region", "h"}, "h on an annulus");
    expect_error(with_value(text, "kind", "\"disk\"", 1), {"blends[0].region.kind", "split is cut and glue"},
                 "a disk split");
    expect_error(with_value(text, "kind", "\"torus\"", 1), {"blends[0].region.kind", "unknown region kind"},
                 "unknown region kind");
    expect_error(with_value(text, "kind", "\"hole_end\"", 2), {"blends[0].added_side", "hole_component"},
                 "hole end on an ellipsoid");
    expect_error(with_value(text, "hole", "0"), {"blends[0].hole", "only a blend of kind \"hole\""},
                 "a split in a hole");
    // The structure as a whole.
    expect_error(with_value(text, "kind", "\"disk\"", 4),
                 {"blends[4].base_component", "component 2 is still being blended in gradually by blend 1"},
                 "a blend based on a gradual part");
    expect_error(with_value(text, "added_component", "2"), {"components[1]", "added by 0 blends, expected 1"},
                 "a component added by no blend");
    expect_error(with_value(text, "added_component", "1", 1), {"components[1]", "added by 2 blends, expected 1"},
                 "a component added twice");
    expect_error(with_value(text, "base_component", "5", 4),
                 {"blends[4].added_component", "component 4 comes before its base component 5"}, "hierarchy order");
    // The hierarchy is derived: whatever it says is ignored.
    try
    {
      BS_CHECK(to_text(from_text(with_value(text, "hierarchy", "{\"anything\": [1, 2]}"))) == text,
               kernel << ": the hierarchy is not ignored");
      const std::size_t h = text.find(",\n  \"hierarchy\"");
      BS_CHECK(to_text(from_text(text.substr(0, h) + "\n}\n")) == text, kernel << ": the hierarchy is required");
    }
    catch(const std::exception& e)
    {
      BS_CHECK(false, kernel << ": changing the hierarchy: " << e.what());
    }
  }

  // Random damage: every damaged text either loads (and then survives a
  // round trip unchanged) or throws Input_error; nothing else, no crash.
  void test_fuzz(const std::string& text, int rounds)
  {
    // Where the numbers are (outside strings).
    std::vector<std::pair<std::size_t, std::size_t>> numbers;
    bool in_string = false;
    for(std::size_t i = 0; i < text.size(); ++i)
    {
      if(text[i] == '"')
        in_string = !in_string;
      if(in_string || !(text[i] == '-' || (text[i] >= '0' && text[i] <= '9')))
        continue;
      const std::size_t e = text.find_first_of(",]}\n ", i);
      numbers.emplace_back(i, e - i);
      i = e - 1;
    }
    static const char* values[] = {"-1", "0", "-0", "1", "2", "0.5", "3.5", "7", "4096", "1e15", "1e-300", "1e300",
                                   "-1e300", "5e-324", "1.0000000000000002", "0.49999999999999994", "null", "\"x\"",
                                   "[]", "{}", "[0, 0]", "true"};
    static const char bytes[] = " {}[],:\"0123456789-.eEatfnul\\x";
    int loaded = 0, refused = 0;
    for(int round = 0; round < rounds; ++round)
    {
      std::string t = text;
      const int damages = 1 + int(rng() % 3);
      for(int d = 0; d < damages; ++d)
      {
        const int how = int(rng() % 4);
        if(how <= 1 && !numbers.empty())
        {
          // Replace a number, counted from the end so that earlier damage does not shift it.
          const auto& n = numbers[rng() % numbers.size()];
          const std::size_t from_end = text.size() - n.first;
          if(from_end > t.size())
            continue;
          const std::size_t p = t.size() - from_end;
          const std::size_t e = t.find_first_of(",]}\n ", p);
          t = t.substr(0, p) + values[rng() % (sizeof(values) / sizeof(values[0]))] + t.substr(e);
        }
        else if(how == 2 && !t.empty())
          t[rng() % t.size()] = bytes[rng() % (sizeof(bytes) - 1)];
        else if(!t.empty())
        {
          const std::size_t p = rng() % t.size();
          t.erase(p, 1 + rng() % 10);
        }
      }
      try
      {
        const Shape s = from_text(t);
        ++loaded;
        const std::string w = to_text(s);
        BS_CHECK(to_text(from_text(w)) == w, kernel << ": fuzz round " << round << ": a damaged model that loads does not "
                                                    "survive a round trip");
        for(int k = 0; k < 20; ++k)
        {
          const std::size_t c = std::size_t(rng() % s.number_of_components());
          const std::size_t chart = std::size_t(rng() % s.component(c).shape().number_of_charts());
          // Inside every chart domain (disks of radius >= 1, tubes, tori).
          const typename K::Point_3 x =
              s.point(BS::Shape_point(c, BS::Chart_point(chart, uniform(-0.7, 0.7), uniform(-0.7, 0.7))));
          BS_CHECK(std::isfinite(CGAL::to_double(x.x())) && std::isfinite(CGAL::to_double(x.y())) &&
                       std::isfinite(CGAL::to_double(x.z())),
                   kernel << ": fuzz round " << round << ": a loaded model evaluates to a non-finite point");
        }
      }
      catch(const BS::Input_error&)
      {
        ++refused;
      }
      catch(const std::exception& e)
      {
        BS_CHECK(false, kernel << ": fuzz round " << round << ": " << typeid(e).name() << ": " << e.what() << "\n" << t);
      }
    }
    BS_CHECK(loaded > 0 && refused > 0, kernel << ": fuzz: " << loaded << " loaded, " << refused << " refused");
    if(std::getenv("BLENDED_SHAPE_IO_VERBOSE"))
      std::cout << kernel << ": fuzz: " << loaded << " loaded, " << refused << " refused" << std::endl;
  }

  void test_hole_errors(const std::string& text)
  {
    // The sphere + hole model: blends 0 and 1 are the ends of hole 0, component 1.
    expect_error(with_value(text, "domain", "\"two_disks\""), {"components[1].domain", "Two_disks"},
                 "two disks with an open hole");
    expect_error(with_value(text, "domain", "\"sphere\""), {"components[1].domain", "unknown hole domain"},
                 "unknown domain");
    expect_error(with_value(text, "hole", "null"), {"blends[0].hole", "names its hole"}, "hole blend without hole");
    expect_error(with_value(text, "delta", "0.7"), {"blends[0].added_side", "(0, 0.5)"}, "delta out of bounds");
    expect_error(with_value(text, "end", "1"), {"holes[0].blends[0]", "end 1"}, "swapped ends");
    expect_error(with_value(text, "end", "2"), {"blends[0].added_side.end", "out of range"}, "end 2");
    expect_error(replaced(text, "\"blends\": [0, 1]", "\"blends\": [0, 0]"), {"holes[0].blends[1]"}, "same blend twice");
    expect_error(replaced(text, "\"blends\": [0, 1]", "\"blends\": [0]"),
                 {"holes[0].blends", "expected an array of 2 blend indices"}, "one end");
    expect_error(replaced(text, "\"component\": 1", "\"component\": 0"), {"holes[0].component", "not a hole_component"},
                 "hole on the root");
    expect_error(with_value(text, "holes", "[]"), {"blends[0].hole", "hole index 0 is out of range", "0 holes"},
                 "missing hole record");
    expect_error(with_value(text, "kind", "\"disk\"", 1), {"holes[0].blends[0]", "tube domain", "annulus"},
                 "gradual end of a tube hole");
    expect_error(with_value(text, "kind", "\"part\""), {"blends[0].hole", "only a blend of kind \"hole\""},
                 "hole blend of kind part");
  }

  // A component of another kernel is not a known primitive: the writer refuses it.
  template <class Other>
  void test_unknown_primitive()
  {
    Shape s = sphere();
    s.add_part(0, 0, Region::make_parameters(0.1, 0.1, 0.2, 0.15, 0.3, 0.8, 0.), 0.05,
               BS::Superquadric_toroid<Other>(0.3, 0.3, 0.1, 2., 2., 1., 1.), "my_toroid", Eigen::Vector3d(0., 0., 1.),
               Eigen::Vector4d(1., 0., 0., 0.), 0, Region::make_parameters(3., 3., 0.5, 0.4, 0., 1., 0.), 0.1);
    bool threw = false;
    try
    {
      to_text(s);
    }
    catch(const std::invalid_argument& e)
    {
      threw = contains(e.what(), "component 1 is a 'my_toroid'") && contains(e.what(), "superquadric_toroid");
      BS_CHECK(threw, kernel << ": message: " << e.what());
    }
    BS_CHECK(threw, kernel << ": a component of another kernel is written");
    namespace fs = std::filesystem;
    const fs::path file = fs::temp_directory_path() / ("blended_shape_io_unknown_" + kernel + ".json");
    threw = false;
    try
    {
      BS::write_blended_shape(file.string(), s);
    }
    catch(const std::invalid_argument&)
    {
      threw = true;
    }
    BS_CHECK(threw && !fs::exists(file), kernel << ": the file of an unwritable model exists");
  }

  // A custom type name is kept.
  void test_type_name()
  {
    Shape s = sphere();
    s.add_part(0, 0, Region::make_parameters(0.1, 0.1, 0.2, 0.15, 0.3, 0.8, 0.), 0.05,
               Toroid(0.3, 0.3, 0.1, 2., 2., 1., 1.), "handle", Eigen::Vector3d(0., 0., 1.),
               Eigen::Vector4d(1., 0., 0., 0.), 0, Region::make_parameters(3., 3., 0.5, 0.4, 0., 1., 0.), 0.1);
    const std::string text = to_text(s);
    BS_CHECK(contains(text, "\"type_name\": \"handle\""), kernel << ": type name not written");
    check_same(s, from_text(text), kernel + ", type name");
    BS_CHECK(to_text(from_text(text)) == text, kernel << ": type name round trip");
  }

  // A region moved by set_parameters() past its chart is still saved and loaded.
  // A region may not be moved out of its chart (set_parameters() refuses,
  // the shape unchanged), and a file with such a region, or with regions that
  // meet, is refused with a message naming the blend.
  void test_moved_region()
  {
    Shape s = sphere();
    const std::size_t b = s.split(0, 0, Region::make_parameters(0.7, 0.1, 0.2, 0.15, 0.3, 0.8, 0.), 0.05);
    const Eigen::VectorXd before = s.parameters();
    Eigen::VectorXd q = before;
    q[Eigen::Index(s.blend_offset(b) + Region::E_U)] = 1.15; // the strip would leave the chart disk
    bool refused = false;
    try { s.set_parameters(q); }
    catch(const std::invalid_argument& e) { refused = std::string(e.what()).find("leaves chart") != std::string::npos; }
    BS_CHECK(refused && s.parameters() == before, kernel << ": a region moved out of its chart was accepted");
    const std::string text = to_text(s);
    const std::string e_u = "\"parameters\": [0.7,";
    BS_CHECK(text.find(e_u) != std::string::npos, kernel << ": e_u not found in " << text);
    if(text.find(e_u) == std::string::npos)
      return;
    std::string moved = text;
    moved.replace(moved.find(e_u), e_u.size(), "\"parameters\": [1.15,");
    bool rejected = false;
    try { from_text(moved); }
    catch(const BS::Input_error& e) { rejected = std::string(e.what()).find("leaves chart") != std::string::npos; }
    BS_CHECK(rejected, kernel << ": a file with a region out of its chart was not rejected with a message");
    // two splits whose regions meet
    Shape t = sphere();
    t.split(0, 0, Region::make_parameters(0.3, 0.1, 0.2, 0.15, 0.3, 0.8, 0.), 0.05);
    t.split(0, 0, Region::make_parameters(-0.3, 0.1, 0.2, 0.15, 0.3, 0.8, 0.), 0.05);
    std::string meeting = to_text(t);
    const std::string minus = "\"parameters\": [-0.3,";
    BS_CHECK(meeting.find(minus) != std::string::npos, kernel << ": e_u of the second split not found");
    if(meeting.find(minus) == std::string::npos)
      return;
    meeting.replace(meeting.find(minus), minus.size(), "\"parameters\": [0.35,");
    rejected = false;
    try { from_text(meeting); }
    catch(const BS::Input_error& e) { rejected = std::string(e.what()).find("meets the region of blend 0") != std::string::npos; }
    BS_CHECK(rejected, kernel << ": a file with meeting regions was not rejected with a message");
  }

  void run()
  {
    test_round_trips();
    test_type_name();
    test_moved_region();
  }
};

// Every check of this part.
void run_all()
{
  test_json();
#ifndef BLENDED_SHAPE_ONE_KERNEL // sanitizer builds: Epick only (see test/CMakeLists.txt)
  {
    Io_tests<CGAL::Simple_cartesian<double>> t{"Simple_cartesian"};
    t.run();
    t.test_unknown_primitive<CGAL::Exact_predicates_inexact_constructions_kernel>();
  }
#endif
  {
    Io_tests<CGAL::Exact_predicates_inexact_constructions_kernel> t{"Epick"};
    t.run();
    t.test_unknown_primitive<CGAL::Simple_cartesian<double>>();
  }
}

} // namespace blended_shape_io_checks

#endif // BLENDED_SHAPE_BLENDED_SHAPE_IO_CHECKS_H
