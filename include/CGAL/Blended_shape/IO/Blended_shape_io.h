// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_BLENDED_SHAPE_IO_BLENDED_SHAPE_IO_H
#define CGAL_BLENDED_SHAPE_IO_BLENDED_SHAPE_IO_H

#include <CGAL/Blended_shape/Blending/Blend.h>
#include <CGAL/Blended_shape/Blending/Blended_shape.h>
#include <CGAL/Blended_shape/Blending/Blending_region.h>
#include <CGAL/Blended_shape/Primitives/Component_shape.h>
#include <CGAL/Blended_shape/Primitives/Hole_component.h>
#include <CGAL/Blended_shape/IO/Input_error.h>
#include <CGAL/Blended_shape/Primitives/Superquadric_ellipsoid.h>
#include <CGAL/Blended_shape/Primitives/Superquadric_toroid.h>
#include <CGAL/Blended_shape/IO/internal/json.h>
#include <CGAL/Blended_shape/internal/write_file_atomically.h>

#include <Eigen/Core>

#include <cmath>
#include <cstddef>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <istream>
#include <memory>
#include <optional>
#include <ostream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <system_error>
#include <vector>

namespace CGAL {
namespace Blended_shapes {

/// \ingroup PkgBlendedShapeIO
/// The version of the model file format that write_blended_shape_json() writes
/// and read_blended_shape_json() reads. Version 2: placements are relative
/// to the parent component (Blended_shape::parent()); in version 1 they were
/// relative to the root.
constexpr int blended_shape_file_version = 2;

namespace internal {

namespace bs_json = internal::json;

inline const char* hole_domain_file_name(Hole_domain d) { return d == Hole_domain::Tube ? "tube" : "two_disks"; }

inline bs_json::Value json_numbers(const double* x, std::size_t n)
{
  bs_json::Value a = bs_json::Value::array();
  for(std::size_t i = 0; i < n; ++i)
    a.push_back(bs_json::Value::number(x[i]));
  return a;
}

inline bs_json::Value json_index(std::size_t i) { return bs_json::Value::number(double(i)); }

// Chart, half-width, segments, theta (only when not uniform) and parameters.
inline void region_to_json(const Ellipse_blending_region& R, bs_json::Value& o, bool with_kind)
{
  o.set("chart", json_index(R.chart()));
  if(with_kind)
    o.set("kind", bs_json::Value::string(R.kind() == Blending_region_kind::Disk ? "disk" : "annulus"));
  o.set("half_width", bs_json::Value::number(R.half_width()));
  o.set("segments", json_index(R.number_of_segments()));
  const std::vector<double>& theta = R.region().thetas();
  if(theta != Blending_region::uniform_theta(theta.size()))
    o.set("theta", json_numbers(theta.data(), theta.size()));
  o.set("parameters", json_numbers(R.parameters().data(), std::size_t(R.parameters().size())));
}

template <class GT>
bs_json::Value blended_shape_to_json(const Blended_shape<GT>& shape)
{
  typedef Blended_shape<GT> Shape;
  typedef typename Shape::Ellipsoid Ellipsoid;
  typedef typename Shape::Toroid Toroid;
  typedef typename Shape::Hole Hole;
  bs_json::Value doc = bs_json::Value::object();
  doc.set("format", bs_json::Value::string("blended_shape"));
  doc.set("version", bs_json::Value::number(blended_shape_file_version));

  bs_json::Value components = bs_json::Value::array();
  for(std::size_t c = 0; c < shape.number_of_components(); ++c)
  {
    const typename Shape::Component& k = shape.component(c);
    const Component_shape& s = k.shape();
    bs_json::Value o = bs_json::Value::object();
    std::string type;
    if(s.template primitive<Ellipsoid>())
      type = "superquadric_ellipsoid";
    else if(s.template primitive<Toroid>())
      type = "superquadric_toroid";
    else if(s.template primitive<Hole>())
      type = "hole_component";
    else
      throw std::invalid_argument("write_blended_shape_json: component " + std::to_string(c) + " is a '" +
                                  s.type_name() +
                                  "', which model files cannot hold (they know superquadric_ellipsoid, "
                                  "superquadric_toroid and hole_component)");
    o.set("type", bs_json::Value::string(type));
    if(s.type_name() != type)
      o.set("type_name", bs_json::Value::string(s.type_name()));
    if(const Ellipsoid* e = s.template primitive<Ellipsoid>())
      o.set("chart_margin", bs_json::Value::number(e->chart_margin()));
    if(const Hole* h = s.template primitive<Hole>())
      o.set("domain", bs_json::Value::string(hole_domain_file_name(h->domain())));
    bs_json::Value p = bs_json::Value::object();
    const Eigen::VectorXd q = s.parameters();
    for(std::size_t i = 0; i < s.number_of_parameters(); ++i)
      p.set(s.parameter_info(i).name, bs_json::Value::number(q[Eigen::Index(i)]));
    o.set("parameters", p);
    o.set("translation", json_numbers(k.translation().data(), 3));
    o.set("quaternion", json_numbers(k.quaternion().data(), 4));
    components.push_back(o);
  }
  doc.set("components", components);

  bs_json::Value blends = bs_json::Value::array(), hierarchy = bs_json::Value::array();
  for(std::size_t b = 0; b < shape.number_of_blends(); ++b)
  {
    const Blend& B = shape.blend(b);
    bs_json::Value o = bs_json::Value::object();
    o.set("kind", bs_json::Value::string(blend_kind_name(B.kind())));
    o.set("base_component", json_index(B.base_component()));
    o.set("added_component", json_index(B.added_component()));
    bs_json::Value region = bs_json::Value::object();
    region_to_json(B.base_region(), region, true);
    o.set("region", region);
    const Added_side& A = B.added_side();
    bs_json::Value side = bs_json::Value::object();
    if(A.kind() == Added_side::Ellipse)
    {
      side.set("kind", bs_json::Value::string("ellipse"));
      region_to_json(A.ellipse_region(), side, false);
    }
    else
    {
      side.set("kind", bs_json::Value::string("hole_end"));
      side.set("end", json_index(std::size_t(A.end())));
      side.set("delta", bs_json::Value::number(A.delta()));
      side.set("phase", bs_json::Value::number(A.phase()));
    }
    o.set("added_side", side);
    o.set("hole", B.hole() == Blend::no_hole ? bs_json::Value() : json_index(B.hole()));
    o.set("core_stretch", bs_json::Value::number(B.core_stretch()));
    blends.push_back(o);

    bs_json::Value h = bs_json::Value::object();
    h.set("blend", json_index(b));
    h.set("kind", bs_json::Value::string(blend_kind_name(B.kind())));
    h.set("base_component", json_index(B.base_component()));
    h.set("added_component", json_index(B.added_component()));
    hierarchy.push_back(h);
  }
  doc.set("blends", blends);

  bs_json::Value holes = bs_json::Value::array();
  for(const typename Shape::Hole_record& r : shape.holes())
  {
    bs_json::Value o = bs_json::Value::object();
    o.set("component", json_index(r.component));
    bs_json::Value ends = bs_json::Value::array();
    ends.push_back(json_index(r.blends[0])).push_back(json_index(r.blends[1]));
    o.set("blends", ends);
    holes.push_back(o);
  }
  doc.set("holes", holes);
  // Derived, for readers of the file: recomputed on every write, ignored on read.
  doc.set("hierarchy", hierarchy);
  return doc;
}

template <class GT>
std::string blended_shape_to_json_text(const Blended_shape<GT>& shape)
{
  const bs_json::Value doc = blended_shape_to_json(shape);
  std::ostringstream s;
  bs_json::write(s, doc);
  return s.str();
}

// Reads and validates a model; every error is an Input_error naming the
// source, the JSON path of the bad field and what was expected.
template <class GT>
class Blended_shape_reader
{
public:
  typedef Blended_shape<GT> Shape;
  typedef typename Shape::Ellipsoid Ellipsoid;
  typedef typename Shape::Toroid Toroid;
  typedef typename Shape::Hole Hole;
  typedef bs_json::Value Value;

