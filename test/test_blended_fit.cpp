// SPDX-License-Identifier: LGPL-3.0-or-later
// The blended_fit tool: bad input exits non-zero with a message and writes
// nothing; a good run writes valid JSON with every documented key, and the
// mesh, hierarchy and model files; the fit is the same at any scale and place.
#include "test_util.h"
#include "tool_test_util.h"

#include <blended_shape_testing/synthetic_scans.h>

#include <CGAL/Blended_shape/Blending/Blended_shape_mesh.h>
#include <CGAL/Blended_shape/IO/Blended_shape_io.h>
#include <CGAL/IO/OFF.h>

#include <CGAL/IO/polygon_soup_io.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <nlohmann/json.hpp>

#include <cctype>
#include <iomanip>
#include <cmath>
#include <fstream>
#include <map>
#include <random>
#include <sstream>
#include <set>

namespace BS = CGAL::Blended_shapes;
typedef CGAL::Exact_predicates_inexact_constructions_kernel K;

namespace {

// (sanitizer builds leave out the runs that repeat the tool's code paths on
// the same data for other numbers: a moved reference, two evolution runs)
using blended_shape_test::reduced;

const std::string tool = BLENDED_FIT_EXE;

// A strict little JSON reader: validates the whole text and collects the
// top-level keys and the top-level number values.
class Json_checker
{
public:
  explicit Json_checker(const std::string& text) : m_s(text) {}
  bool valid()
  {
    skip();
    if(!value(0)) return false;
    skip();
    return m_i == m_s.size();
  }
  std::set<std::string> keys;
  std::map<std::string, double> numbers;

private:
  void skip() { while(m_i < m_s.size() && std::isspace(static_cast<unsigned char>(m_s[m_i]))) ++m_i; }
  bool literal(const char* word)
  {
    const std::string w(word);
    if(m_s.compare(m_i, w.size(), w) != 0) return false;
    m_i += w.size();
    return true;
  }
  bool string(std::string* out)
  {
    if(m_i >= m_s.size() || m_s[m_i] != '"') return false;
    ++m_i;
    std::string text;
    while(m_i < m_s.size() && m_s[m_i] != '"')
    {
      if(static_cast<unsigned char>(m_s[m_i]) < 0x20) return false;
      if(m_s[m_i] == '\\') { text += m_s[m_i++]; if(m_i >= m_s.size()) return false; }
      text += m_s[m_i++];
    }
    if(m_i >= m_s.size()) return false;
    ++m_i;
    if(out) *out = text;
    return true;
  }
  bool number(double* out)
  {
    const char* begin = m_s.c_str() + m_i;
    if(!(*begin == '-' || std::isdigit(static_cast<unsigned char>(*begin)))) return false;
    char* end = nullptr;
    const double x = std::strtod(begin, &end);
    if(end == begin || !std::isfinite(x)) return false;
    m_i += std::size_t(end - begin);
    if(out) *out = x;
    return true;
  }
  bool value(int depth)
  {
    skip();
    if(m_i >= m_s.size() || depth > 64) return false;
    const char c = m_s[m_i];
    if(c == '{')
    {
      ++m_i;
      skip();
      if(m_i < m_s.size() && m_s[m_i] == '}') { ++m_i; return true; }
      for(;;)
      {
        skip();
        std::string key;
        if(!string(&key)) return false;
        skip();
        if(m_i >= m_s.size() || m_s[m_i++] != ':') return false;
        skip();
        if(depth == 0)
        {
          keys.insert(key);
          const std::size_t at = m_i;
          double x;
          if(number(&x)) numbers[key] = x;
          m_i = at;
        }
        if(!value(depth + 1)) return false;
        skip();
        if(m_i >= m_s.size()) return false;
        const char d = m_s[m_i++];
        if(d == '}') return true;
        if(d != ',') return false;
      }
    }
    if(c == '[')
    {
      ++m_i;
      skip();
      if(m_i < m_s.size() && m_s[m_i] == ']') { ++m_i; return true; }
      for(;;)
      {
        if(!value(depth + 1)) return false;
        skip();
        if(m_i >= m_s.size()) return false;
        if(m_s[m_i] == ']') { ++m_i; return true; }
        if(m_s[m_i++] != ',') return false;
      }
    }
    if(c == '"') return string(nullptr);
    if(literal("true") || literal("false") || literal("null")) return true;
    return number(nullptr);
  }
  const std::string m_s;
  std::size_t m_i = 0;
};

std::string read_file(const std::string& name)
{
  std::ifstream in(name);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::size_t count_of(const std::string& text, const std::string& what)
{
  std::size_t n = 0;
  for(std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1))
    ++n;
  return n;
}

bool exists(const std::string& file) { return std::ifstream(file).good(); }

// 17 digits: every double is read back exactly.
void write_points(const std::string& file, const std::vector<K::Point_3>& pts, double scale = 1.,
                  const K::Vector_3& offset = K::Vector_3(0., 0., 0.))
{
  std::ofstream out(file);
  out.precision(17);
  for(const auto& p : pts) out << K::Point_3(scale * p.x(), scale * p.y(), scale * p.z()) + offset << '\n';
}

void test_json_checker()
{
  const int before = blended_shape_test::failures();
  BS_CHECK(Json_checker("{\"a\": 1, \"b\": [1, 2], \"c\": {\"d\": \"x\"}}").valid(), "valid JSON rejected");
  for(const char* bad : {"{\"a\": nan}", "{\"a\": 1,}", "{\"a\" 1}", "[1, 2", "{\"a\": 1} x", "{\"a\": inf}"})
    BS_CHECK(!Json_checker(bad).valid(), "invalid JSON accepted: " << bad);
  blended_shape_test::report("json_checker");
  (void)before;
}

void test_bad_input(const Temp_dir& dir)
{
  const std::string json = dir / "out.json";
  std::vector<K::Point_3> five;
  for(int i = 0; i < 5; ++i) five.emplace_back(i, i * i, 1);
  write_points(dir / "five.xyz", five);
  std::ofstream(dir / "empty.xyz").close();
  std::ofstream(dir / "garbage.xyz") << "1 2 three\n";
  std::ofstream(dir / "garbage.off") << "OFF\n3 1 0\n0 0\n";
  // `says`: what the message must contain, if anything (a range refused names the range)
  struct Case { std::string args; int code; std::string says = std::string(); };
  const std::vector<Case> cases = {
    {quote(dir / "missing.xyz"), 1},
    {quote(dir / "empty.xyz"), 1},
    {quote(dir / "five.xyz"), 1},
    {quote(dir / "garbage.xyz"), 1},
    {quote(dir / "garbage.off"), 1},
    {quote(dir.path.string()), 1},                      // a directory
    {quote(dir / "five.xyz") + " --bogus", 2},
    {"", 2},                                            // no input
    {quote(dir / "five.xyz") + " --max-iterations abc", 2},
    {quote(dir / "five.xyz") + " --max-iterations 0", 2, "--max-iterations must be in [1, 1000000], not 0"},
    {quote(dir / "five.xyz") + " --threads 5000", 2, "--threads must be in [0, 4096] (0: all cores), not 5000"},
    {quote(dir / "five.xyz") + " --seed 4294967296", 2, "--seed must be in [0, 4294967295]"},
    {quote(dir / "five.xyz") + " --seed -3", 2},
    {quote(dir / "five.xyz") + " --mesh " + quote(dir / "m.stl"), 2},
    {quote(dir / "five.xyz") + " --max-parts 0", 2, "--max-parts must be in [1, 1000]"},
    {quote(dir / "five.xyz") + " --no-split --max-parts 3", 2},
    {quote(dir / "five.xyz") + " --splits sideways", 2},
    {quote(dir / "five.xyz") + " --area-weight -1", 2},
    {quote(dir / "five.xyz") + " --area-weight x", 2},
    {quote(dir / "five.xyz") + " --area-weight 0x10", 2, "is not a number"},  // decimal only
    {quote(dir / "five.xyz") + " --blend-stages 0", 2},
    {quote(dir / "five.xyz") + " --stage-iterations 0", 2},
    {quote(dir / "five.xyz") + " --runs 0", 2, "--runs must be in [1, 1000], not 0"},
    {quote(dir / "five.xyz") + " --reference " + quote(dir / "missing.off"), 1, "missing.off"},
    {quote(dir / "five.xyz") + " --reference " + quote(dir / "garbage.off"), 1, "garbage.off"},
    {quote(dir / "five.xyz") + " --json", 2},           // missing value
    // outputs checked before anything is read or fitted
    {quote(dir / "five.xyz") + " --json " + quote(dir / "five.xyz"), 2, "same file"},  // would overwrite the input
    {quote(dir / "five.xyz") + " --strays " + quote(dir / "m.ply"), 2, "same file"},    // two outputs in one file
    {quote(dir / "five.xyz") + " --json " + quote(dir.path.string()), 2, "is a directory"},
    {quote(dir / "five.xyz") + " --hierarchy " + quote(dir / "no_dir/h.dot"), 1, "does not exist"},
    {quote(dir / "a.xyz") + " " + quote(dir / "b.xyz"), 2}};
  for(const Case& c : cases)
  {
    const std::size_t files = dir.number_of_files();
    std::string err;
    // every output requested first, so that the case's own flags come last
    const int code = run(quote(tool) + " --json " + quote(json) + " --mesh " + quote(dir / "m.ply") +
                           " --hierarchy " + quote(dir / "h.dot") + " --model " + quote(dir / "model.json") +
                           " --strays " + quote(dir / "strays.txt") + " " + c.args,
                         dir, &err);
    BS_CHECK(code == c.code, "blended_fit " << c.args << ": exit " << code << " instead of " << c.code);
    BS_CHECK(err.rfind("blended_fit: ", 0) == 0 && err.size() > 20, "no clear message: '" << err << "'");
    BS_CHECK(err.find(c.says) != std::string::npos, "blended_fit " << c.args << ": the message '" << err
                                                                      << "' does not say '" << c.says << "'");
    BS_CHECK(dir.number_of_files() == files, "blended_fit " << c.args << " left a file behind");
  }
  blended_shape_test::report("blended_fit_bad_input");
}

// A write that fails after the fit (here a full disk) removes the outputs
// written before it; a failed write to standard output is an error.
void test_failed_writes(const Temp_dir& dir)
{
  if(!std::filesystem::is_character_file("/dev/full"))
  {
    std::cout << "blended_fit_failed_writes: skipped (no /dev/full)" << std::endl;
    return;
  }
  std::mt19937_64 rng(6);
  write_points(dir / "small.xyz", BS::testing::synthetic_scan(BS::testing::random_superellipsoid<K>(rng), 300, true, 0.002, rng));
  const std::size_t files = dir.number_of_files();
  std::string err;
  const int code = run(quote(tool) + " " + quote(dir / "small.xyz") + " --quiet --no-split --mesh " + quote(dir / "m.ply") +
                         " --hierarchy " + quote(dir / "h.dot") + " --model " + quote(dir / "model.json") +
                         " --json /dev/full",
                       dir, &err);
  BS_CHECK(code == 1 && err.find("/dev/full") != std::string::npos,
           "--json /dev/full: exit " << code << ", message '" << err << "'");
  BS_CHECK(dir.number_of_files() == files, "a failed write left " << dir.number_of_files() - files << " outputs");
  const std::string err_file = dir / "stderr.txt";
  for(const std::string& args : {std::string(" --help"), " " + quote(dir / "small.xyz") + " --quiet --no-split"})
  {
    const int status = std::system((quote(tool) + args + " >/dev/full 2>" + quote(err_file)).c_str());
    std::ifstream in(err_file);
    std::string message;
    std::getline(in, message);
    BS_CHECK(WIFEXITED(status) && WEXITSTATUS(status) == 1 && message.find("standard output") != std::string::npos,
             "blended_fit" << args << " >/dev/full: exit " << WEXITSTATUS(status) << ", message '" << message << "'");
  }
  std::filesystem::remove(err_file);
  // More threads than the machine runs: the same fit, and TBB has nothing to warn about.
  std::string many, one;
  BS_CHECK(run(quote(tool) + " " + quote(dir / "small.xyz") + " --quiet --no-split --threads 4096", dir, &err, &many) == 0 &&
             err.empty(),
           "--threads 4096: " << err);
  BS_CHECK(run(quote(tool) + " " + quote(dir / "small.xyz") + " --quiet --no-split --threads 1", dir, nullptr, &one) == 0,
           "--threads 1");
  const auto model_of = [](const std::string& summary) { return summary.substr((std::min)(summary.find("\"model\""), summary.size())); };
  BS_CHECK(!one.empty() && model_of(one) == model_of(many), "--threads 4096 and --threads 1 gave other models");
  blended_shape_test::report("blended_fit_failed_writes");
}

void test_good_run(const Temp_dir& dir)
{
  std::mt19937_64 rng(4);
  const auto model = BS::testing::random_superellipsoid<K>(rng);
  write_points(dir / "cloud.xyz", BS::testing::synthetic_scan(model, 800, true, 0.002, rng));
  std::string err, out;
  const int code = run(quote(tool) + " " + quote(dir / "cloud.xyz") + " --mesh " + quote(dir / "m.ply") +
                         " --hierarchy " + quote(dir / "h.dot") + " --model " + quote(dir / "model.json") +
                         " --trace " + quote(dir / "trace"),
                       dir, &err, &out);
  BS_CHECK(code == 0, "good run failed: " << err);
  BS_CHECK(err.find("iteration") != std::string::npos && err.find("parts") != std::string::npos, "no progress shown");
  Json_checker summary(out);
  BS_CHECK(summary.valid(), "the summary is not valid JSON:\n" << out);
  for(const char* key : {"points", "parameters", "iterations", "iterations_on_all_points", "relative_rms",
                         "rms_over_bbox_diagonal", "stray_points", "degeneracy", "parts", "holes", "genus", "evolution",
                         "seconds", "model"})
    BS_CHECK(summary.keys.count(key) == 1, "missing key " << key);
  BS_CHECK(out.find("\"degeneracy\": \"none\"") != std::string::npos && err.find("note:") == std::string::npos,
           "a superquadric's scan is flat?\n" << out);
  // The short fits that compare starts use 160 of the 800 points; the fits
  // to rest use all.
  BS_CHECK(summary.numbers["iterations_on_all_points"] > 0 &&
             summary.numbers["iterations_on_all_points"] < summary.numbers["iterations"],
           "iterations on all points " << summary.numbers["iterations_on_all_points"] << " of "
                                       << summary.numbers["iterations"]);
  // A clean single superquadric: evolution tries splits and keeps none.
  BS_CHECK(summary.numbers["points"] == 800 && summary.numbers["parameters"] == 12 && summary.numbers["parts"] == 1,
           "points / parameters / parts: " << summary.numbers["points"] << " / " << summary.numbers["parameters"]
                                           << " / " << summary.numbers["parts"]);
  // Evolution on a sample (400 of the 800 points), whose first fit sees
  // the sample only: the summary still counts every input point.
  {
    std::string sampled_out;
    BS_CHECK(run(quote(tool) + " " + quote(dir / "cloud.xyz") + " --quiet --evolution-points 400", dir, nullptr,
                 &sampled_out) == 0,
             "run with --evolution-points 400 failed");
    Json_checker sampled(sampled_out);
    BS_CHECK(sampled.valid() && sampled.numbers["points"] == 800 && sampled.numbers["parts"] == 1,
             "--evolution-points 400: points / parts " << sampled.numbers["points"] << " / " << sampled.numbers["parts"]);
  }
  BS_CHECK(summary.numbers["rms_over_bbox_diagonal"] < 0.01, "a poor fit of a clean superquadric");
  const std::size_t events = count_of(out, "\"kind\": ");
  BS_CHECK(out.find("\"events\": [") != std::string::npos && count_of(out, "\"kind\": \"split\"") == 0,
           "the evolution events: " << out);
  BS_CHECK(count_of(err, "blended_fit: event ") == events, "progress does not name the " << events << " events");
  BS_CHECK(err.find("part evolution: split proposals") != std::string::npos &&
             count_of(err, "part evolution: fit of a split model") == events,
           "progress does not name the evolution phases");
  // The trace: the first fit, then the model after each event, as PLY and DOT.
  BS_CHECK(exists(dir / "trace/00_first_fit.ply") && exists(dir / "trace/00_first_fit.dot"), "trace of the first fit");
  for(std::size_t e = 1; e <= events; ++e)
  {
    const std::string stem = dir / ("trace/" + std::string(e < 10 ? "0" : "") + std::to_string(e) + "_undo");
    std::vector<K::Point_3> points;
    std::vector<std::vector<std::size_t>> faces;
    BS_CHECK(CGAL::IO::read_polygon_soup(stem + ".ply", points, faces) && faces.size() > 100 &&
               read_file(stem + ".dot").find("digraph") != std::string::npos,
             "trace of event " << e);
  }
  Json_checker model_file(read_file(dir / "model.json"));
  BS_CHECK(model_file.valid() && model_file.keys.count("pose") && model_file.keys.count("shape"), "model file");
  // Its shape is a model file of the package, and with its pose it is the fitted surface.
  {
    const std::string text = read_file(dir / "model.json");
    const std::size_t at = text.find("\"shape\": ");
    std::istringstream shape_text(at == std::string::npos ? std::string() : text.substr(at + 9, text.rfind('}') - at - 9));
    bool readable = false;
    try
    {
      readable = BS::read_blended_shape_json<K>(shape_text).number_of_components() == 1;
    }
    catch(const std::exception& e)
    {
      std::cerr << e.what() << std::endl;
    }
    BS_CHECK(readable, "the model file's shape does not read back");
  }
  // --no-split: one superquadric and no event.
  BS_CHECK(run(quote(tool) + " " + quote(dir / "cloud.xyz") + " --quiet --no-split", dir, nullptr, &out) == 0 &&
             Json_checker(out).valid() && out.find("\"events\": []") != std::string::npos,
           "--no-split: " << out);
  BS_CHECK(read_file(dir / "h.dot").find("digraph") != std::string::npos, "hierarchy file");
  for(const char* mesh : {"m.ply", "m.off"})
  {
    if(std::string(mesh) == "m.off")
      BS_CHECK(run(quote(tool) + " " + quote(dir / "cloud.xyz") + " --quiet --mesh " + quote(dir / mesh), dir) == 0,
               "--mesh .off");
    std::vector<K::Point_3> points;
    std::vector<std::vector<std::size_t>> faces;
    BS_CHECK(CGAL::IO::read_polygon_soup(dir / mesh, points, faces) && faces.size() > 100, "mesh " << mesh);
  }
  // --json FILE and --quiet: nothing on stdout or stderr, the file holds the summary.
  BS_CHECK(run(quote(tool) + " " + quote(dir / "cloud.xyz") + " --quiet --json " + quote(dir / "s.json"), dir, &err,
               &out) == 0 && out.empty() && err.empty(), "--quiet --json");
  BS_CHECK(Json_checker(read_file(dir / "s.json")).valid(), "--json file");
  BS_CHECK(run(quote(tool) + " --help", dir, nullptr, &out) == 0 && out.find("Usage") != std::string::npos, "--help");
  blended_shape_test::report("blended_fit_good_run");
}

// Data made of parts (a body with a part, testing::body_with_part_scan()):
// the tool returns two parts, says so in its summary and its progress
// (the iterations of a split model's fit count its parts), and traces the split.
// The "evolution" object of a summary, empty if the summary is not valid
// JSON or has none (the caller's Json_checker reports that), and its array
// `key`, empty if it has none: no exception on a broken summary.
nlohmann::json evolution_of(const std::string& summary)
{
  const nlohmann::json parsed = nlohmann::json::parse(summary, nullptr, false);
  const nlohmann::json evolution = parsed.is_object() ? parsed.value("evolution", nlohmann::json::object()) : nlohmann::json();
  return evolution.is_object() ? evolution : nlohmann::json::object();
}

nlohmann::json array_of(const nlohmann::json& evolution, const char* key)
{
  const nlohmann::json a = evolution.value(key, nlohmann::json::array());
  return a.is_array() ? a : nlohmann::json::array();
}

void test_parts_run(const Temp_dir& dir)
{
  write_points(dir / "parts.xyz", BS::testing::body_with_part_scan<K>(1500, 1));
  // --reference: a mesh of the scan's body (its part left out), and the same
  // moved by 10 along x: the Chamfer distance of the model (two parts, about
  // 2 across) to it is below 0.5, of one superquadric (--no-split, cheaper)
  // to the moved one 10 give or take 2, in the points' unit
  for(const double shift : {0., 10.})
  {
    CGAL::Surface_mesh<K::Point_3> body =
      BS::make_unified_mesh(BS::Blended_shape<K>(BS::Superquadric_ellipsoid<K>(1., 0.8, 0.6, 1., 1.)));
    for(auto v : body.vertices())
      body.point(v) = body.point(v) + K::Vector_3(shift, 0., 0.);
    CGAL::IO::write_OFF(dir / (shift == 0. ? "body.off" : "moved_body.off"), body);
  }
  std::string err, out;
  BS_CHECK(run(quote(tool) + " " + quote(dir / "parts.xyz") + " --max-parts 2 --trace " + quote(dir / "parts_trace") +
                 " --reference " + quote(dir / "body.off"),
               dir, &err, &out) == 0,
           "run on data made of parts failed: " << err);
  Json_checker summary(out);
  BS_CHECK(summary.valid(), "the summary is not valid JSON:\n" << out);
  BS_CHECK(summary.numbers.count("chamfer_distance") == 1 && summary.numbers["chamfer_distance"] > 0. &&
             summary.numbers["chamfer_distance"] < 0.5,
           "Chamfer distance to the body " << summary.numbers["chamfer_distance"]);
  if(!reduced)
  {
    std::string moved_out;
    BS_CHECK(run(quote(tool) + " " + quote(dir / "parts.xyz") + " --quiet --no-split --reference " +
                   quote(dir / "moved_body.off"), dir, nullptr, &moved_out) == 0, "--reference, moved");
    Json_checker moved(moved_out);
    BS_CHECK(moved.valid(), "the summary is not valid JSON:\n" << moved_out);
    BS_CHECK(moved.numbers["chamfer_distance"] > 8. && moved.numbers["chamfer_distance"] < 12.,
             "Chamfer distance to the body moved by 10: " << moved.numbers["chamfer_distance"]);
  }
  BS_CHECK(summary.numbers["parts"] == 2 && summary.numbers["genus"] == 0 && count_of(out, "\"accepted\": true") == 1,
           "parts " << summary.numbers["parts"] << ", genus " << summary.numbers["genus"] << ":\n" << out);
  BS_CHECK(err.find("  parts 2  holes 0") != std::string::npos, "the progress of a split model's fit does not count its parts");
  BS_CHECK(err.find("split of component 0 kept") != std::string::npos, "the progress does not name the kept split");
  // The trace's files are numbered by event (from 1), in the order of the summary's events.
  const nlohmann::json evolution = evolution_of(out);
  const nlohmann::json events = array_of(evolution, "events");
  std::size_t kept = 0;
  for(std::size_t i = 0; i < events.size(); ++i)
    if(events[i].is_object() && events[i].value("accepted", false))
      kept = i + 1;
  std::ostringstream kept_trace;
  kept_trace << "parts_trace/" << std::setw(2) << std::setfill('0') << kept << "_split.ply";
  BS_CHECK(kept > 0 && exists(dir / kept_trace.str()), "no trace of the kept split (" << kept_trace.str() << ")");
  BS_CHECK(evolution.value("split_source", std::string()) == "creases",
           "the summary does not name the split source (creases by default)");
  // one evolution run by default: its description length, run 0 kept
  const nlohmann::json lengths = array_of(evolution, "run_description_lengths");
  BS_CHECK(evolution.value("runs", 0.) == 1. && evolution.value("run_kept", -1.) == 0. &&
             lengths.size() == 1 && lengths[0].is_number(),
           "the summary does not give the one evolution run and its description length");
  blended_shape_test::report("blended_fit_parts");
}

// Two evolution runs on the data of test_parts_run(): two lengths, the
// shorter kept; the trace holds both runs' events in turn, numbered on, then
// the final model.
void test_two_runs(const Temp_dir& dir)
{
  std::string runs_out;
  BS_CHECK(run(quote(tool) + " " + quote(dir / "parts.xyz") + " --quiet --max-parts 2 --runs 2 --trace " +
                 quote(dir / "runs_trace"), dir, nullptr, &runs_out) == 0, "--runs 2");
  const nlohmann::json runs_evolution = evolution_of(runs_out);
  const nlohmann::json two = array_of(runs_evolution, "run_description_lengths");
  const bool two_lengths = two.size() == 2 && two[0].is_number() && two[1].is_number();
  BS_CHECK(two_lengths && runs_evolution.value("runs", 0.) == 2. &&
             runs_evolution.value("run_kept", -1.) == (two[1].get<double>() < two[0].get<double>() ? 1. : 0.),
           "--runs 2: not two lengths with the shorter kept:\n" << runs_out);
  std::size_t traced = 0; // the events' files of both runs
  for(const auto& entry : std::filesystem::directory_iterator(dir / "runs_trace"))
  {
    const std::string name = entry.path().filename().string();
    traced += (name.size() > 4 && name.substr(name.size() - 4) == ".ply" && name.find("_first_fit") == std::string::npos &&
               name.find("_final") == std::string::npos) ? 1 : 0;
  }
  std::ostringstream final_trace;
  final_trace << "runs_trace/" << std::setw(2) << std::setfill('0') << traced + 1 << "_final.ply";
  const nlohmann::json kept_events = array_of(runs_evolution, "events");
  BS_CHECK(traced >= kept_events.size() && exists(dir / final_trace.str()),
           "--runs 2 --trace: " << traced << " events traced, " << kept_events.size() << " in the summary, no "
                                << final_trace.str());
  blended_shape_test::report("blended_fit_two_runs");
}

// 200 strays over 10 times the box of 800 points: by default they are found
// (a stray within the noise of the surface may pass for an inlier) and
// listed by --strays; --no-robust judges none stray.
void test_strays(const Temp_dir& dir)
{
  std::mt19937_64 rng(5);
  auto points = BS::testing::synthetic_scan(BS::testing::random_superellipsoid<K>(rng), 800, false, 0.002, rng);
  BS::testing::add_stray_points(points, 200, 10., rng);
  write_points(dir / "strays.xyz", points);
  std::string out;
  BS_CHECK(run(quote(tool) + " " + quote(dir / "strays.xyz") + " --quiet --no-split --strays " + quote(dir / "strays.txt"), dir,
               nullptr, &out) == 0, "--strays");
  Json_checker summary(out);
  BS_CHECK(summary.valid(), "the summary is not valid JSON:\n" << out);
  std::ifstream list(dir / "strays.txt");
  std::size_t index = 0, listed = 0, strays_listed = 0;
  while(list >> index)
  {
    ++listed;
    strays_listed += index >= 800 ? 1 : 0;
  }
  BS_CHECK(summary.numbers["stray_points"] == double(listed) && strays_listed >= 195 && listed <= 202,
           "stray count " << summary.numbers["stray_points"] << ", " << listed << " listed, " << strays_listed
                          << " of them strays");
  BS_CHECK(run(quote(tool) + " " + quote(dir / "strays.xyz") + " --quiet --no-split --no-robust", dir, nullptr, &out) == 0 &&
             Json_checker(out).valid(), "--no-robust");
  Json_checker plain(out);
  BS_CHECK(plain.valid() && plain.numbers["stray_points"] == 0., "--no-robust judged points stray");
  blended_shape_test::report("blended_fit_strays");
}

// The same cloud scaled by 1e-12 and 1e12, or moved by 1e15 (exactly: its
// coordinates on the grid of doubles there), fits the same, relatively; at
// 1e300 the tool fails with a clear message and writes nothing.
void test_any_scale(const Temp_dir& dir)
{
  std::mt19937_64 rng(5);
  const auto model = BS::testing::random_superellipsoid<K>(rng);
  std::vector<K::Point_3> cloud;
  for(const auto& p : BS::testing::synthetic_scan(model, 500, true, 0.002, rng))
    cloud.emplace_back(std::round(p.x() * 8e6) / 8., std::round(p.y() * 8e6) / 8., std::round(p.z() * 8e6) / 8.);
  auto fit = [&](double scale, const K::Vector_3& offset, std::string* err) {
    write_points(dir / "scaled.xyz", cloud, scale, offset);
    std::string out;
    const int code = run(quote(tool) + " " + quote(dir / "scaled.xyz") + " --quiet", dir, err, &out);
    Json_checker summary(out);
    BS_CHECK(code == 0 || summary.valid() || out.empty(), "exit " << code << " with output " << out);
    return code == 0 && summary.valid() ? summary.numbers : std::map<std::string, double>();
  };
  std::string err;
  const auto unit = fit(1., K::Vector_3(0., 0., 0.), &err);
  BS_CHECK(!unit.empty(), "unit cloud: " << err);
  struct Case { double scale; K::Vector_3 offset; };
  for(const Case& c : {Case{1e-12, K::Vector_3(0., 0., 0.)}, Case{1e12, K::Vector_3(0., 0., 0.)},
                       Case{1., K::Vector_3(1e15, -1e15, 0.5e15)}})
  {
    const auto scaled = fit(c.scale, c.offset, &err);
    BS_CHECK(!scaled.empty(), "scale " << c.scale << ", offset " << c.offset << ": " << err);
    if(scaled.empty() || unit.empty())
      continue;
    BS_CHECK(std::abs(scaled.at("rms_over_bbox_diagonal") / unit.at("rms_over_bbox_diagonal") - 1.) < 1e-6 &&
               std::abs(scaled.at("rms") / (c.scale * unit.at("rms")) - 1.) < 1e-6,
             "scale " << c.scale << ", offset " << c.offset << ": rms " << scaled.at("rms") << " vs "
                      << c.scale * unit.at("rms"));
  }
  const std::size_t files = dir.number_of_files();
  BS_CHECK(fit(1e300, K::Vector_3(0., 0., 0.), &err).empty() && err.find("beyond 1e+150") != std::string::npos &&
             err.find("nan") == std::string::npos && dir.number_of_files() == files,
           "1e300: " << err);
  blended_shape_test::report("blended_fit_any_scale");
}

// Points in a plane or on a line: the fit ends at a flat superquadric or a
// needle (an exact "fit"), and both the summary and a note on standard
// error (also with --quiet) say that the points were flat.
void test_flat_points(const Temp_dir& dir)
{
  std::vector<K::Point_3> plane, line;
  for(int i = 0; i < 20; ++i)
    for(int j = 0; j < 20; ++j)
      plane.emplace_back(0.05 * i, 0.03 * j, 0.2 + 0.01 * i - 0.02 * j); // a tilted plane
  for(int i = 0; i < 100; ++i)
    line.emplace_back(0.01 * i, 0.02 * i, 0.03 * i);
  for(const auto& [name, points] : {std::make_pair("coplanar", plane), std::make_pair("collinear", line)})
  {
    write_points(dir / "flat.xyz", points);
    std::string err, out;
    const int code = run(quote(tool) + " " + quote(dir / "flat.xyz") + " --no-split --quiet", dir, &err, &out);
    BS_CHECK(code == 0, name << ": exit " << code << ": " << err);
    BS_CHECK(out.find(std::string("\"degeneracy\": \"") + name + "\"") != std::string::npos,
             name << ": the summary does not say so:\n" << out);
    BS_CHECK(err.find(std::string("note: the points are ") + name) != std::string::npos,
             name << ": no note on standard error: " << err);
  }
  blended_shape_test::report("blended_fit_flat_points");
}

// The manual's copy of the usage text (its section on blended_fit) is the
// text --help prints: a new option shows up in the manual too.
void test_manual_usage(const Temp_dir& dir)
{
  std::string out;
  BS_CHECK(run(quote(tool) + " --help", dir, nullptr, &out) == 0, "--help");
  const std::string manual = read_file(BLENDED_SHAPE_MANUAL);
  const std::string heading = "\\subsection BlendedShapeSecToolFit blended_fit\n\n\\verbatim\n";
  const std::size_t start = manual.find(heading);
  const std::size_t end = start == std::string::npos ? start : manual.find("\\endverbatim", start);
  BS_CHECK(end != std::string::npos, "the manual has no usage block of blended_fit");
  if(end != std::string::npos)
    BS_CHECK(manual.substr(start + heading.size(), end - start - heading.size()) == out,
             "the manual's usage text of blended_fit is not what blended_fit --help prints:\n" << out);
  blended_shape_test::report("blended_fit_manual_usage");
}

} // namespace

int main()
{
  test_json_checker();
  Temp_dir dir("blended_test_fit");
  test_bad_input(dir);
  test_failed_writes(dir);
  test_good_run(dir);
  test_parts_run(dir);
  if(!reduced) // (sanitizer builds: the same code paths as test_parts_run())
    test_two_runs(dir);
  test_strays(dir);
  test_any_scale(dir);
  test_flat_points(dir);
  test_manual_usage(dir);
  blended_shape_test::report("test_blended_fit");
  return blended_shape_test::exit_code();
}
