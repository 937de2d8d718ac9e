// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_BLENDED_SHAPE_BLENDING_BLENDING_HIERARCHY_H
#define CGAL_BLENDED_SHAPE_BLENDING_BLENDING_HIERARCHY_H

#include <CGAL/Blended_shape/Blending/Blend.h>
#include <CGAL/Blended_shape/Blending/Blended_shape.h>
#include <CGAL/Blended_shape/internal/write_file_atomically.h>

#include <boost/graph/adjacency_list.hpp>
#include <boost/graph/graph_traits.hpp>
#include <boost/graph/graphviz.hpp>
#include <boost/property_map/property_map.hpp>

#include <cstddef>
#include <locale>
#include <numeric>
#include <ostream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace CGAL {
namespace Blended_shapes {

/*!
\ingroup PkgBlendedShapeBlending

A vertex of a `Blending_hierarchy` (sec. 3.6): a leaf stands for a
primitive (a component of the blended shape), an inner vertex for the
blended shape that one blend produces. The fields that do not apply to the
vertex's kind keep their default values.
*/
struct Blending_hierarchy_node
{
  /// What a vertex stands for.
  enum Kind
  {
    Primitive_node, ///< a leaf: component `index` of the shape
    Blend_node      ///< an inner vertex: the result of blend `index`
  };

  /// What the vertex stands for.
  Kind kind = Primitive_node;
  /// The component index (`Primitive_node`) or the blend index (`Blend_node`).
  std::size_t index = 0;

  /// `Primitive_node`: the primitive's type name ("superquadric_ellipsoid", "hole_component", ...).
  std::string type_name;
  /// `Primitive_node` of a hole component: whether the hole is in its Tube domain (open, a handle).
  bool hole_is_tube = false;

  /// `Blend_node`: how the blend came about (split, part or hole end).
  Blend_kind blend_kind = Blend_kind::Split;
  /// `Blend_node`: the component whose chart holds the blend's base region.
  std::size_t base_component = 0;
  /// `Blend_node`: the component glued in by the blend.
  std::size_t added_component = 0;
  /// `Blend_node`: whether the blend is gradual (a disk region, `h` free; sec. 4.1).
  bool gradual = false;
  /// `Blend_node`: the blend's `h` (eq. 4); always 0 for a final (annulus) blend.
  double h = 0.;
  /// The hole: for a `Blend_node`, the hole the blend is an end of; for a
  /// `Primitive_node`, the hole whose component it is; `Blend::no_hole` otherwise.
  std::size_t hole = Blend::no_hole;
  /// `Blend_node` of a hole end: which end of the hole component (0 or 1); -1 otherwise.
  int hole_end = -1;
};

/*!
\ingroup PkgBlendedShapeBlending

An edge of a `Blending_hierarchy`: it goes from a blend's vertex to one of
the two shapes the blend joins (eq. 3).
*/
struct Blending_hierarchy_edge
{
  /// Which of the two blended shapes the edge leads to.
  enum Role
  {
    Base,  ///< `s_1`: the shape the region is cut into
    Added  ///< `s_2`: the shape glued in
  };