  explicit Blended_shape_reader(std::string where) : m_where(std::move(where)) {}

  Shape read(const std::string& text)
  {
    if(text.find_first_not_of(" \t\r\n") == std::string::npos)
      throw Input_error(Input_error::Malformed_content,
                        m_where + ": the input is empty; expected a blended shape model (a JSON object with "
                                  "\"format\": \"blended_shape\")");
    Value doc;
    try
    {
      doc = bs_json::parse(text);
    }
    catch(const bs_json::Parse_error& e)
    {
      throw Input_error(Input_error::Malformed_content, m_where + ": not valid JSON: " + e.what() +
                                                            " (truncated or corrupt file?)");
    }
    return read(doc);
  }

private:
  [[noreturn]] void fail(const std::string& path, const std::string& what,
                         Input_error::Code code = Input_error::Malformed_content) const
  {
    throw Input_error(code, m_where + ": " + (path.empty() ? std::string("the document") : path) + ": " + what);
  }

  static std::string member_path(const std::string& path, const std::string& key)
  {
    return path.empty() ? key : path + "." + key;
  }
  static std::string element_path(const std::string& path, std::size_t i)
  {
    return path + "[" + std::to_string(i) + "]";
  }

  static std::string found(const Value& v)
  {
    std::string s = std::string("found ") + bs_json::type_description(v.type());
    if(v.type() == bs_json::Type::String)
    {
      std::string t;
      for(char ch : v.as_string())
        t += (static_cast<unsigned char>(ch) < 0x20 || ch == 0x7f) ? '?' : ch;
      s += " \"" + (t.size() > 40 ? t.substr(0, 40) + "..." : t) + "\"";
    }
    else if(v.type() == bs_json::Type::Number)
      s += " " + bs_json::format_number(v.as_number());
    return s;
  }

