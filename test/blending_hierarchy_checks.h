// SPDX-License-Identifier: LGPL-3.0-or-later
// The blending hierarchy (sec. 3.6): a DAG whose leaves are the components
// and whose inner vertices are the blends, one root reaching everything, the
// hole components with two parents; part adjacency; DOT export to a stream
// and, atomically, to a file. Shapes: a sphere, a split, a gradual part,
// three nested splits and a part, one hole (closed and open), a hole between
// two parts, two holes, blends listed out of order, a loose component.
// Both supported kernels.
#ifndef BLENDED_SHAPE_BLENDING_HIERARCHY_CHECKS_H
#define BLENDED_SHAPE_BLENDING_HIERARCHY_CHECKS_H
// Part of test_blended_shape (one program, one compilation of the blended
// shape for each kernel; CTest runs it as `test_blended_shape_hierarchy`).
#include "test_util.h"
#include "blended_shape_test_util.h"

#include <CGAL/Blended_shape/Blending/Blending_hierarchy.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Simple_cartesian.h>

#include <boost/graph/topological_sort.hpp>

#include <algorithm>
#include <cstddef>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <regex>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <unistd.h>

namespace blending_hierarchy_checks {

namespace BS = CGAL::Blended_shapes;

using blended_shape_test::set_parameter;

typedef BS::Ellipse_blending_region Region;
typedef BS::Blending_hierarchy Hierarchy;
typedef Hierarchy::Graph Graph;
typedef Hierarchy::Vertex Vertex;

template <class K>
using Shape = BS::Blended_shape<K>;

template <class K>
Shape<K> sphere(double e1 = 0.8, double e2 = 1.1)
{
  return Shape<K>(BS::Superquadric_ellipsoid<K>(1.0, 0.9, 1.1, e1, e2));
}

template <class K>
void add_tilted_part(Shape<K>& s, std::size_t base)
{
  s.add_part(base, 1, Region::make_parameters(-0.2, 0.25, 0.32, 0.28, -0.4, 0.85, 1.), 0.07,
             BS::Superquadric_ellipsoid<K>(0.5, 0.45, 0.8, 0.6, 1.2), "superquadric_ellipsoid",
             Eigen::Vector3d(0.1, -0.2, -0.9), Eigen::Vector4d(0.95, 0.2, -0.1, 0.05), 0,
             Region::make_parameters(0.05, 0., 0.55, 0.5, 0.1, 1., 0.), 0.1);
}

// What a test expects of a blend's vertex: the names of its base and added children.
struct Expected_blend
{
  std::string base_child, added_child;
};

// Names of the targets of the out-edges of v, by role.
std::pair<std::string, std::string> children(const Hierarchy& h, Vertex v, int& n_base, int& n_added)
{
  const Graph& g = h.graph();
  std::pair<std::string, std::string> r;
  n_base = n_added = 0;
  for(auto e : boost::make_iterator_range(boost::out_edges(v, g)))
  {
    if(g[e].role == BS::Blending_hierarchy_edge::Base)
    {
      ++n_base;
      r.first = h.vertex_name(boost::target(e, g));
    }
    else
    {
      ++n_added;
      r.second = h.vertex_name(boost::target(e, g));
    }
  }
  return r;
}

// The leaves (component indices) reachable from v.
std::set<std::size_t> leaves_below(const Graph& g, Vertex v)
{
  std::set<std::size_t> leaves;
  std::vector<bool> seen(boost::num_vertices(g), false);
  std::vector<Vertex> stack(1, v);
  while(!stack.empty())
  {
    const Vertex u = stack.back();
    stack.pop_back();
    if(seen[u])
      continue;
    seen[u] = true;
    if(g[u].kind == BS::Blending_hierarchy_node::Primitive_node)
      leaves.insert(g[u].index);
    for(auto e : boost::make_iterator_range(boost::out_edges(u, g)))
      stack.push_back(boost::target(e, g));
  }
  return leaves;
}

std::size_t count_reachable(const Graph& g, Vertex v)
{
  std::vector<bool> seen(boost::num_vertices(g), false);
  std::vector<Vertex> stack(1, v);
  std::size_t n = 0;
  while(!stack.empty())
  {
    const Vertex u = stack.back();
    stack.pop_back();
    if(seen[u])
      continue;
    seen[u] = true;
    ++n;
    for(auto e : boost::make_iterator_range(boost::out_edges(u, g)))
      stack.push_back(boost::target(e, g));
  }
  return n;
}

std::size_t count(const std::string& text, const std::string& what)
{
  std::size_t n = 0;
  for(std::size_t p = text.find(what); p != std::string::npos; p = text.find(what, p + what.size()))
    ++n;
  return n;
}

// The DOT text: node and edge lines against the graph.
void check_dot(const std::string& name, const Hierarchy& h, const std::string& dot)
{
  const Graph& g = h.graph();
  std::istringstream in(dot);
  std::string line;
  const std::regex node_line(R"re(^([cb][0-9]+)\[label=.*, shape=(box|ellipse)(, peripheries=2)?\];$)re");
  const std::regex edge_line(R"re(^([cb][0-9]+)->([cb][0-9]+) \[label="(base c[0-9]+|added|end [01])"\];$)re");
  std::size_t nodes = 0, edges = 0, boxes = 0, roots = 0;
  std::multiset<std::pair<std::string, std::string>> dot_edges, graph_edges;
  std::set<std::string> node_names;
  bool header = false, footer = false;
  while(std::getline(in, line))
  {
    std::smatch m;
    if(line == "digraph G {")
      header = true;
    else if(line == "}")
      footer = true;
    else if(std::regex_match(line, m, node_line))
    {
      ++nodes;
      node_names.insert(m[1]);
      boxes += (m[2] == "box") ? 1 : 0;
      roots += m[3].matched ? 1 : 0;
      if(m[3].matched)
        BS_CHECK(m[1] == h.vertex_name(h.root()), name << ": DOT marks " << m[1] << " as the root");
    }
    else if(line.find("->") != std::string::npos)
    {
      ++edges;
      BS_CHECK(std::regex_match(line, m, edge_line), name << ": malformed DOT edge line: " << line);
      if(m.size() > 2)
        dot_edges.insert(std::make_pair(m[1].str(), m[2].str()));
    }
  }
  for(auto e : boost::make_iterator_range(boost::edges(g)))
    graph_edges.insert(std::make_pair(h.vertex_name(boost::source(e, g)), h.vertex_name(boost::target(e, g))));
  BS_CHECK(header && footer, name << ": DOT text lacks 'digraph G {' or '}'");
  BS_CHECK(nodes == boost::num_vertices(g), name << ": " << nodes << " DOT nodes, expected " << boost::num_vertices(g));
  BS_CHECK(node_names.size() == nodes, name << ": DOT node names repeat");
  BS_CHECK(edges == boost::num_edges(g), name << ": " << edges << " DOT edges, expected " << boost::num_edges(g));
  BS_CHECK(boxes == h.number_of_components(), name << ": " << boxes << " boxes, expected one per component");
  BS_CHECK(roots == 1, name << ": " << roots << " nodes drawn as the root");
  BS_CHECK(dot_edges == graph_edges, name << ": the DOT edges differ from the graph's");
  BS_CHECK(count(dot, "shape=ellipse") == h.number_of_blends(), name << ": expected one ellipse per blend");
}

/*
The checks every hierarchy must pass, and the expected children of each
blend (`expected[b]`) and root name.
*/
template <class K>
void check_hierarchy(const std::string& name, const Shape<K>& s, const std::vector<Expected_blend>& expected,
                     const std::string& expected_root)
{
  const std::size_t nc = s.number_of_components(), nb = s.number_of_blends();
  BS_CHECK(expected.size() == nb, name << ": test set-up: " << expected.size() << " expectations for " << nb << " blends");
  Hierarchy h(s);
  const Graph& g = h.graph();
  const std::size_t nv = boost::num_vertices(g), ne = boost::num_edges(g);
  std::cout << "  " << name << ": " << nc << " components, " << nb << " blends, " << s.holes().size() << " holes -> "
            << nv << " vertices, " << ne << " edges, root " << h.vertex_name(h.root()) << std::endl;

  // Counts.
  BS_CHECK(h.number_of_components() == nc && h.number_of_blends() == nb, name << ": wrong sizes");
  BS_CHECK(nv == nc + nb, name << ": " << nv << " vertices, expected " << nc + nb);
  BS_CHECK(ne == 2 * nb, name << ": " << ne << " edges, expected " << 2 * nb);

  // Acyclic.
  bool dag = true;
  std::vector<Vertex> order;
  try
  {
    boost::topological_sort(g, std::back_inserter(order));
  }
  catch(const boost::not_a_dag&)
  {
    dag = false;
  }
  BS_CHECK(dag && order.size() == nv, name << ": the hierarchy has a cycle");

  // One root, reaching every vertex.
  std::vector<Vertex> roots;
  for(Vertex v = 0; v < nv; ++v)
    if(boost::in_degree(v, g) == 0)
      roots.push_back(v);
  BS_CHECK(roots.size() == 1, name << ": " << roots.size() << " vertices without parent");
  BS_CHECK(roots.size() == 1 && roots[0] == h.root(), name << ": root() is not the vertex without parent");
  BS_CHECK(count_reachable(g, h.root()) == nv, name << ": the root does not reach every vertex");
  BS_CHECK(h.vertex_name(h.root()) == expected_root,
           name << ": root " << h.vertex_name(h.root()) << ", expected " << expected_root);
  std::set<std::size_t> all;
  for(std::size_t c = 0; c < nc; ++c)
    all.insert(c);
  BS_CHECK(leaves_below(g, h.root()) == all, name << ": the root does not cover every component");

  // Leaves = components, inner vertices = blends.
  for(Vertex v = 0; v < nv; ++v)
  {
    const BS::Blending_hierarchy_node& n = g[v];
    const bool leaf = boost::out_degree(v, g) == 0;
    BS_CHECK(leaf == (v < nc), name << ": vertex " << v << " has out-degree " << boost::out_degree(v, g));
    BS_CHECK((n.kind == BS::Blending_hierarchy_node::Primitive_node) == (v < nc), name << ": vertex " << v << " kind");
  }
  std::size_t multi_parent = 0;
  for(std::size_t c = 0; c < nc; ++c)
  {
    const Vertex v = h.component_vertex(c);
    const BS::Blending_hierarchy_node& n = g[v];
    BS_CHECK(n.index == c, name << ": leaf " << v << " has index " << n.index);
    BS_CHECK(n.type_name == s.component(c).shape().type_name(), name << ": leaf " << c << " type " << n.type_name);
    BS_CHECK(h.label(v).find(n.type_name) != std::string::npos, name << ": label of c" << c << " lacks its type");
    // Parents: a hole component has two (its two ends), every other non-root leaf one.
    std::size_t hole = BS::Blend::no_hole;
    for(std::size_t k = 0; k < s.holes().size(); ++k)
      if(s.holes()[k].component == c)
        hole = k;
    BS_CHECK(n.hole == hole, name << ": leaf " << c << " names hole " << n.hole);
    std::set<Vertex> parents;
    for(auto e : boost::make_iterator_range(boost::in_edges(v, g)))
      parents.insert(boost::source(e, g));
    if(hole != BS::Blend::no_hole)
    {
      BS_CHECK(n.hole_is_tube == s.hole_is_tube(hole), name << ": hole " << hole << " domain");
      const std::set<Vertex> ends = {h.blend_vertex(s.holes()[hole].blends[0]), h.blend_vertex(s.holes()[hole].blends[1])};
      BS_CHECK(parents == ends, name << ": the parents of hole component c" << c << " are not its two end blends");
    }
    else
      BS_CHECK(boost::in_degree(v, g) == (v == h.root() ? 0u : 1u),
               name << ": leaf c" << c << " has " << boost::in_degree(v, g) << " parents");
    multi_parent += parents.size() > 1 ? 1 : 0;
  }
  // Not a tree exactly when there are holes.
  std::size_t inner_multi = 0;
  for(std::size_t b = 0; b < nb; ++b)
    inner_multi += boost::in_degree(h.blend_vertex(b), g) > 1 ? 1 : 0;
  BS_CHECK(inner_multi == 0, name << ": a blend vertex has several parents");
  BS_CHECK(multi_parent == s.holes().size(), name << ": " << multi_parent << " vertices with several parents, expected "
                                                  << s.holes().size() << " (one per hole)");

  // Blends: properties and children.
  for(std::size_t b = 0; b < nb; ++b)
  {
    const BS::Blend& B = s.blend(b);
    const Vertex v = h.blend_vertex(b);
    const BS::Blending_hierarchy_node& n = g[v];
    BS_CHECK(n.index == b && n.blend_kind == B.kind() && n.base_component == B.base_component() &&
               n.added_component == B.added_component() && n.hole == B.hole() && n.gradual == B.is_gradual(),
             name << ": blend " << b << " properties");
    const double hb = B.base_region().parameters()[Region::H];
    BS_CHECK(n.h == hb, name << ": blend " << b << " h " << n.h << ", expected " << hb);
    BS_CHECK(h.label(v).find(BS::blend_kind_name(B.kind())) != std::string::npos, name << ": label of b" << b);
    int n_base = 0, n_added = 0;
    const auto ch = children(h, v, n_base, n_added);
    BS_CHECK(n_base == 1 && n_added == 1, name << ": blend " << b << " has " << n_base << " base and " << n_added
                                                << " added edges");
    if(b < expected.size())
    {
      BS_CHECK(ch.first == expected[b].base_child,
               name << ": blend " << b << " base child " << ch.first << ", expected " << expected[b].base_child);
      BS_CHECK(ch.second == expected[b].added_child,
               name << ": blend " << b << " added child " << ch.second << ", expected " << expected[b].added_child);
    }
    for(auto e : boost::make_iterator_range(boost::out_edges(v, g)))
    {
      const BS::Blending_hierarchy_edge& p = g[e];
      const std::size_t c = (p.role == BS::Blending_hierarchy_edge::Base) ? B.base_component() : B.added_component();
      BS_CHECK(p.component == c, name << ": blend " << b << " edge names component " << p.component);
      const std::set<std::size_t> below = leaves_below(g, boost::target(e, g));
      BS_CHECK(below.count(c) == 1, name << ": blend " << b << ": component " << c << " is not below its edge");
    }
  }

  // Part adjacency: the blends' (base, added) pairs.
  const std::vector<BS::Part_adjacency> adj = BS::part_adjacency(s);
  BS_CHECK(adj.size() == nb, name << ": " << adj.size() << " adjacencies for " << nb << " blends");
  for(std::size_t b = 0; b < std::min(adj.size(), nb); ++b)
  {
    const BS::Blend& B = s.blend(b);
    BS_CHECK(adj[b].blend == b && adj[b].base_component == B.base_component() &&
               adj[b].added_component == B.added_component() && adj[b].kind == B.kind() && adj[b].hole == B.hole(),
             name << ": adjacency " << b << " is (" << adj[b].base_component << ", " << adj[b].added_component
                  << "), blend (" << B.base_component() << ", " << B.added_component() << ")");
  }

  // DOT to a stream, two ways.
  std::ostringstream dot1, dot2;
  BS::write_blending_hierarchy_dot(dot1, s);
  h.write_dot(dot2);
  BS_CHECK(dot1.str() == dot2.str(), name << ": the two DOT writers differ");
  check_dot(name, h, dot1.str());
}

// A temporary directory of this process, removed at the end.
struct Temporary_directory
{
  std::filesystem::path path;
  explicit Temporary_directory(const std::string& tag)
  {
    path = std::filesystem::temp_directory_path() /
           ("test_blending_hierarchy_" + tag + "_" + std::to_string(long(::getpid())));
    std::filesystem::remove_all(path);
    std::filesystem::create_directories(path);
  }
  ~Temporary_directory()
  {
    std::error_code ec;
    std::filesystem::remove_all(path, ec);
  }
  std::vector<std::string> entries() const
  {
    std::vector<std::string> r;
    for(const auto& e : std::filesystem::directory_iterator(path))
      r.push_back(e.path().filename().string());
    std::sort(r.begin(), r.end());
    return r;
  }
};

std::string read_text(const std::filesystem::path& p)
{
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// The file writer: same text as the stream; bad paths throw and leave nothing behind.
template <class K>
void test_file_writer(const std::string& tag, const Shape<K>& s)
{
  Temporary_directory dir(tag);
  std::ostringstream expected;
  BS::write_blending_hierarchy_dot(expected, s);

  const std::filesystem::path good = dir.path / "hierarchy.dot";
  BS::write_blending_hierarchy_dot(good.string(), s);
  BS_CHECK(read_text(good) == expected.str(), tag << ": the file differs from the stream output");
  BS::write_blending_hierarchy_dot(good.string(), sphere<K>()); // replaces it
  std::ostringstream small;
  BS::write_blending_hierarchy_dot(small, sphere<K>());
  BS_CHECK(read_text(good) == small.str(), tag << ": the file was not replaced");
  BS_CHECK(dir.entries() == std::vector<std::string>{"hierarchy.dot"}, tag << ": stray files after writing");

  // A missing directory.
  const std::filesystem::path missing = dir.path / "no_such_dir" / "hierarchy.dot";
  bool thrown = false;
  try
  {
    BS::write_blending_hierarchy_dot(missing.string(), s);
  }
  catch(const std::runtime_error& e)
  {
    thrown = true;
    const std::string w = e.what();
    BS_CHECK(w.find("write_blending_hierarchy_dot") != std::string::npos && w.find(missing.string()) != std::string::npos,
             tag << ": unclear message: " << w);
  }
  BS_CHECK(thrown, tag << ": writing into a missing directory did not throw std::runtime_error");
  BS_CHECK(!std::filesystem::exists(missing), tag << ": a file appeared in a missing directory");

  // A path that is a directory: the temporary file is made, the rename fails, nothing stays.
  const std::filesystem::path taken = dir.path / "taken";
  std::filesystem::create_directory(taken);
  thrown = false;
  try
  {
    BS::write_blending_hierarchy_dot(taken.string(), s);
  }
  catch(const std::runtime_error& e)
  {
    thrown = true;
    BS_CHECK(std::string(e.what()).find("write_blending_hierarchy_dot") != std::string::npos,
             tag << ": unclear message: " << e.what());
  }
  BS_CHECK(thrown, tag << ": writing onto a directory did not throw std::runtime_error");
  BS_CHECK(std::filesystem::is_directory(taken) && std::filesystem::is_empty(taken), tag << ": the directory changed");
  BS_CHECK((dir.entries() == std::vector<std::string>{"hierarchy.dot", "taken"}),
           tag << ": a failed write left a file behind");

  // An empty path.
  thrown = false;
  try
  {
    BS::write_blending_hierarchy_dot(std::string(), s);
  }
  catch(const std::invalid_argument&)
  {
    thrown = true;
  }
  BS_CHECK(thrown, tag << ": an empty path did not throw std::invalid_argument");
}

template <class K>
void run(const char* kernel, const std::string& tag)
{
  std::cout << "kernel " << kernel << std::endl;
  const Region::Parameter_vector split_region = Region::make_parameters(0.15, -0.1, 0.5, 0.42, 0.3, 0.9, 0.);

  // A single primitive: one leaf, which is the root.
  {
    Shape<K> s = sphere<K>();
    check_hierarchy<K>("sphere", s, {}, "c0");
    Hierarchy h(s);
    BS_CHECK(h.root() == h.component_vertex(0), "sphere: the root is not the leaf");
    std::ostringstream dot;
    h.write_dot(dot);
    BS_CHECK(count(dot.str(), "->") == 0 && count(dot.str(), "shape=box") == 1, "sphere: DOT " << dot.str());
  }

  // A split.
  Shape<K> split = sphere<K>();
  split.split(0, 0, split_region, 0.08);
  check_hierarchy<K>("split", split, {{"c0", "c1"}}, "b0");
  {
    Hierarchy h(split);
    BS_CHECK(!h.graph()[h.blend_vertex(0)].gradual && h.label(h.blend_vertex(0)).find("final") != std::string::npos,
             "split: the split is final: " << h.label(h.blend_vertex(0)));
  }

  // A gradual part, half expressed.
  {
    Shape<K> s = sphere<K>();
    add_tilted_part(s, 0);
    set_parameter(s, "b0.h", 0.4);
    check_hierarchy<K>("part", s, {{"c0", "c1"}}, "b0");
    Hierarchy h(s);
    const BS::Blending_hierarchy_node& n = h.graph()[h.blend_vertex(0)];
    BS_CHECK(n.blend_kind == BS::Blend_kind::Part && n.gradual && n.h == 0.4, "part: node " << n.h);
    BS_CHECK(h.label(h.blend_vertex(0)).find("gradual, h = 0.4") != std::string::npos,
             "part: label " << h.label(h.blend_vertex(0)));
  }

  // Three nested levels of splits (a part of a part of a part), then a part on the body.
  {
    Shape<K> s = split;
    s.split(1, 0, Region::make_parameters(0.2, -0.05, 0.13, 0.11, -0.2, 0.7, 0.), 0.04);
    s.split(2, 0, Region::make_parameters(0.2, -0.05, 0.04, 0.035, 0., 0.7, 0.), 0.012);
    add_tilted_part(s, 0);
    set_parameter(s, "b3.h", 0.6);
    check_hierarchy<K>("nested (three levels)", s, {{"c0", "c1"}, {"b0", "c2"}, {"b1", "c3"}, {"b2", "c4"}}, "b3");
    Hierarchy h(s);
    const Graph& g = h.graph();
    // The base edges name the component carrying each region: 0, 1, 2, 0.
    const std::size_t base_of[4] = {0, 1, 2, 0};
    for(std::size_t b = 0; b < 4; ++b)
      for(auto e : boost::make_iterator_range(boost::out_edges(h.blend_vertex(b), g)))
        if(g[e].role == BS::Blending_hierarchy_edge::Base)
          BS_CHECK(g[e].component == base_of[b], "nested: blend " << b << " base edge names c" << g[e].component);
    std::ostringstream dot;
    h.write_dot(dot);
    BS_CHECK(dot.str().find("b2->b1 [label=\"base c2\"];") != std::string::npos, "nested: DOT\n" << dot.str());
  }

  // One hole: its component has the two end blends as parents; closed, then open.
  {
    Shape<K> s = sphere<K>(1., 1.);
    s.add_hole(BS::Shape_point(0, BS::Chart_point(0, 0.05, 0.)), BS::Shape_point(0, BS::Chart_point(1, 0., 0.05)), 0.3,
               0.08, 0.1);
    check_hierarchy<K>("one hole (closed)", s, {{"c0", "c1"}, {"b0", "c1"}}, "b1");
    set_parameter(s, "b0.h", 0.);
    set_parameter(s, "b1.h", 0.);
    s.switch_hole_to_tube(0);
    check_hierarchy<K>("one hole (open)", s, {{"c0", "c1"}, {"b0", "c1"}}, "b1");
    Hierarchy h(s);
    BS_CHECK(boost::in_degree(h.component_vertex(1), h.graph()) == 2, "one hole: the hole component's in-degree");
    BS_CHECK(h.label(h.component_vertex(1)).find("tube") != std::string::npos, "one hole: label "
                                                                                 << h.label(h.component_vertex(1)));
    std::ostringstream dot;
    h.write_dot(dot);
    BS_CHECK(count(dot.str(), "->c1 ") == 2 && dot.str().find("b1->c1 [label=\"end 1\"];") != std::string::npos,
             "one hole: DOT\n" << dot.str());
  }

  // A hole from the body to a split-off part: its ends have different base components.
  {
    Shape<K> s = split;
    s.add_hole(BS::Shape_point(0, BS::Chart_point(1, 0., 0.05)), BS::Shape_point(1, BS::Chart_point(0, 0.15, -0.1)),
               0.12, 0.04, 0.1);
    check_hierarchy<K>("hole between two parts", s, {{"c0", "c1"}, {"b0", "c2"}, {"b1", "c2"}}, "b2");
    const std::vector<BS::Part_adjacency> adj = BS::part_adjacency(s);
    BS_CHECK(adj.size() == 3 && adj[1].base_component == 0 && adj[2].base_component == 1 && adj[1].added_component == 2 &&
               adj[2].added_component == 2 && adj[2].hole == 0,
             "hole between two parts: adjacency");
  }

  // Two holes.
  Shape<K> two(BS::Superquadric_ellipsoid<K>(1.6, 1., 0.6, 1., 1.));
  for(double x : {-0.45, 0.45})
    two.add_hole(BS::Shape_point(0, BS::Chart_point(0, x, 0.)), BS::Shape_point(0, BS::Chart_point(1, x, 0.)), 0.2, 0.06,
                 0.1);
  check_hierarchy<K>("two holes", two, {{"c0", "c1"}, {"b0", "c1"}, {"b1", "c2"}, {"b2", "c2"}}, "b3");

  // Blends listed out of order (as a model file may): blend 0 splits
  // component 1, which blend 1 adds later; blend 1 then joins two blended
  // shapes, component 0 and the result of blend 0.
  {
    Shape<K> s = sphere<K>();
    for(int k = 0; k < 2; ++k)
      s.append_component(BS::make_component_shape(BS::Superquadric_ellipsoid<K>(1.0, 0.9, 1.1, 0.8, 1.1),
                                                  "superquadric_ellipsoid"),
                         Eigen::Vector3d::Zero(), Eigen::Vector4d(1., 0., 0., 0.));
    auto make_blend = [](std::size_t base, std::size_t added, const Region::Parameter_vector& q, double w) {
      Region b(q, w, 8, BS::Blending_region_kind::Annulus, BS::Retained_side::Outside);
      b.set_chart(0);
      Region a(q, w, 8, BS::Blending_region_kind::Annulus, BS::Retained_side::Inside);
      a.set_chart(0);
      return BS::Blend(BS::Blend_kind::Split, base, b, added, BS::Added_side::ellipse(a));
    };
    s.append_blend(make_blend(1, 2, Region::make_parameters(0.2, -0.05, 0.13, 0.11, -0.2, 0.7, 0.), 0.04), false);
    s.append_blend(make_blend(0, 1, split_region, 0.08), false);
    check_hierarchy<K>("out of order", s, {{"c1", "c2"}, {"c0", "b0"}}, "b1");
  }

  // A component joined by no blend: not one shape.
  {
    Shape<K> s = sphere<K>();
    s.append_component(BS::make_component_shape(BS::Superquadric_ellipsoid<K>(1.0, 0.9, 1.1, 0.8, 1.1),
                                                "superquadric_ellipsoid"),
                       Eigen::Vector3d::Zero(), Eigen::Vector4d(1., 0., 0., 0.));
    bool thrown = false;
    try
    {
      Hierarchy h(s);
    }
    catch(const std::invalid_argument& e)
    {
      thrown = std::string(e.what()).find("component(s) 1 ") != std::string::npos;
    }
    BS_CHECK(thrown, "loose component: no std::invalid_argument naming it");
  }

  BS_CHECK(BS::Blending_hierarchy(two).component_vertex(2) == 2 && BS::Blending_hierarchy(two).blend_vertex(0) == 3,
           "vertex numbering");
  bool out_of_range = false;
  try
  {
    BS::Blending_hierarchy(two).blend_vertex(4);
  }
  catch(const std::out_of_range&)
  {
    out_of_range = true;
  }
  BS_CHECK(out_of_range, "blend_vertex(4) of a shape with 4 blends did not throw");

  test_file_writer<K>(tag, two);
}

// Every check of this part.
void run_all()
{
#ifndef BLENDED_SHAPE_ONE_KERNEL // sanitizer builds: Epick only (see test/CMakeLists.txt)
  run<CGAL::Simple_cartesian<double>>("Simple_cartesian<double>", "sc");
#endif
  run<CGAL::Exact_predicates_inexact_constructions_kernel>("Epick", "epick");
}

} // namespace blending_hierarchy_checks

#endif // BLENDED_SHAPE_BLENDING_HIERARCHY_CHECKS_H
