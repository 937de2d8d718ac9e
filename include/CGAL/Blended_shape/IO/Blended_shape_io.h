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
#include <CGAL/Blended_shape/IO/internal/json_text.h>
#include <CGAL/Blended_shape/internal/write_file_atomically.h>

#include <Eigen/Core>

#include <algorithm>
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

inline const char* hole_domain_file_name(Hole_domain d) { return d == Hole_domain::Tube ? "tube" : "two_disks"; }

inline Json json_numbers(const double* x, std::size_t n)
{
  Json a = Json::array();
  for(std::size_t i = 0; i < n; ++i)
    a.push_back(x[i]);
  return a;
}

inline Json json_index(std::size_t i) { return Json(double(i)); }

// Chart, half-width, segments, theta (only when not uniform) and parameters.
inline void region_to_json(const Ellipse_blending_region& R, Json& o, bool with_kind)
{
  o["chart"] = json_index(R.chart());
  if(with_kind)
    o["kind"] = R.kind() == Blending_region_kind::Disk ? "disk" : "annulus";
  o["half_width"] = R.half_width();
  o["segments"] = json_index(R.number_of_segments());
  const std::vector<double>& theta = R.region().thetas();
  if(theta != Blending_region::uniform_theta(theta.size()))
    o["theta"] = json_numbers(theta.data(), theta.size());
  o["parameters"] = json_numbers(R.parameters().data(), std::size_t(R.parameters().size()));
}

// The "type" of component `c` in the file.
template <class GT>
std::string component_file_type(const Component_shape& s, std::size_t c)
{
  if(s.template primitive<typename Blended_shape<GT>::Ellipsoid>())
    return "superquadric_ellipsoid";
  if(s.template primitive<typename Blended_shape<GT>::Toroid>())
    return "superquadric_toroid";
  if(s.template primitive<typename Blended_shape<GT>::Hole>())
    return "hole_component";
  throw std::invalid_argument("write_blended_shape_json: component " + std::to_string(c) + " is a '" +
                              s.type_name() +
                              "', which model files cannot hold (they know superquadric_ellipsoid, "
                              "superquadric_toroid and hole_component)");
}

template <class GT>
Json component_to_json(const Blended_shape<GT>& shape, std::size_t c)
{
  const auto& k = shape.component(c);
  const Component_shape& s = k.shape();
  const std::string type = component_file_type<GT>(s, c);
  Json o = Json::object();
  o["type"] = type;
  if(s.type_name() != type)
    o["type_name"] = s.type_name();
  if(const auto* e = s.template primitive<typename Blended_shape<GT>::Ellipsoid>())
    o["chart_margin"] = e->chart_margin();
  if(const auto* h = s.template primitive<typename Blended_shape<GT>::Hole>())
    o["domain"] = hole_domain_file_name(h->domain());
  Json p = Json::object();
  const Eigen::VectorXd q = s.parameters();
  for(std::size_t i = 0; i < s.number_of_parameters(); ++i)
    p[s.parameter_info(i).name] = q[Eigen::Index(i)];
  o["parameters"] = p;
  o["translation"] = json_numbers(k.translation().data(), 3);
  o["quaternion"] = json_numbers(k.quaternion().data(), 4);
  return o;
}

inline Json added_side_to_json(const Added_side& A)
{
  Json side = Json::object();
  if(A.kind() == Added_side::Ellipse)
  {
    side["kind"] = "ellipse";
    region_to_json(A.ellipse_region(), side, false);
    return side;
  }
  side["kind"] = "hole_end";
  side["end"] = json_index(std::size_t(A.end()));
  side["delta"] = A.delta();
  side["phase"] = A.phase();
  return side;
}

inline Json blend_to_json(const Blend& B)
{
  Json o = Json::object();
  o["kind"] = blend_kind_name(B.kind());
  o["base_component"] = json_index(B.base_component());
  o["added_component"] = json_index(B.added_component());
  Json region = Json::object();
  region_to_json(B.base_region(), region, true);
  o["region"] = region;
  o["added_side"] = added_side_to_json(B.added_side());
  o["hole"] = B.hole() == Blend::no_hole ? Json() : json_index(B.hole());
  o["core_stretch"] = B.core_stretch();
  return o;
}