  static std::string list(std::initializer_list<const char*> names)
  {
    std::string s;
    for(const char* n : names)
      s += (s.empty() ? "" : ", ") + std::string(n);
    return s;
  }

  void expect_object(const Value& v, const std::string& path, std::initializer_list<const char*> allowed) const
  {
    if(v.type() != bs_json::Type::Object)
      fail(path, "expected an object, " + found(v));
    for(std::size_t i = 0; i < v.size(); ++i)
    {
      bool known = false;
      for(const char* a : allowed)
        known = known || v.key(i) == a;
      if(!known)
        fail(path, "unknown field \"" + v.key(i) + "\"; the fields here are " + list(allowed));
    }
  }

  const Value& field(const Value& o, const std::string& path, const char* key) const
  {
    const Value* v = o.find(key);
    if(!v)
      fail(path, std::string("missing field \"") + key + "\"");
    return *v;
  }

  const Value& array(const Value& v, const std::string& path) const
  {
    if(v.type() != bs_json::Type::Array)
      fail(path, "expected an array, " + found(v));
    return v;
  }

  const Value& array(const Value& v, const std::string& path, std::size_t n, const char* of) const
  {
    if(v.type() != bs_json::Type::Array)
      fail(path, "expected an array of " + std::to_string(n) + " " + of + ", " + found(v));
    if(v.size() != n)
      fail(path, "expected an array of " + std::to_string(n) + " " + of + ", found " + std::to_string(v.size()) +
                   (v.size() == 1 ? " element" : " elements"));
    return v;
  }

  double number(const Value& v, const std::string& path) const
  {
    if(v.type() != bs_json::Type::Number)
      fail(path, "expected a number, " + found(v));
    return v.as_number(); // always finite: the parser rejects NaN, infinities and overflows
  }

  const std::string& string(const Value& v, const std::string& path) const
  {
    if(v.type() != bs_json::Type::String)
      fail(path, "expected a string, " + found(v));
    return v.as_string();
  }

  // An integer in [0, limit): `what` says what it counts ("component", ...),
  // `owner` who has `limit` of them (empty: "there are").
  std::size_t index(const Value& v, const std::string& path, std::size_t limit, const std::string& what,
                    const std::string& owner = std::string()) const
  {
    if(v.type() != bs_json::Type::Number)
      fail(path, "expected a " + what + " index (a non-negative integer), " + found(v));
    const double x = v.as_number();
    if(!(x >= 0.) || x != std::floor(x))
      fail(path, "expected a " + what + " index (a non-negative integer), " + found(v));
    if(!(x < double(limit)))
      fail(path, what + " index " + bs_json::format_number(x) + " is out of range: " +
                   (owner.empty() ? (limit == 1 ? "there is " : "there are ") : owner + " has ") +
                   std::to_string(limit) + " " + what + (limit == 1 ? "" : "s") +
                   (limit == 0 ? "" : " (0 to " + std::to_string(limit - 1) + ")"));
    return std::size_t(x);
  }

  // A parameter vector: an object with exactly the parameters' names, or an
  // array of them in order; each value inside its bounds.
  template <class Info>
  Eigen::VectorXd parameters(const Value& v, const std::string& path, std::size_t n, Info info) const
  {
    Eigen::VectorXd q = Eigen::VectorXd::Zero(Eigen::Index(n));
    std::vector<std::string> paths(n);
    if(v.type() == bs_json::Type::Array)
    {
      array(v, path, n, "numbers");
      for(std::size_t i = 0; i < n; ++i)
      {
        paths[i] = element_path(path, i) + " (" + info(i).name + ")";
        q[Eigen::Index(i)] = number(v[i], paths[i]);
      }
    }
    else if(v.type() == bs_json::Type::Object)
    {
      std::string names;
      for(std::size_t i = 0; i < n; ++i)
        names += (i ? ", " : "") + std::string(info(i).name);
      for(std::size_t i = 0; i < v.size(); ++i)
      {
        bool known = false;
        for(std::size_t j = 0; j < n; ++j)
          known = known || v.key(i) == info(j).name;
        if(!known)
          fail(path, "unknown parameter \"" + v.key(i) + "\"; the parameters are " + names);
      }
      for(std::size_t i = 0; i < n; ++i)
      {
        paths[i] = member_path(path, info(i).name);
        q[Eigen::Index(i)] = number(field(v, path, info(i).name), paths[i]);
      }
    }
    else
      fail(path, "expected the parameters as an object or an array of " + std::to_string(n) + " numbers, " +
                   found(v));
    for(std::size_t i = 0; i < n; ++i)
    {
      const Parameter_info& p = info(i);
      const double x = q[Eigen::Index(i)];
      if(!(x >= p.lower_bound && x <= p.upper_bound))
        fail(paths[i], std::string(p.name) + " = " + bs_json::format_number(x) + " is out of bounds: expected a value in [" +
                         bound_text(p.lower_bound) + ", " + bound_text(p.upper_bound) + "]");
    }
    return q;
  }

