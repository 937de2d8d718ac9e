// SPDX-License-Identifier: LGPL-3.0-or-later
// The JSON text of the model files, on top of nlohmann::ordered_json (which
// keeps the members in their order). Reading adds what the model files need
// beyond nlohmann's strict RFC 8259 parser: duplicate member names and
// nesting deeper than 64 levels are errors, every number is a double (-0
// keeps its sign), and messages give the line and column. Writing keeps the
// layout and number format of the files written so far: containers of
// scalars on one line, numbers in the shortest form that reads back to the
// same double (std::to_chars; nlohmann's dump writes 1 as 1.0), so files stay
// byte for byte the same.
#ifndef CGAL_BLENDED_SHAPE_IO_INTERNAL_JSON_TEXT_H
#define CGAL_BLENDED_SHAPE_IO_INTERNAL_JSON_TEXT_H

#include <nlohmann/json.hpp>

#include <charconv>
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <iterator>
#include <locale>
#include <ostream>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <system_error>
#include <vector>

namespace CGAL {
namespace Blended_shapes {
namespace internal {

typedef nlohmann::ordered_json Json;

/// A syntax error: where (1-based line and column, in bytes) and what was expected.
class Json_syntax_error : public std::runtime_error
{
public:
  Json_syntax_error(const std::string& what, std::size_t line, std::size_t column)
    : std::runtime_error("line " + std::to_string(line) + ", column " + std::to_string(column) + ": " + what),
      m_line(line), m_column(column)
  {}
  std::size_t line() const { return m_line; }
  std::size_t column() const { return m_column; }

private:
  std::size_t m_line, m_column;
};

struct Json_limits
{
  std::size_t max_depth = 64;                  // arrays and objects nested deeper are an error
  std::size_t max_size = std::size_t(64) << 20; // larger inputs (bytes) are an error
};

/// "a number", "an object", ... for messages.
inline const char* json_type_description(const Json& v)
{
  if(v.is_null())
    return "null";
  if(v.is_boolean())
    return "a boolean";
  if(v.is_number())
    return "a number";
  if(v.is_string())
    return "a string";
  return v.is_array() ? "an array" : "an object";
}

/// The shortest decimal text that reads back as `x`, whatever the C locale.
/// \throws std::invalid_argument if `x` is not finite (JSON has no NaN or infinity)
inline std::string json_number_text(double x)
{
  if(!std::isfinite(x))
    throw std::invalid_argument("json: cannot write the non-finite number " + std::to_string(x) +
                                " (JSON has no NaN or infinity)");
  char buf[64];
  const std::to_chars_result r = std::to_chars(buf, buf + sizeof(buf), x);
  if(r.ec != std::errc())
    throw std::logic_error("json: std::to_chars failed");
  return std::string(buf, r.ptr);
}

namespace json_parsing {

// A `const char*` that records how far nlohmann's lexer has read: its parser
// callback gets no position, and the checks below need one.
class Tracking_iterator
{
public:
  typedef std::input_iterator_tag iterator_category;
  typedef char value_type;
  typedef std::ptrdiff_t difference_type;
  typedef const char* pointer;
  typedef const char& reference;

  Tracking_iterator(const char* p, const char** furthest) : m_p(p), m_furthest(furthest) {}
  reference operator*() const { return *m_p; }
  Tracking_iterator& operator++()
  {
    *m_furthest = ++m_p;
    return *this;
  }
  Tracking_iterator operator++(int)
  {
    Tracking_iterator old = *this;
    ++*this;
    return old;
  }
  bool operator==(const Tracking_iterator& o) const { return m_p == o.m_p; }
  bool operator!=(const Tracking_iterator& o) const { return m_p != o.m_p; }

private:
  const char* m_p;
  const char** m_furthest;
};

// One parse: the text, how far the lexer has read, the member names of the
// open objects, and the error messages with their positions.
class Parse
{
public:
  Parse(const std::string& text, const Json_limits& limits)
    : m_begin(text.data()), m_end(text.data() + text.size()), m_read(m_begin), m_limits(limits)
  {}