// Derived, for readers of the file: recomputed on every write, ignored on read.
inline Json hierarchy_entry_to_json(const Blend& B, std::size_t b)
{
  Json h = Json::object();
  h["blend"] = json_index(b);
  h["kind"] = blend_kind_name(B.kind());
  h["base_component"] = json_index(B.base_component());
  h["added_component"] = json_index(B.added_component());
  return h;
}

template <class GT>
Json blended_shape_to_json(const Blended_shape<GT>& shape)
{
  Json doc = Json::object();
  doc["format"] = "blended_shape";
  doc["version"] = double(blended_shape_file_version);
  Json components = Json::array(), blends = Json::array(), holes = Json::array(), hierarchy = Json::array();
  for(std::size_t c = 0; c < shape.number_of_components(); ++c)
    components.push_back(component_to_json(shape, c));
  for(std::size_t b = 0; b < shape.number_of_blends(); ++b)
  {
    blends.push_back(blend_to_json(shape.blend(b)));
    hierarchy.push_back(hierarchy_entry_to_json(shape.blend(b), b));
  }
  for(const auto& r : shape.holes())
    holes.push_back(Json{{"component", json_index(r.component)},
                         {"blends", Json::array({json_index(r.blends[0]), json_index(r.blends[1])})}});
  doc["components"] = components;
  doc["blends"] = blends;
  doc["holes"] = holes;
  doc["hierarchy"] = hierarchy;
  return doc;
}

template <class GT>
std::string blended_shape_to_json_text(const Blended_shape<GT>& shape)
{
  const Json doc = blended_shape_to_json(shape);
  std::ostringstream s;
  write_json(s, doc);
  return s.str();
}

// The checks of single JSON values that the reader below makes: each returns
// the value or throws an Input_error naming the source, the JSON path of the
// value and what was expected.
class Json_value_checker
{
public:
  explicit Json_value_checker(std::string where) : m_where(std::move(where)) {}

  const std::string& where() const { return m_where; }

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

  // "found a string \"abc\"", "found a number 3", "found null", ...
  static std::string found(const Json& v)
  {
    std::string s = std::string("found ") + json_type_description(v);
    if(v.is_string())
    {
      std::string t;
      for(char ch : v.get_ref<const std::string&>())
        t += (static_cast<unsigned char>(ch) < 0x20 || ch == 0x7f) ? '?' : ch;
      s += " \"" + (t.size() > 40 ? t.substr(0, 40) + "..." : t) + "\"";
    }
    else if(v.is_number())
      s += " " + json_number_text(v.get<double>());
    return s;
  }

  static const Json* find(const Json& o, const std::string& key)
  {
    const auto it = o.find(key);
    return it == o.end() ? nullptr : &*it;
  }

  void expect_object(const Json& v, const std::string& path, std::initializer_list<const char*> allowed) const
  {
    if(!v.is_object())
      fail(path, "expected an object, " + found(v));
    std::string names;
    for(const char* n : allowed)
      names += (names.empty() ? "" : ", ") + std::string(n);
    for(auto it = v.begin(); it != v.end(); ++it)
      if(std::find(allowed.begin(), allowed.end(), it.key()) == allowed.end())
        fail(path, "unknown field \"" + it.key() + "\"; the fields here are " + names);
  }

  const Json& field(const Json& o, const std::string& path, const char* key) const
  {
    const Json* v = find(o, key);
    if(!v)
      fail(path, std::string("missing field \"") + key + "\"");
    return *v;
  }

  const Json& array(const Json& v, const std::string& path) const
  {
    if(!v.is_array())
      fail(path, "expected an array, " + found(v));
    return v;
  }

  const Json& array(const Json& v, const std::string& path, std::size_t n, const char* of) const
  {
    if(!v.is_array())
      fail(path, "expected an array of " + std::to_string(n) + " " + of + ", " + found(v));
    if(v.size() != n)
      fail(path, "expected an array of " + std::to_string(n) + " " + of + ", found " + std::to_string(v.size()) +
                   (v.size() == 1 ? " element" : " elements"));
    return v;
  }

  double number(const Json& v, const std::string& path) const
  {
    if(!v.is_number())
      fail(path, "expected a number, " + found(v));
    return v.get<double>(); // always finite: parse_json() rejects NaN, infinities and overflows
  }