  static std::string bound_text(double x)
  {
    if(std::isinf(x))
      return x < 0. ? "-inf" : "inf";
    return bs_json::format_number(x);
  }

  template <class Primitive>
  Eigen::VectorXd primitive_parameters(const Value& o, const std::string& path) const
  {
    return parameters(field(o, path, "parameters"), member_path(path, "parameters"),
                      std::size_t(Primitive::number_of_parameters),
                      [](std::size_t i) -> const Parameter_info& { return Primitive::parameter_info(int(i)); });
  }

  std::unique_ptr<Component_shape> read_component(const Value& o, const std::string& path, Eigen::Vector3d& t,
                                                  Eigen::Vector4d& q, bool root) const
  {
    if(o.type() != bs_json::Type::Object)
      fail(path, "expected an object (a component), " + found(o));
    const std::string type = string(field(o, path, "type"), member_path(path, "type"));
    std::string type_name = type;
    if(const Value* n = o.find("type_name"))
      type_name = string(*n, member_path(path, "type_name"));
    std::unique_ptr<Component_shape> s;
    try
    {
      if(type == "superquadric_ellipsoid")
      {
        expect_object(o, path, {"type", "type_name", "chart_margin", "parameters", "translation", "quaternion"});
        const Eigen::VectorXd p = primitive_parameters<Ellipsoid>(o, path);
        const std::string mpath = member_path(path, "chart_margin");
        const double m = number(field(o, path, "chart_margin"), mpath);
        if(!(m > 0. && m < 1.))
          fail(mpath, "chart margin " + bs_json::format_number(m) + " is out of bounds: expected a value in (0, 1)");
        s = make_component_shape(Ellipsoid(p[0], p[1], p[2], p[3], p[4], m), type_name);
      }
      else if(type == "superquadric_toroid")
      {
        expect_object(o, path, {"type", "type_name", "parameters", "translation", "quaternion"});
        const Eigen::VectorXd p = primitive_parameters<Toroid>(o, path);
        s = make_component_shape(Toroid(p[0], p[1], p[2], p[3], p[4], p[5], p[6]), type_name);
      }
      else if(type == "hole_component")
      {
        expect_object(o, path, {"type", "type_name", "domain", "parameters", "translation", "quaternion"});
        const Eigen::VectorXd p = primitive_parameters<Hole>(o, path);
        const std::string dpath = member_path(path, "domain");
        const std::string& d = string(field(o, path, "domain"), dpath);
        if(d != "two_disks" && d != "tube")
          fail(dpath, "unknown hole domain \"" + d + "\"; expected \"two_disks\" or \"tube\"");
        const Hole_domain domain = (d == "tube") ? Hole_domain::Tube : Hole_domain::Two_disks;
        try
        {
          s = make_component_shape(Hole(p[0], p[1], p[2], p[3], p[4], p[5], p[6], domain), type_name);
        }
        catch(const std::logic_error& e)
        {
          if(dynamic_cast<const std::invalid_argument*>(&e))
            throw;
          fail(dpath, e.what());
        }
      }
      else
        fail(member_path(path, "type"), "unknown component type \"" + type +
                                            "\"; the known types are superquadric_ellipsoid, superquadric_toroid "
                                            "and hole_component");
    }
    catch(const std::invalid_argument& e)
    {
      fail(path, e.what());
    }
    const std::string tpath = member_path(path, "translation"), qpath = member_path(path, "quaternion");
    t = Eigen::Vector3d::Zero();
    q = Eigen::Vector4d(1., 0., 0., 0.);
    const Value* tv = o.find("translation");
    const Value* qv = o.find("quaternion");
    if(!root && !tv)
      fail(path, "missing field \"translation\"");
    if(!root && !qv)
      fail(path, "missing field \"quaternion\"");
    if(tv)
    {
      array(*tv, tpath, 3, "numbers");
      for(std::size_t i = 0; i < 3; ++i)
        t[Eigen::Index(i)] = number((*tv)[i], element_path(tpath, i));
    }
    if(qv)
    {
      array(*qv, qpath, 4, "numbers");
      for(std::size_t i = 0; i < 4; ++i)
        q[Eigen::Index(i)] = number((*qv)[i], element_path(qpath, i));
      if(!(q.norm() > 1e-12))
        fail(qpath, "expected a nonzero quaternion (w, x, y, z)");
    }
    if(root && (t != Eigen::Vector3d::Zero() || q != Eigen::Vector4d(1., 0., 0., 0.)))
      fail(path, "the root component (component 0) is not placed: expected the translation [0, 0, 0] and the "
                 "quaternion [1, 0, 0, 0], or none");
    return s;
  }