  Json run()
  {
    if(std::size_t(m_end - m_begin) > m_limits.max_size)
      fail_at(m_begin, "the input is larger than " + std::to_string(m_limits.max_size) + " bytes");
    try
    {
      return Json::parse(Tracking_iterator(m_begin, &m_read), Tracking_iterator(m_end, &m_read),
                         [this](int depth, Json::parse_event_t event, Json& parsed) {
                           return on_event(depth, event, parsed);
                         });
    }
    catch(const Json::parse_error& e)
    {
      fail_syntax(e);
    }
    catch(const Json::out_of_range&) // only "number overflow": strtod gave an infinity
    {
      const char* start = token_start(number_end() - 1);
      fail_at(start, "the number " + std::string(start, number_end()) + " is out of the range of a double");
    }
  }

private:
  bool on_event(int depth, Json::parse_event_t event, Json& parsed)
  {
    switch(event)
    {
    case Json::parse_event_t::object_start:
    case Json::parse_event_t::array_start:
      if(std::size_t(depth) >= m_limits.max_depth) // `depth` counts the containers around this one
        fail_at(m_read - 1, "arrays and objects nested deeper than " + std::to_string(m_limits.max_depth) +
                              " levels");
      m_keys.emplace_back();
      break;
    case Json::parse_event_t::object_end:
    case Json::parse_event_t::array_end: m_keys.pop_back(); break;
    case Json::parse_event_t::key:
      if(!m_keys.back().insert(parsed.get<std::string>()).second)
        fail_at(token_start(m_read - 1), "duplicate member name \"" + parsed.get<std::string>() + "\"");
      break;
    case Json::parse_event_t::value:
      if(parsed.is_number_integer())
      {
        // nlohmann reads "-0" as the integer 0; the only integer tokens of
        // zero are "0" and "-0".
        const char* end = number_end();
        const bool minus = end - m_begin >= 2 && end[-2] == '-';
        parsed = (parsed == 0 && minus) ? -0. : parsed.get<double>();
      }
      break;
    }
    return true;
  }

  // The end of the number token just read: the lexer has read one character
  // past it (which cannot be a digit), unless it met the end of the input.
  const char* number_end() const
  {
    return (m_read > m_begin && m_read[-1] >= '0' && m_read[-1] <= '9') ? m_read : m_read - 1;
  }

  // The first character of the token whose last character is at `last`.
  const char* token_start(const char* last) const
  {
    if(last >= m_end || last < m_begin)
      return last;
    if(*last == '"') // back to the opening quote, past escaped quotes
    {
      for(const char* q = last - 1; q >= m_begin; --q)
      {
        std::size_t backslashes = 0;
        while(q - 1 - std::ptrdiff_t(backslashes) >= m_begin && q[-1 - std::ptrdiff_t(backslashes)] == '\\')
          ++backslashes;
        if(*q == '"' && backslashes % 2 == 0)
          return q;
      }
      return last;
    }
    const char* p = last;
    while(p > m_begin && (std::isalnum(static_cast<unsigned char>(p[-1])) || p[-1] == '.' || p[-1] == '+' ||
                          p[-1] == '-'))
      --p;
    return p;
  }

  std::string describe(const char* p) const
  {
    if(p >= m_end)
      return "end of input";
    const unsigned char c = static_cast<unsigned char>(*p);
    if(c >= 0x20 && c < 0x7f)
      return std::string("'") + char(c) + "'";
    char buf[16];
    std::snprintf(buf, sizeof(buf), "byte 0x%x", unsigned(c));
    return buf;
  }

  // nlohmann's messages reworded as the expectation at the place of the
  // error ("expected ... after an array element, found ']'").
  [[noreturn]] void fail_syntax(const Json::parse_error& e) const
  {
    const std::string m = e.what();
    const std::size_t read = m.find("; last read: ");
    const char* at = m_begin + std::min<std::size_t>(e.byte > 0 ? e.byte - 1 : 0, std::size_t(m_end - m_begin));
    std::string what;
    if(read != std::string::npos && m.find("; expected end of input") == std::string::npos)
    { // the lexer's error inside a token
      const std::size_t dash = m.find(" - ");
      what = m.substr(dash + 3, read - dash - 3);
      if(what == "invalid literal")
        what = value_expected;
      else if(what == "invalid string: forbidden character after backslash")
        what = "invalid escape sequence: expected one of \\\" \\\\ \\/ \\b \\f \\n \\r \\t \\u after '\\'";
    }
    else
    {
      at = token_start(at);
      what = expectation(m);
      // nlohmann ends a number at a leading 0 and then meets the next digit.
      const char* zero = (at < m_end && *at == '-') ? at + 1 : at;
      if(zero + 1 < m_end && *zero == '0' && std::isdigit(static_cast<unsigned char>(zero[1])))
      {
        at = zero + 1;
        what = "expected '.', 'e' or the end of the number after a leading 0";
      }
    }
    const char* start = token_start(at < m_end ? at : m_end - 1);
    const bool not_json_number = start < m_end && (*start == 'N' || *start == 'I' ||
                                                   (*start == '-' && start + 1 < m_end && start[1] == 'I'));
    const bool leading_zero = what.find("leading 0") != std::string::npos;
    fail_at(at, what + ", found " + describe(at) +
                  (not_json_number ? " (NaN and Infinity are not JSON numbers)" : "") +
                  (leading_zero ? " (JSON numbers have no leading zeros)" : ""));
  }