  /// Which of the two blended shapes the edge leads to.
  Role role = Base;
  /// `Base`: the component of the base shape whose chart holds the region;
  /// `Added`: the added component.
  std::size_t component = 0;
};

/*!
\ingroup PkgBlendedShapeBlending

One gluing of two components (part adjacency, sec. 3.6): blend `blend`
glues component `added_component` onto component `base_component`. Splits
count (the two halves of a split are adjacent parts). A hole gives two
records, one per end, both with the hole component as added component.
*/
struct Part_adjacency
{
  std::size_t blend = 0;           ///< the blend doing the gluing
  std::size_t base_component = 0;  ///< the component whose chart holds the region
  std::size_t added_component = 0; ///< the component glued in
  Blend_kind kind = Blend_kind::Split; ///< how the blend came about
  std::size_t hole = Blend::no_hole;   ///< the hole the blend is an end of, or `Blend::no_hole`
};

/*!
\ingroup PkgBlendedShapeBlending

The part adjacency of `shape` (sec. 3.6): one record per blend, in blend
order, naming the two components the blend glues directly together.
*/
template <class GeomTraits>
std::vector<Part_adjacency> part_adjacency(const Blended_shape<GeomTraits>& shape)
{
  std::vector<Part_adjacency> r;
  r.reserve(shape.number_of_blends());
  for(std::size_t b = 0; b < shape.number_of_blends(); ++b)
  {
    const Blend& B = shape.blend(b);
    Part_adjacency a;
    a.blend = b;
    a.base_component = B.base_component();
    a.added_component = B.added_component();
    a.kind = B.kind();
    a.hole = B.hole();
    r.push_back(a);
  }
  return r;
}

/*!
\ingroup PkgBlendedShapeBlending

The blending hierarchy of a blended shape (sec. 3.6): a directed acyclic
graph (Boost.Graph `adjacency_list`, bidirectional) whose leaves are the
primitives and whose inner vertices are the blended shapes made by the
blends. Every edge goes from a blend's vertex to one of the two shapes that
blend joins, so the leaves have no out-edges and a single root, the whole
model, has no in-edge.

<b>Vertices.</b> Vertex `c` (for `c` below `number_of_components()`) is the
leaf of component `c`; vertex `number_of_components() + b` is the inner
vertex of blend `b`. Their properties are `Blending_hierarchy_node`s.

<b>Edges.</b> The vertex of blend `b` has two out-edges
(`Blending_hierarchy_edge`), base first:
- *base*: to the vertex of the shape that held `b`'s base component when
  `b` was made: the vertex of the latest earlier blend whose result contains
  that component, or the component's leaf if no earlier blend involves it.
  The edge names the base component, since that shape may hold several.
- *added*: to the added component's leaf. For the second end of a hole
  this leaf is already part of the base shape (through the first end): the
  edge still goes to the leaf, so a hole component has two parents, the
  vertices of its two ends. This is why the hierarchy is a DAG and not a
  tree (sec. 3.6: "not necessarily a tree, based on how holes are added").
  In the one case where the added component already carries blends of its
  own while belonging to another shape than the base (a model file listing a
  part's blend before the blend that adds the part), the edge goes to that
  shape's vertex instead: the blend of two blended shapes of sec. 3.6.

<b>Why this structure.</b> In the paper every evolution step replaces the
model by a blend of it with a new shape (sec. 4.1, 4.2), so each blend's
base is the blended shape built so far and the hierarchy records the order
of the blends, which the paper's hierarchies show (Fig. 21(l); in Fig. 23
the same holes added in the other order give another hierarchy). With the
blends of one `Blended_shape` (made by split(), add_part(), add_hole()) all
the blend vertices thus form a chain in blend order, the root is the last
blend (or the only leaf if there is no blend), and which component each
blend is glued to is kept by the edges and by `part_adjacency()`, the part
graph (sec. 3.6: "part-adjacency information").

<b>Root.</b> The root is the only vertex without in-edges and reaches every
vertex.
*/
class Blending_hierarchy
{
public:
  /// The graph: vertices carry `Blending_hierarchy_node`, edges `Blending_hierarchy_edge`.
  typedef boost::adjacency_list<boost::vecS, boost::vecS, boost::bidirectionalS, Blending_hierarchy_node,
                                Blending_hierarchy_edge>
    Graph;
  /// A vertex of the graph (an index).
  typedef boost::graph_traits<Graph>::vertex_descriptor Vertex;

  /// The hierarchy of `shape`.
  /// \throws std::invalid_argument if a component is joined to the root by
  ///         no blend (impossible for shapes made by the `Blended_shape` API
  ///         or read from model files).
  template <class GeomTraits>
  explicit Blending_hierarchy(const Blended_shape<GeomTraits>& shape)
    : m_number_of_components(shape.number_of_components()), m_number_of_blends(shape.number_of_blends())
  {
    const std::size_t nc = m_number_of_components, nb = m_number_of_blends;
    for(std::size_t c = 0; c < nc; ++c)
    {
      Blending_hierarchy_node n;
      n.kind = Blending_hierarchy_node::Primitive_node;
      n.index = c;
      n.type_name = shape.component(c).shape().type_name();
      // add_vertex(g) then the property: add_vertex(property, g) makes g++ 12
      // warn inside Boost's named-graph lookup in sanitizer builds.
      m_graph[boost::add_vertex(m_graph)] = n;
    }
    for(std::size_t h = 0; h < shape.holes().size(); ++h)
    {
      Blending_hierarchy_node& n = m_graph[Vertex(shape.holes()[h].component)];
      n.hole = h;
      n.hole_is_tube = shape.hole_is_tube(h);
    }

    // Components joined so far form groups (union-find); each group is one
    // blended shape whose vertex is `top[find(c)]`.
    std::vector<std::size_t> parent(nc);
    std::iota(parent.begin(), parent.end(), std::size_t(0));
    std::vector<Vertex> top(nc);
    for(std::size_t c = 0; c < nc; ++c)
      top[c] = Vertex(c);
    auto find = [&parent](std::size_t c) {
      while(parent[c] != c)
      {
        parent[c] = parent[parent[c]];
        c = parent[c];
      }
      return c;
    };

    for(std::size_t b = 0; b < nb; ++b)
    {
      const Blend& B = shape.blend(b);
      Blending_hierarchy_node n;
      n.kind = Blending_hierarchy_node::Blend_node;
      n.index = b;
      n.blend_kind = B.kind();
      n.base_component = B.base_component();
      n.added_component = B.added_component();
      n.gradual = B.is_gradual();
      n.h = B.base_region().parameters()[Ellipse_blending_region::H];
      n.hole = B.hole();
      if(B.added_side().kind() == Added_side::Hole_end)
        n.hole_end = B.added_side().end();
      const Vertex v = boost::add_vertex(m_graph);
      m_graph[v] = n;

      const std::size_t gb = find(B.base_component()), ga = find(B.added_component());
      Blending_hierarchy_edge e;
      e.role = Blending_hierarchy_edge::Base;
      e.component = B.base_component();
      boost::add_edge(v, top[gb], e, m_graph);
      e.role = Blending_hierarchy_edge::Added;
      e.component = B.added_component();
      boost::add_edge(v, (ga == gb) ? Vertex(B.added_component()) : top[ga], e, m_graph);

      parent[ga] = gb;
      top[gb] = v;
    }

    std::vector<std::size_t> loose;
    for(std::size_t c = 1; c < nc; ++c)
      if(find(c) != find(0))
        loose.push_back(c);
    if(!loose.empty())
    {
      std::string list;
      for(std::size_t c : loose)
        list += (list.empty() ? "" : ", ") + std::to_string(c);
      throw std::invalid_argument("Blending_hierarchy: component(s) " + list +
                                  " are joined to the root component 0 by no blend; the shape is not one "
                                  "blended shape");
    }
    m_root = top[find(0)];
  }