  Ellipse_blending_region read_region(const Value& o, const std::string& path, bool base,
                                      std::size_t number_of_charts, const std::string& component) const
  {
    if(base)
      expect_object(o, path, {"chart", "kind", "half_width", "segments", "theta", "parameters"});
    else
      expect_object(o, path, {"kind", "chart", "half_width", "segments", "theta", "parameters"});
    const std::size_t chart =
      index(field(o, path, "chart"), member_path(path, "chart"), number_of_charts, "chart", component);
    Blending_region_kind kind = Blending_region_kind::Annulus;
    if(base)
    {
      const std::string kpath = member_path(path, "kind");
      const std::string& k = string(field(o, path, "kind"), kpath);
      if(k != "disk" && k != "annulus")
        fail(kpath, "unknown region kind \"" + k + "\"; expected \"disk\" or \"annulus\"");
      kind = (k == "disk") ? Blending_region_kind::Disk : Blending_region_kind::Annulus;
    }
    const std::string wpath = member_path(path, "half_width");
    const double half_width = number(field(o, path, "half_width"), wpath);
    if(!(half_width > 0.))
      fail(wpath, "the strip half-width " + bs_json::format_number(half_width) + " must be positive");
    const std::string spath = member_path(path, "segments");
    const Value& sv = field(o, path, "segments");
    const double max_segments = 4096.;
    const double sd = number(sv, spath);
    if(!(sd >= 4. && sd <= max_segments) || sd != std::floor(sd))
      fail(spath, "expected a number of segments, an integer from 4 to 4096, " + found(sv));
    const std::size_t segments = std::size_t(sd);
    std::vector<double> theta;
    if(const Value* tv = o.find("theta"))
    {
      const std::string tpath = member_path(path, "theta");
      array(*tv, tpath, segments, "numbers (one angle per segment)");
      for(std::size_t i = 0; i < segments; ++i)
        theta.push_back(number((*tv)[i], element_path(tpath, i)));
    }
    const Eigen::VectorXd q =
      parameters(field(o, path, "parameters"), member_path(path, "parameters"),
                 std::size_t(Ellipse_blending_region::number_of_parameters),
                 [](std::size_t i) -> const Parameter_info& { return Ellipse_blending_region::parameter_info(int(i)); });
    try
    {
      Ellipse_blending_region r(Ellipse_blending_region::Parameter_vector(q), half_width, segments, kind,
                                base ? Retained_side::Outside : Retained_side::Inside, theta);
      r.set_chart(chart);
      return r;
    }
    catch(const std::invalid_argument& e)
    {
      fail(path, e.what());
    }
  }