  static std::string expectation(const std::string& m)
  {
    if(m.find("; expected end of input") != std::string::npos)
      return "expected end of input after the JSON document";
    if(m.find("while parsing array") != std::string::npos)
      return "expected ',' or ']' after an array element";
    if(m.find("while parsing object key") != std::string::npos)
      return "expected a member name (a string in double quotes)";
    if(m.find("while parsing object separator") != std::string::npos)
      return "expected ':' after the member name";
    if(m.find("while parsing object") != std::string::npos)
      return "expected ',' or '}' after an object member";
    return value_expected;
  }

  [[noreturn]] void fail_at(const char* where, const std::string& what) const
  {
    std::size_t line = 1, column = 1;
    for(const char* q = m_begin; q < where && q < m_end; ++q)
    {
      column = (*q == '\n') ? 1 : column + 1;
      line += (*q == '\n') ? 1 : 0;
    }
    throw Json_syntax_error(what, line, column);
  }

  static constexpr const char* value_expected =
    "expected a JSON value (object, array, string, number, true, false or null)";

  const char* m_begin;
  const char* m_end;
  const char* m_read; // one past the last character the lexer has read
  Json_limits m_limits;
  std::vector<std::set<std::string>> m_keys; // one per open container (empty for arrays)
};

inline void write_string(std::ostream& out, const std::string& s)
{
  out << '"';
  for(const char ch : s)
  {
    const unsigned char c = static_cast<unsigned char>(ch);
    switch(c)
    {
    case '"': out << "\\\""; break;
    case '\\': out << "\\\\"; break;
    case '\n': out << "\\n"; break;
    case '\r': out << "\\r"; break;
    case '\t': out << "\\t"; break;
    case '\b': out << "\\b"; break;
    case '\f': out << "\\f"; break;
    default:
      if(c < 0x20)
      {
        static const char hex[] = "0123456789abcdef";
        out << "\\u00" << hex[c >> 4] << hex[c & 15];
      }
      else
        out << ch;
    }
  }
  out << '"';
}

// On one line: containers of scalars, and small containers of scalars and
// containers of scalars (at most 8 numbers in all).
inline bool fits_on_one_line(const Json& v)
{
  bool flat = true, shallow = true;
  std::size_t scalars = 0;
  for(const Json& e : v)
  {
    if(!e.is_structured() || e.empty())
    {
      ++scalars;
      continue;
    }
    flat = false;
    for(const Json& f : e)
      shallow = shallow && !f.is_structured();
    scalars += e.size();
  }
  return flat || (shallow && scalars <= 8);
}

inline void write_value(std::ostream& out, const Json& v, int indent)
{
  if(v.is_null())
    out << "null";
  else if(v.is_boolean())
    out << (v.get<bool>() ? "true" : "false");
  else if(v.is_number())
    out << json_number_text(v.get<double>());
  else if(v.is_string())
    write_string(out, v.get_ref<const std::string&>());
  if(!v.is_structured())
    return;
  const char open = v.is_object() ? '{' : '[', close = v.is_object() ? '}' : ']';
  const bool flat = fits_on_one_line(v);
  out << open;
  for(auto it = v.begin(); it != v.end(); ++it)
  {
    if(it != v.begin())
      out << (flat ? ", " : ",");
    if(!flat)
      out << '\n' << std::string(std::size_t(indent + 2), ' ');
    if(v.is_object())
    {
      write_string(out, it.key());
      out << ": ";
    }
    write_value(out, *it, indent + 2);
  }
  if(!flat && !v.empty())
    out << '\n' << std::string(std::size_t(indent), ' ');
  out << close;
}

} // namespace json_parsing

/// Parses the JSON document `text` (all of it) into a value whose numbers
/// are all doubles.
/// \throws Json_syntax_error on a syntax error, a duplicate member name, too
///         deep nesting or a too large input
inline Json parse_json(const std::string& text, const Json_limits& limits = Json_limits())
{
  return json_parsing::Parse(text, limits).run();
}

/// Writes `v` indented by two spaces per level, containers of scalars on
/// one line, and a final newline.
/// \throws std::invalid_argument if a number is not finite
inline void write_json(std::ostream& out, const Json& v)
{
  json_parsing::write_value(out, v, 0);
  out << '\n';
}

} // namespace internal
} // namespace Blended_shapes
} // namespace CGAL

#endif // CGAL_BLENDED_SHAPE_IO_INTERNAL_JSON_TEXT_H