  /// The graph.
  const Graph& graph() const { return m_graph; }
  /// The root: the vertex of the whole model (the last blend's, or the only
  /// leaf's if there is no blend).
  Vertex root() const { return m_root; }
  /// The number of components (leaves).
  std::size_t number_of_components() const { return m_number_of_components; }
  /// The number of blends (inner vertices).
  std::size_t number_of_blends() const { return m_number_of_blends; }

  /// The leaf of component `c`. \throws std::out_of_range if there is no such component.
  Vertex component_vertex(std::size_t c) const
  {
    if(c >= m_number_of_components)
      throw std::out_of_range("Blending_hierarchy: no component " + std::to_string(c));
    return Vertex(c);
  }
  /// The vertex of blend `b`. \throws std::out_of_range if there is no such blend.
  Vertex blend_vertex(std::size_t b) const
  {
    if(b >= m_number_of_blends)
      throw std::out_of_range("Blending_hierarchy: no blend " + std::to_string(b));
    return Vertex(m_number_of_components + b);
  }

  /// The name of vertex `v` in DOT output: "c" and the component index for
  /// a leaf, "b" and the blend index for a blend.
  std::string vertex_name(Vertex v) const
  {
    const Blending_hierarchy_node& n = m_graph[v];
    return (n.kind == Blending_hierarchy_node::Primitive_node ? "c" : "b") + std::to_string(n.index);
  }

  /// The label of vertex `v`, several lines separated by `'\n'`: for a leaf
  /// the component and its type name (and for a hole component the hole and
  /// its domain); for a blend its index and kind, the components it joins,
  /// and whether it is final or gradual with its `h`.
  std::string label(Vertex v) const
  {
    const Blending_hierarchy_node& n = m_graph[v];
    std::ostringstream s;
    s.imbue(std::locale::classic());
    if(n.kind == Blending_hierarchy_node::Primitive_node)
    {
      s << "component " << n.index << '\n' << n.type_name;
      if(n.hole != Blend::no_hole)
        s << "\nhole " << n.hole << (n.hole_is_tube ? ", tube (open)" : ", two disks (closed)");
      return s.str();
    }
    s << "blend " << n.index << ": " << blend_kind_name(n.blend_kind);
    if(n.hole != Blend::no_hole)
      s << " " << n.hole << " end " << n.hole_end;
    s << "\nc" << n.base_component << " + c" << n.added_component << '\n';
    if(n.gradual)
      s << "gradual, h = " << n.h;
    else
      s << "final";
    return s.str();
  }