  Shape read(const Value& doc)
  {
    if(doc.type() != bs_json::Type::Object)
      fail("", "expected a JSON object with \"format\": \"blended_shape\", " + found(doc) +
                 "; this is not a blended shape model",
           Input_error::Unsupported_format);
    const Value* format = doc.find("format");
    if(!format)
      fail("", "missing field \"format\"; this is not a blended shape model (expected \"format\": \"blended_shape\")",
           Input_error::Unsupported_format);
    if(format->type() != bs_json::Type::String || format->as_string() != "blended_shape")
      fail("format", "expected \"blended_shape\", " + found(*format) + "; this is not a blended shape model",
           Input_error::Unsupported_format);
    const Value& version = field(doc, "", "version");
    if(version.type() != bs_json::Type::Number || version.as_number() != double(blended_shape_file_version))
      fail("version", "expected " + std::to_string(blended_shape_file_version) + ", " + found(version) +
                        "; this library reads version " + std::to_string(blended_shape_file_version) +
                        " of the blended shape format",
           Input_error::Unsupported_format);
    expect_object(doc, "", {"format", "version", "components", "blends", "holes", "hierarchy"});

    // Components.
    const Value& components = array(field(doc, "", "components"), "components");
    if(components.size() == 0)
      fail("components", "expected at least one component (the root)");
    // Far beyond any fitted model; bounds the loading time (Blended_shape
    // recomputes its layout, in quadratic time, on every append).
    const std::size_t max_count = 1000;
    if(components.size() > max_count)
      fail("components", std::to_string(components.size()) + " components; at most " + std::to_string(max_count) +
                           " are supported");
    std::vector<std::unique_ptr<Component_shape>> shapes;
    std::vector<Eigen::Vector3d> translations;
    std::vector<Eigen::Vector4d> quaternions;
    for(std::size_t c = 0; c < components.size(); ++c)
    {
      Eigen::Vector3d t;
      Eigen::Vector4d q;
      shapes.push_back(read_component(components[c], element_path("components", c), t, q, c == 0));
      translations.push_back(t);
      quaternions.push_back(q);
    }
    const std::size_t nc = shapes.size();
    std::vector<std::string> type_of(nc);
    std::vector<bool> is_hole(nc);
    for(std::size_t c = 0; c < nc; ++c)
    {
      type_of[c] = components[c].find("type")->as_string();
      is_hole[c] = shapes[c]->template primitive<Hole>() != nullptr;
    }
    Shape shape(std::move(shapes[0]));
    for(std::size_t c = 1; c < nc; ++c)
    {
      try
      {
        shape.append_component(std::move(shapes[c]), translations[c], quaternions[c]);
      }
      catch(const std::invalid_argument& e)
      {
        fail(element_path("components", c), e.what());
      }
    }

    // Blends (their hole indices are checked against the holes below).
    const Value& blends = array(field(doc, "", "blends"), "blends");
    const Value& holes = array(field(doc, "", "holes"), "holes");
    const std::size_t nb = blends.size(), nh = holes.size();
    if(nb > 2 * max_count)
      fail("blends", std::to_string(nb) + " blends; at most " + std::to_string(2 * max_count) + " are supported");
    for(std::size_t b = 0; b < nb; ++b)
    {
      const std::string path = element_path("blends", b);
      const Value& o = blends[b];
      expect_object(o, path, {"kind", "base_component", "added_component", "region", "added_side", "hole", "core_stretch"});
      const std::string kpath = member_path(path, "kind");
      const std::string& ks = string(field(o, path, "kind"), kpath);
      Blend_kind kind = Blend_kind::Split;
      if(ks == "split")
        kind = Blend_kind::Split;
      else if(ks == "part")
        kind = Blend_kind::Part;
      else if(ks == "hole")
        kind = Blend_kind::Hole;
      else
        fail(kpath, "unknown blend kind \"" + ks + "\"; expected \"split\", \"part\" or \"hole\"");
      const std::size_t base =
        index(field(o, path, "base_component"), member_path(path, "base_component"), nc, "component");
      const std::string apath = member_path(path, "added_component");
      const std::size_t added = index(field(o, path, "added_component"), apath, nc, "component");
      if(added == 0)
        fail(apath, "component 0 is the root: no blend adds it");
      if(added == base)
        fail(apath, "a blend joins two different components, found " + std::to_string(added) + " twice");
      if(!(base < added))
        fail(apath, "component " + std::to_string(added) + " comes before its base component " +
                      std::to_string(base) + "; a blend adds a component to the shape built before it");
      const Component_shape& bs = shape.component(base).shape();
      const Component_shape& as = shape.component(added).shape();
      const Ellipse_blending_region region =
        read_region(field(o, path, "region"), member_path(path, "region"), true, bs.number_of_charts(),
                    "component " + std::to_string(base));
      if(kind == Blend_kind::Split && region.kind() != Blending_region_kind::Annulus)
        fail(member_path(member_path(path, "region"), "kind"),
             "a split is cut and glue: expected an \"annulus\" region, found \"disk\"");

      const std::string spath = member_path(path, "added_side");
      const Value& so = field(o, path, "added_side");
      if(so.type() != bs_json::Type::Object)
        fail(spath, "expected an object, " + found(so));
      const std::string skpath = member_path(spath, "kind");
      const std::string& sk = string(field(so, spath, "kind"), skpath);
      std::optional<Added_side> side;
      if(sk == "ellipse")
        side = Added_side::ellipse(
          read_region(so, spath, false, as.number_of_charts(), "component " + std::to_string(added)));
      else if(sk == "hole_end")
      {
        if(!is_hole[added])
          fail(spath, "a hole end needs a hole_component as the added component; component " +
                        std::to_string(added) + " is a " + type_of[added]);
        expect_object(so, spath, {"kind", "end", "delta", "phase"});
        const std::size_t end = index(field(so, spath, "end"), member_path(spath, "end"), 2, "hole end");
        const double delta = number(field(so, spath, "delta"), member_path(spath, "delta"));
        const double phase = number(field(so, spath, "phase"), member_path(spath, "phase"));
        try
        {
          side = Added_side::hole_end(int(end), delta, phase);
        }
        catch(const std::invalid_argument& e)
        {
          fail(spath, e.what());
        }
      }
      else
        fail(skpath, "unknown added side kind \"" + sk + "\"; expected \"ellipse\" or \"hole_end\"");

      const std::string hpath = member_path(path, "hole");
      const Value& hv = field(o, path, "hole");
      const std::size_t hole = hv.is_null() ? Blend::no_hole : index(hv, hpath, nh, "hole");
      if((kind == Blend_kind::Hole) != (hole != Blend::no_hole))
        fail(hpath, kind == Blend_kind::Hole ? "a blend of kind \"hole\" names its hole, found null"
                                             : "only a blend of kind \"hole\" belongs to a hole; expected null");
      if((kind == Blend_kind::Hole) != (side->kind() == Added_side::Hole_end))
        fail(skpath, kind == Blend_kind::Hole ? "a blend of kind \"hole\" has a \"hole_end\" added side"
                                              : "only a blend of kind \"hole\" has a \"hole_end\" added side");
      try
      {
        // Optional (default: Blend::default_core_stretch()), written by every writer.
        double stretch = 0.;
        if(const Value* sv = o.find("core_stretch"))
        {
          const std::string stpath = member_path(path, "core_stretch");
          stretch = number(*sv, stpath);
          if(!(stretch > 0.))
            fail(stpath, "expected a positive number");
        }
        shape.append_blend(Blend(kind, base, region, added, *side, hole, stretch), false); // regions: below
      }
      catch(const std::invalid_argument& e)
      {
        fail(path, e.what());
      }
    }

    // Holes.
    std::vector<std::size_t> hole_of_component(nc, Blend::no_hole);
    for(std::size_t h = 0; h < nh; ++h)
    {
      const std::string path = element_path("holes", h);
      const Value& o = holes[h];
      expect_object(o, path, {"component", "blends"});
      const std::string cpath = member_path(path, "component");
      const std::size_t c = index(field(o, path, "component"), cpath, nc, "component");
      if(!is_hole[c])
        fail(cpath, "component " + std::to_string(c) + " is a " + type_of[c] + ", not a hole_component");
      if(hole_of_component[c] != Blend::no_hole)
        fail(cpath, "component " + std::to_string(c) + " is already the component of hole " +
                      std::to_string(hole_of_component[c]));
      hole_of_component[c] = h;
      const std::string bpath = member_path(path, "blends");
      const Value& ends = array(field(o, path, "blends"), bpath, 2, "blend indices (ends 0 and 1)");
      typename Shape::Hole_record r;
      r.component = c;
      for(std::size_t e = 0; e < 2; ++e)
      {
        const std::string epath = element_path(bpath, e);
        const std::size_t b = index(ends[e], epath, nb, "blend");
        const Blend& B = shape.blend(b);
        if(B.hole() != h)
          fail(epath, "blend " + std::to_string(b) + " is not an end of hole " + std::to_string(h) +
                        " (its \"hole\" is " + (B.hole() == Blend::no_hole ? "null" : std::to_string(B.hole())) + ")");
        if(B.added_component() != c)
          fail(epath, "blend " + std::to_string(b) + " adds component " + std::to_string(B.added_component()) +
                        ", not the hole's component " + std::to_string(c));
        if(B.added_side().end() != int(e))
          fail(epath, "blend " + std::to_string(b) + " is glued to end " + std::to_string(B.added_side().end()) +
                        " of the hole, expected end " + std::to_string(e));
        r.blends[e] = b;
      }
      const bool tube = shape.component(c).shape().template primitive<Hole>()->domain() == Hole_domain::Tube;
      for(std::size_t e = 0; e < 2; ++e)
        if(shape.blend(r.blends[e]).is_gradual() == tube)
          fail(element_path(bpath, e),
               tube ? "the hole is in its tube domain, so its blends are final: expected an \"annulus\" region"
                    : "the hole is in its two_disks domain, so its blends are gradual: expected a \"disk\" region");
      try
      {
        shape.append_hole(r);
      }
      catch(const std::invalid_argument& e)
      {
        fail(path, e.what());
      }
    }

    // The structure as a whole.
    std::vector<std::size_t> added_by(nc, 0), gradual_blend(nc, Blend::no_hole);
    for(std::size_t b = 0; b < nb; ++b)
    {
      const Blend& B = shape.blend(b);
      ++added_by[B.added_component()];
      if(B.is_gradual() && gradual_blend[B.added_component()] == Blend::no_hole)
        gradual_blend[B.added_component()] = b;
    }
    for(std::size_t b = 0; b < nb; ++b)
    {
      const std::size_t c = shape.blend(b).base_component(), a = gradual_blend[c];
      if(a != Blend::no_hole)
        fail(member_path(element_path("blends", b), "base_component"),
             "component " + std::to_string(c) + " is still being blended in gradually by blend " + std::to_string(a) +
               " (a \"disk\" region); a blend can be based on it only once that blend is final");
    }
    for(std::size_t c = 1; c < nc; ++c)
    {
      const std::size_t expected = (hole_of_component[c] != Blend::no_hole) ? 2 : 1;
      if(added_by[c] != expected)
        fail(element_path("components", c),
             "the component is added by " + std::to_string(added_by[c]) + " blends, expected " +
               std::to_string(expected) +
               " (every component but the root is added by one blend, a hole's component by two, one per end)");
    }
    // The regions, once the structure is known to be sound: inside their
    // charts, disjoint, and on the surface (what Blended_shape maintains).
    for(std::size_t b = 0; b < nb; ++b)
    {
      try
      {
        shape.check_blend_regions(b);
      }
      catch(const std::invalid_argument& e)
      {
        fail(element_path("blends", b), e.what());
      }
    }
    return shape;
  }