  const std::string& string(const Json& v, const std::string& path) const
  {
    if(!v.is_string())
      fail(path, "expected a string, " + found(v));
    return v.get_ref<const std::string&>();
  }

  // An integer in [0, limit): `what` says what it counts ("component", ...),
  // `owner` who has `limit` of them (empty: "there are").
  std::size_t index(const Json& v, const std::string& path, std::size_t limit, const std::string& what,
                    const std::string& owner = std::string()) const
  {
    const double x = v.is_number() ? v.get<double>() : -1.;
    if(!(x >= 0.) || x != std::floor(x))
      fail(path, "expected a " + what + " index (a non-negative integer), " + found(v));
    if(!(x < double(limit)))
      fail(path, what + " index " + json_number_text(x) + " is out of range: " +
                   (owner.empty() ? (limit == 1 ? "there is " : "there are ") : owner + " has ") +
                   std::to_string(limit) + " " + what + (limit == 1 ? "" : "s") +
                   (limit == 0 ? "" : " (0 to " + std::to_string(limit - 1) + ")"));
    return std::size_t(x);
  }

  // A parameter vector: an object with exactly the parameters' names, or an
  // array of them in order; each value inside its bounds.
  template <class Info>
  Eigen::VectorXd parameters(const Json& v, const std::string& path, std::size_t n, Info info) const
  {
    Eigen::VectorXd q = Eigen::VectorXd::Zero(Eigen::Index(n));
    std::vector<std::string> paths(n);
    if(v.is_array())
    {
      array(v, path, n, "numbers");
      for(std::size_t i = 0; i < n; ++i)
      {
        paths[i] = element_path(path, i) + " (" + info(i).name + ")";
        q[Eigen::Index(i)] = number(v[i], paths[i]);
      }
    }
    else if(v.is_object())
    {
      check_parameter_names(v, path, n, info);
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
        fail(paths[i], std::string(p.name) + " = " + json_number_text(x) + " is out of bounds: expected a value in [" +
                         bound_text(p.lower_bound) + ", " + bound_text(p.upper_bound) + "]");
    }
    return q;
  }

private:
  template <class Info>
  void check_parameter_names(const Json& v, const std::string& path, std::size_t n, Info info) const
  {
    std::string names;
    for(std::size_t i = 0; i < n; ++i)
      names += (i ? ", " : "") + std::string(info(i).name);
    for(auto it = v.begin(); it != v.end(); ++it)
    {
      bool known = false;
      for(std::size_t j = 0; j < n; ++j)
        known = known || it.key() == info(j).name;
      if(!known)
        fail(path, "unknown parameter \"" + it.key() + "\"; the parameters are " + names);
    }
  }

  static std::string bound_text(double x)
  {
    if(std::isinf(x))
      return x < 0. ? "-inf" : "inf";
    return json_number_text(x);
  }

  std::string m_where;
};

// Reads and validates a model, part by part: the header, the components, the
// blends, the holes, then the structure as a whole and the regions.
template <class GT>
class Blended_shape_reader : private Json_value_checker
{
  using Shape = Blended_shape<GT>;
  using Ellipsoid = typename Shape::Ellipsoid;
  using Toroid = typename Shape::Toroid;
  using Hole = typename Shape::Hole;

public:
  explicit Blended_shape_reader(const std::string& where) : Json_value_checker(where) {}

  Shape read(const std::string& text)
  {
    if(text.find_first_not_of(" \t\r\n") == std::string::npos)
      throw Input_error(Input_error::Malformed_content,
                        where() + ": the input is empty; expected a blended shape model (a JSON object with "
                                  "\"format\": \"blended_shape\")");
    Json doc;
    try
    {
      doc = parse_json(text);
    }
    catch(const Json_syntax_error& e)
    {
      throw Input_error(Input_error::Malformed_content,
                        where() + ": not valid JSON: " + e.what() + " (truncated or corrupt file?)");
    }
    read_header(doc);
    Shape shape = read_components(array(field(doc, "", "components"), "components"));
    const Json& blends = array(field(doc, "", "blends"), "blends");
    const Json& holes = array(field(doc, "", "holes"), "holes");
    read_blends(blends, holes.size(), shape);
    read_holes(holes, shape);
    check_structure(shape);
    check_regions(shape);
    return shape;
  }

private:
  // Far beyond any fitted model; bounds the loading time (Blended_shape
  // recomputes its layout, in quadratic time, on every append).
  static constexpr std::size_t max_components = 1000;