  /*!
  Writes the hierarchy to `out` in Graphviz DOT (`boost::write_graphviz()`):
  a directed graph whose nodes are named as by vertex_name() and labelled by
  label(), primitives drawn as boxes and blends as ellipses (the root with a
  double outline), and whose edges from a blend to its base and added shapes
  are labelled "base cN" and "added" (or "end E" for a hole). One node or
  edge per line. The text is built before anything is written.
  \throws std::runtime_error if writing to `out` fails
  */
  void write_dot(std::ostream& out) const
  {
    const std::string text = dot_text();
    out << text;
    out.flush();
    if(!out)
      throw std::runtime_error("Blending_hierarchy::write_dot: writing the DOT text to the stream failed");
  }

private:
  // DOT strings: quotes and backslashes escaped, line breaks as \n.
  static std::string quoted(const std::string& t)
  {
    std::string q = "\"";
    for(char ch : t)
    {
      if(ch == '\n')
        q += "\\n";
      else if(ch == '"' || ch == '\\')
      {
        q += '\\';
        q += ch;
      }
      else if(ch != '\r')
        q += ch;
    }
    return q + "\"";
  }

  struct Vertex_writer
  {
    const Blending_hierarchy* h;
    void operator()(std::ostream& out, Vertex v) const
    {
      const bool leaf = h->m_graph[v].kind == Blending_hierarchy_node::Primitive_node;
      out << "[label=" << quoted(h->label(v)) << ", shape=" << (leaf ? "box" : "ellipse");
      if(v == h->m_root)
        out << ", peripheries=2";
      out << "]";
    }
  };

  struct Edge_writer
  {
    const Blending_hierarchy* h;
    void operator()(std::ostream& out, boost::graph_traits<Graph>::edge_descriptor e) const
    {
      const Blending_hierarchy_edge& p = h->m_graph[e];
      const Blending_hierarchy_node& n = h->m_graph[boost::source(e, h->m_graph)];
      std::string l;
      if(p.role == Blending_hierarchy_edge::Base)
        l = "base c" + std::to_string(p.component);
      else if(n.hole_end >= 0)
        l = "end " + std::to_string(n.hole_end);
      else
        l = "added";
      out << "[label=" << quoted(l) << "]";
    }
  };

  struct Graph_writer
  {
    void operator()(std::ostream& out) const { out << "label=\"blending hierarchy\";\nlabelloc=t;\n"; }
  };

  std::string dot_text() const
  {
    std::vector<std::string> names(boost::num_vertices(m_graph));
    for(std::size_t v = 0; v < names.size(); ++v)
      names[v] = vertex_name(Vertex(v));
    std::ostringstream s;
    s.imbue(std::locale::classic());
    boost::write_graphviz(s, m_graph, Vertex_writer{this}, Edge_writer{this}, Graph_writer(),
                          boost::make_iterator_property_map(names.begin(), boost::get(boost::vertex_index, m_graph)));
    return s.str();
  }

  Graph m_graph;
  Vertex m_root = 0;
  std::size_t m_number_of_components = 0, m_number_of_blends = 0;
};

/*!
\ingroup PkgBlendedShapeBlending

Writes the blending hierarchy of `shape` (sec. 3.6, see `Blending_hierarchy`)
to `out` in Graphviz DOT (Blending_hierarchy::write_dot()). Render it with
e.g. `dot -Tsvg hierarchy.dot -o hierarchy.svg`.
\throws std::runtime_error if writing to `out` fails
*/
template <class GeomTraits>
void write_blending_hierarchy_dot(std::ostream& out, const Blended_shape<GeomTraits>& shape)
{
  Blending_hierarchy(shape).write_dot(out);
}

/*!
\ingroup PkgBlendedShapeBlending

Writes the blending hierarchy of `shape` to the file `path` in Graphviz DOT
(see write_blending_hierarchy_dot(std::ostream&, const Blended_shape<GeomTraits>&)),
through a temporary file renamed at the end, as write_blended_shape() does:
a failure leaves no file behind, and an existing file is replaced only by
a complete one.
\throws std::invalid_argument on an empty path
\throws std::runtime_error if the file cannot be created (e.g. a missing or
        read-only directory), written or renamed; the message names the file
*/
template <class GeomTraits>
void write_blending_hierarchy_dot(const std::string& path, const Blended_shape<GeomTraits>& shape)
{
  std::ostringstream s;
  Blending_hierarchy(shape).write_dot(s);
  const std::string text = s.str();
  try
  {
    internal::write_file_atomically(path, [&](std::ostream& out) { out << text; });
  }
  catch(const std::invalid_argument& e)
  {
    throw std::invalid_argument(std::string("write_blending_hierarchy_dot: ") + e.what());
  }
  catch(const std::runtime_error& e)
  {
    throw std::runtime_error(std::string("write_blending_hierarchy_dot: ") + e.what());
  }
}

} // namespace Blended_shapes
} // namespace CGAL

#endif // CGAL_BLENDED_SHAPE_BLENDING_BLENDING_HIERARCHY_H