  std::string m_where;
};

// The whole of `in`, at most `limit` bytes.
inline std::string read_all(std::istream& in, std::size_t limit, const std::string& where)
{
  std::string text;
  char buf[1 << 16];
  while(in)
  {
    in.read(buf, sizeof(buf));
    const std::streamsize n = in.gcount();
    if(n <= 0)
      break;
    if(text.size() + std::size_t(n) > limit)
      throw Input_error(Input_error::Malformed_content, where + ": the input is larger than " +
                                                          std::to_string(limit >> 20) +
                                                          " MiB; this is not a blended shape model");
    text.append(buf, std::size_t(n));
  }
  if(in.bad())
    throw Input_error(Input_error::Unreadable_file, where + ": reading failed (I/O error)");
  return text;
}

} // namespace internal

/*!
\ingroup PkgBlendedShapeIO

Writes `shape` to `out` as a JSON model file: its components (type,
parameters by name, placement, `chart_margin` of ellipsoids, `domain` of
hole components), its blends (kind, components, base region, added side,
hole), its holes, and, for readers, the blending hierarchy (derived, not read
back). Numbers are written in the shortest form that reads back to the same
`double`, so read_blended_shape_json() rebuilds a bit-identical model. The
text is built before anything is written.

\throws std::invalid_argument if a component is not a Superquadric_ellipsoid,
        Superquadric_toroid or Hole_component (of the same kernel)
\throws std::runtime_error if writing to `out` fails
*/
template <class GeomTraits>
void write_blended_shape_json(std::ostream& out, const Blended_shape<GeomTraits>& shape)
{
  const std::string text = internal::blended_shape_to_json_text(shape);
  out << text;
  out.flush();
  if(!out)
    throw std::runtime_error("write_blended_shape_json: writing the model to the stream failed");
}

/*!
\ingroup PkgBlendedShapeIO

Reads a model written by write_blended_shape_json() from `in` (all of it, at
most 64 MiB, at most 1000 components and 2000 blends). Everything is checked: the JSON syntax, the format name and
version, field names and types, indices, parameter bounds, the regions, and
the structure (blends, holes, hierarchy order). The `"hierarchy"` field is
ignored: it is derived from the blends.

\tparam GeomTraits the kernel of the shape, as for Blended_shape
\throws Input_error (`Malformed_content`, or `Unsupported_format` for a wrong
        `"format"` or `"version"`) whose message names the JSON path of the bad
        field (e.g. `blends[2].region.parameters[2] (e_1)`) and what was expected,
        or the line and column of a syntax error
*/
template <class GeomTraits>
Blended_shape<GeomTraits> read_blended_shape_json(std::istream& in)
{
  const std::string where = "read_blended_shape_json";
  const std::string text = internal::read_all(in, internal::json::Parse_limits().max_size, where);
  return internal::Blended_shape_reader<GeomTraits>(where).read(text);
}

/*!
\ingroup PkgBlendedShapeIO

Writes `shape` to the file `path` (see write_blended_shape_json()) through a
temporary file renamed at the end: a failure leaves no half-written file,
and an existing file is replaced only by a complete model.

\throws std::invalid_argument as write_blended_shape_json(), or on an empty path
\throws std::runtime_error if the file cannot be created, written or renamed
*/
template <class GeomTraits>
void write_blended_shape(const std::string& path, const Blended_shape<GeomTraits>& shape)
{
  const std::string text = internal::blended_shape_to_json_text(shape);
  internal::write_file_atomically(path, [&](std::ostream& out) { out << text; });
}

/*!
\ingroup PkgBlendedShapeIO

Reads the model file `path` (see read_blended_shape_json()).

\tparam GeomTraits the kernel of the shape, as for Blended_shape
\throws Input_error: `File_not_found`, `Unreadable_file` (a directory, no
        permission, an I/O error), or as read_blended_shape_json(); the
        message names the file
*/
template <class GeomTraits>
Blended_shape<GeomTraits> read_blended_shape(const std::string& path)
{
  const std::string where = "read_blended_shape: '" + path + "'";
  if(path.empty())
    throw Input_error(Input_error::File_not_found,
                      "read_blended_shape: empty file name; give the path of a model file (.json)");
  std::error_code ec;
  const std::filesystem::file_status st = std::filesystem::status(path, ec);
  if(st.type() == std::filesystem::file_type::not_found)
    throw Input_error(Input_error::File_not_found, where + ": no such file; check the path");
  if(st.type() == std::filesystem::file_type::directory)
    throw Input_error(Input_error::Unreadable_file, where + " is a directory, not a model file");
  std::ifstream in(path, std::ios::in | std::ios::binary);
  if(!in)
    throw Input_error(Input_error::Unreadable_file, where + ": cannot open the file for reading; check its permissions");
  const std::string text = internal::read_all(in, internal::json::Parse_limits().max_size, where);
  return internal::Blended_shape_reader<GeomTraits>(where).read(text);
}

} // namespace Blended_shapes
} // namespace CGAL

#endif // CGAL_BLENDED_SHAPE_IO_BLENDED_SHAPE_IO_H