  // The format name and version, then the top-level fields.
  void read_header(const Json& doc) const
  {
    const auto U = Input_error::Unsupported_format;
    if(!doc.is_object())
      fail("", "expected a JSON object with \"format\": \"blended_shape\", " + found(doc) +
                 "; this is not a blended shape model", U);
    const Json* format = find(doc, "format");
    if(!format)
      fail("", "missing field \"format\"; this is not a blended shape model (expected \"format\": \"blended_shape\")",
           U);
    if(!format->is_string() || format->get_ref<const std::string&>() != "blended_shape")
      fail("format", "expected \"blended_shape\", " + found(*format) + "; this is not a blended shape model", U);
    const Json& version = field(doc, "", "version");
    if(!version.is_number() || version.get<double>() != double(blended_shape_file_version))
      fail("version", "expected " + std::to_string(blended_shape_file_version) + ", " + found(version) +
                        "; this library reads version " + std::to_string(blended_shape_file_version) +
                        " of the blended shape format", U);
    expect_object(doc, "", {"format", "version", "components", "blends", "holes", "hierarchy"});
  }

  Shape read_components(const Json& components)
  {
    if(components.empty())
      fail("components", "expected at least one component (the root)");
    if(components.size() > max_components)
      fail("components", std::to_string(components.size()) + " components; at most " +
                           std::to_string(max_components) + " are supported");
    std::vector<std::unique_ptr<Component_shape>> shapes;
    std::vector<Eigen::Vector3d> translations(components.size());
    std::vector<Eigen::Vector4d> quaternions(components.size());
    for(std::size_t c = 0; c < components.size(); ++c)
    {
      shapes.push_back(read_component(components[c], element_path("components", c)));
      read_placement(components[c], element_path("components", c), c == 0, translations[c], quaternions[c]);
      m_type_of.push_back(components[c].at("type").get<std::string>());
      m_is_hole.push_back(shapes[c]->template primitive<Hole>() != nullptr);
    }
    Shape shape(std::move(shapes[0]));
    for(std::size_t c = 1; c < shapes.size(); ++c)
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
    return shape;
  }

  // The primitive of a component, without its placement.
  std::unique_ptr<Component_shape> read_component(const Json& o, const std::string& path) const
  {
    if(!o.is_object())
      fail(path, std::string("expected an object (a component), ") + found(o));
    const std::string type = string(field(o, path, "type"), member_path(path, "type"));
    std::string type_name = type;
    if(const Json* n = find(o, "type_name"))
      type_name = string(*n, member_path(path, "type_name"));
    try
    {
      if(type == "superquadric_ellipsoid")
        return read_ellipsoid(o, path, type_name);
      if(type == "superquadric_toroid")
      {
        expect_object(o, path, {"type", "type_name", "parameters", "translation", "quaternion"});
        const Eigen::VectorXd p = primitive_parameters<Toroid>(o, path);
        return make_component_shape(Toroid(p[0], p[1], p[2], p[3], p[4], p[5], p[6]), type_name);
      }
      if(type == "hole_component")
        return read_hole_component(o, path, type_name);
    }
    catch(const std::invalid_argument& e)
    {
      fail(path, e.what());
    }
    fail(member_path(path, "type"), "unknown component type \"" + type +
                                        "\"; the known types are superquadric_ellipsoid, superquadric_toroid "
                                        "and hole_component");
  }

  template <class Primitive>
  Eigen::VectorXd primitive_parameters(const Json& o, const std::string& path) const
  {
    return parameters(field(o, path, "parameters"), member_path(path, "parameters"),
                      std::size_t(Primitive::number_of_parameters),
                      [](std::size_t i) -> const Parameter_info& { return Primitive::parameter_info(int(i)); });
  }

  std::unique_ptr<Component_shape> read_ellipsoid(const Json& o, const std::string& path,
                                                  const std::string& type_name) const
  {
    expect_object(o, path, {"type", "type_name", "chart_margin", "parameters", "translation", "quaternion"});
    const Eigen::VectorXd p = primitive_parameters<Ellipsoid>(o, path);
    const std::string mpath = member_path(path, "chart_margin");
    const double m = number(field(o, path, "chart_margin"), mpath);
    if(!(m > 0. && m < 1.))
      fail(mpath, "chart margin " + json_number_text(m) + " is out of bounds: expected a value in (0, 1)");
    return make_component_shape(Ellipsoid(p[0], p[1], p[2], p[3], p[4], m), type_name);
  }

  std::unique_ptr<Component_shape> read_hole_component(const Json& o, const std::string& path,
                                                       const std::string& type_name) const
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
      return make_component_shape(Hole(p[0], p[1], p[2], p[3], p[4], p[5], p[6], domain), type_name);
    }
    catch(const std::logic_error& e)
    {
      if(dynamic_cast<const std::invalid_argument*>(&e))
        throw;
      fail(dpath, e.what()); // parameters that the domain does not allow
    }
  }

  // The translation and quaternion: required but for the root, which is not placed.
  void read_placement(const Json& o, const std::string& path, bool root, Eigen::Vector3d& t,
                      Eigen::Vector4d& q) const
  {
    const std::string tpath = member_path(path, "translation"), qpath = member_path(path, "quaternion");
    t = Eigen::Vector3d::Zero();
    q = Eigen::Vector4d(1., 0., 0., 0.);
    const Json* tv = find(o, "translation");
    const Json* qv = find(o, "quaternion");
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
  }

  Ellipse_blending_region read_region(const Json& o, const std::string& path, bool base,
                                      std::size_t number_of_charts, const std::string& component) const
  {
    if(base)
      expect_object(o, path, {"chart", "kind", "half_width", "segments", "theta", "parameters"});
    else
      expect_object(o, path, {"kind", "chart", "half_width", "segments", "theta", "parameters"});
    const std::size_t chart =
      index(field(o, path, "chart"), member_path(path, "chart"), number_of_charts, "chart", component);
    const Blending_region_kind kind = base ? region_kind(o, path) : Blending_region_kind::Annulus;
    const std::string wpath = member_path(path, "half_width");
    const double half_width = number(field(o, path, "half_width"), wpath);
    if(!(half_width > 0.))
      fail(wpath, "the strip half-width " + json_number_text(half_width) + " must be positive");
    const std::size_t segments = region_segments(o, path);
    std::vector<double> theta;
    if(const Json* tv = find(o, "theta"))
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

  Blending_region_kind region_kind(const Json& o, const std::string& path) const
  {
    const std::string kpath = member_path(path, "kind");
    const std::string& k = string(field(o, path, "kind"), kpath);
    if(k != "disk" && k != "annulus")
      fail(kpath, "unknown region kind \"" + k + "\"; expected \"disk\" or \"annulus\"");
    return (k == "disk") ? Blending_region_kind::Disk : Blending_region_kind::Annulus;
  }

  std::size_t region_segments(const Json& o, const std::string& path) const
  {
    const std::string spath = member_path(path, "segments");
    const Json& sv = field(o, path, "segments");
    const double sd = number(sv, spath);
    if(!(sd >= 4. && sd <= 4096.) || sd != std::floor(sd))
      fail(spath, "expected a number of segments, an integer from 4 to 4096, " + found(sv));
    return std::size_t(sd);
  }

  // The blends, appended in order (their hole indices are checked against
  // the holes in read_holes()).
  void read_blends(const Json& blends, std::size_t number_of_holes, Shape& shape) const
  {
    if(blends.size() > 2 * max_components)
      fail("blends", std::to_string(blends.size()) + " blends; at most " + std::to_string(2 * max_components) +
                       " are supported");
    for(std::size_t b = 0; b < blends.size(); ++b)
      read_blend(blends[b], element_path("blends", b), number_of_holes, shape);
  }

  void read_blend(const Json& o, const std::string& path, std::size_t number_of_holes, Shape& shape) const
  {
    expect_object(o, path, {"kind", "base_component", "added_component", "region", "added_side", "hole", "core_stretch"});
    const Blend_kind kind = read_blend_kind(o, path);
    std::size_t base = 0, added = 0;
    read_blend_components(o, path, shape.number_of_components(), base, added);
    const std::string rpath = member_path(path, "region");
    const Ellipse_blending_region region = read_region(field(o, path, "region"), rpath, true,
                                                       shape.component(base).shape().number_of_charts(),
                                                       "component " + std::to_string(base));
    if(kind == Blend_kind::Split && region.kind() != Blending_region_kind::Annulus)
      fail(member_path(rpath, "kind"), "a split is cut and glue: expected an \"annulus\" region, found \"disk\"");
    const Added_side side = read_added_side(field(o, path, "added_side"), member_path(path, "added_side"), added,
                                            shape.component(added).shape().number_of_charts());
    const std::size_t hole = read_blend_hole(o, path, number_of_holes, kind, side);
    try
    {
      shape.append_blend(Blend(kind, base, region, added, side, hole, core_stretch(o, path)), false); // regions: later
    }
    catch(const std::invalid_argument& e)
    {
      fail(path, e.what());
    }
  }

  Blend_kind read_blend_kind(const Json& o, const std::string& path) const
  {
    const std::string kpath = member_path(path, "kind");
    const std::string& ks = string(field(o, path, "kind"), kpath);
    if(ks == "split")
      return Blend_kind::Split;
    if(ks == "part")
      return Blend_kind::Part;
    if(ks == "hole")
      return Blend_kind::Hole;
    fail(kpath, "unknown blend kind \"" + ks + "\"; expected \"split\", \"part\" or \"hole\"");
  }

  // The base and added components: a later component added to an earlier one.
  void read_blend_components(const Json& o, const std::string& path, std::size_t nc, std::size_t& base,
                             std::size_t& added) const
  {
    base = index(field(o, path, "base_component"), member_path(path, "base_component"), nc, "component");
    const std::string apath = member_path(path, "added_component");
    added = index(field(o, path, "added_component"), apath, nc, "component");
    if(added == 0)
      fail(apath, "component 0 is the root: no blend adds it");
    if(added == base)
      fail(apath, "a blend joins two different components, found " + std::to_string(added) + " twice");
    if(!(base < added))
      fail(apath, "component " + std::to_string(added) + " comes before its base component " +
                    std::to_string(base) + "; a blend adds a component to the shape built before it");
  }

  Added_side read_added_side(const Json& so, const std::string& spath, std::size_t added,
                             std::size_t number_of_charts) const
  {
    if(!so.is_object())
      fail(spath, "expected an object, " + found(so));
    const std::string skpath = member_path(spath, "kind");
    const std::string& sk = string(field(so, spath, "kind"), skpath);
    if(sk == "ellipse")
      return Added_side::ellipse(
        read_region(so, spath, false, number_of_charts, "component " + std::to_string(added)));
    if(sk != "hole_end")
      fail(skpath, "unknown added side kind \"" + sk + "\"; expected \"ellipse\" or \"hole_end\"");
    if(!m_is_hole[added])
      fail(spath, "a hole end needs a hole_component as the added component; component " + std::to_string(added) +
                    " is a " + m_type_of[added]);
    expect_object(so, spath, {"kind", "end", "delta", "phase"});
    const std::size_t end = index(field(so, spath, "end"), member_path(spath, "end"), 2, "hole end");
    const double delta = number(field(so, spath, "delta"), member_path(spath, "delta"));
    const double phase = number(field(so, spath, "phase"), member_path(spath, "phase"));
    try
    {
      return Added_side::hole_end(int(end), delta, phase);
    }
    catch(const std::invalid_argument& e)
    {
      fail(spath, e.what());
    }
  }

  // The hole of a blend of kind "hole" (null for the others).
  std::size_t read_blend_hole(const Json& o, const std::string& path, std::size_t number_of_holes, Blend_kind kind,
                              const Added_side& side) const
  {
    const std::string hpath = member_path(path, "hole");
    const Json& hv = field(o, path, "hole");
    const std::size_t hole = hv.is_null() ? Blend::no_hole : index(hv, hpath, number_of_holes, "hole");
    if((kind == Blend_kind::Hole) != (hole != Blend::no_hole))
      fail(hpath, kind == Blend_kind::Hole ? "a blend of kind \"hole\" names its hole, found null"
                                           : "only a blend of kind \"hole\" belongs to a hole; expected null");
    if((kind == Blend_kind::Hole) != (side.kind() == Added_side::Hole_end))
      fail(member_path(member_path(path, "added_side"), "kind"),
           kind == Blend_kind::Hole ? "a blend of kind \"hole\" has a \"hole_end\" added side"
                                    : "only a blend of kind \"hole\" has a \"hole_end\" added side");
    return hole;
  }

  // Optional (0: Blend::default_core_stretch()), written by every writer.
  double core_stretch(const Json& o, const std::string& path) const
  {
    const Json* sv = find(o, "core_stretch");
    if(!sv)
      return 0.;
    const std::string stpath = member_path(path, "core_stretch");
    const double stretch = number(*sv, stpath);
    if(!(stretch > 0.))
      fail(stpath, "expected a positive number");
    return stretch;
  }

  void read_holes(const Json& holes, Shape& shape)
  {
    m_hole_of_component.assign(shape.number_of_components(), Blend::no_hole);
    for(std::size_t h = 0; h < holes.size(); ++h)
    {
      const std::string path = element_path("holes", h);
      const typename Shape::Hole_record r = read_hole(holes[h], path, h, shape);
      try
      {
        shape.append_hole(r);
      }
      catch(const std::invalid_argument& e)
      {
        fail(path, e.what());
      }
    }
  }

  typename Shape::Hole_record read_hole(const Json& o, const std::string& path, std::size_t h, const Shape& shape)
  {
    expect_object(o, path, {"component", "blends"});
    const std::string cpath = member_path(path, "component");
    const std::size_t c = index(field(o, path, "component"), cpath, shape.number_of_components(), "component");
    if(!m_is_hole[c])
      fail(cpath, "component " + std::to_string(c) + " is a " + m_type_of[c] + ", not a hole_component");
    if(m_hole_of_component[c] != Blend::no_hole)
      fail(cpath, "component " + std::to_string(c) + " is already the component of hole " +
                    std::to_string(m_hole_of_component[c]));
    m_hole_of_component[c] = h;
    const std::string bpath = member_path(path, "blends");
    const Json& ends = array(field(o, path, "blends"), bpath, 2, "blend indices (ends 0 and 1)");
    typename Shape::Hole_record r;
    r.component = c;
    for(std::size_t e = 0; e < 2; ++e)
      r.blends[e] = read_hole_end(ends[e], element_path(bpath, e), h, c, e, shape);
    const bool tube = shape.component(c).shape().template primitive<Hole>()->domain() == Hole_domain::Tube;
    for(std::size_t e = 0; e < 2; ++e)
      if(shape.blend(r.blends[e]).is_gradual() == tube)
        fail(element_path(bpath, e),
             tube ? "the hole is in its tube domain, so its blends are final: expected an \"annulus\" region"
                  : "the hole is in its two_disks domain, so its blends are gradual: expected a \"disk\" region");
    return r;
  }

  // The blend at end `e` of hole `h`, whose component is `c`.
  std::size_t read_hole_end(const Json& v, const std::string& epath, std::size_t h, std::size_t c, std::size_t e,
                            const Shape& shape) const
  {
    const std::size_t b = index(v, epath, shape.number_of_blends(), "blend");
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
    return b;
  }

  // Every component but the root added by one blend (a hole's by two), and
  // no blend based on a component still being blended in gradually.
  void check_structure(const Shape& shape) const
  {
    const std::size_t nc = shape.number_of_components(), nb = shape.number_of_blends();
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
      const std::size_t expected = (m_hole_of_component[c] != Blend::no_hole) ? 2 : 1;
      if(added_by[c] != expected)
        fail(element_path("components", c),
             "the component is added by " + std::to_string(added_by[c]) + " blends, expected " +
               std::to_string(expected) +
               " (every component but the root is added by one blend, a hole's component by two, one per end)");
    }
  }

  // The regions, once the structure is known to be sound: inside their
  // charts, disjoint, and on the surface (what Blended_shape maintains).
  void check_regions(Shape& shape) const
  {
    for(std::size_t b = 0; b < shape.number_of_blends(); ++b)
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
  }

  std::vector<std::string> m_type_of; // the "type" of each component
  std::vector<bool> m_is_hole;
  std::vector<std::size_t> m_hole_of_component;
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
  const std::string text = internal::read_all(in, internal::Json_limits().max_size, where);
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
  const std::string text = internal::read_all(in, internal::Json_limits().max_size, where);
  return internal::Blended_shape_reader<GeomTraits>(where).read(text);
}

} // namespace Blended_shapes
} // namespace CGAL

#endif // CGAL_BLENDED_SHAPE_IO_BLENDED_SHAPE_IO_H
