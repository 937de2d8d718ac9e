// SPDX-License-Identifier: LGPL-3.0-or-later
// A small self-contained JSON value, parser and writer for the model files
// (RFC 8259, strict): no comments, no trailing commas, no NaN or Infinity,
// no duplicate keys, nothing after the document. Numbers are doubles read
// with std::from_chars on the exact token and written with std::to_chars in
// the shortest form that reads back to the same double, so a value survives
// a write and a read bit for bit (-0 included), whatever the C locale.
#ifndef CGAL_BLENDED_SHAPE_IO_INTERNAL_JSON_H
#define CGAL_BLENDED_SHAPE_IO_INTERNAL_JSON_H

#include <charconv>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>
#include <locale>
#include <ostream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

namespace CGAL {
namespace Blended_shapes {
namespace internal {
namespace json {

/// A syntax error: where (1-based line and column, in bytes) and what was expected.
class Parse_error : public std::runtime_error
{
public:
  /// `message` already contains the position.
  Parse_error(const std::string& message, std::size_t line, std::size_t column)
    : std::runtime_error(message), m_line(line), m_column(column)
  {}
  /// The line of the error (1-based).
  std::size_t line() const { return m_line; }
  /// The column of the error (1-based, in bytes).
  std::size_t column() const { return m_column; }

private:
  std::size_t m_line, m_column;
};

/// The kinds of JSON values.
enum class Type
{
  Null,
  Boolean,
  Number,
  String,
  Array,
  Object
};

/// The name of a kind of value, for messages ("a number", ...).
inline const char* type_description(Type t)
{
  switch(t)
  {
  case Type::Null: return "null";
  case Type::Boolean: return "a boolean";
  case Type::Number: return "a number";
  case Type::String: return "a string";
  case Type::Array: return "an array";
  default: return "an object";
  }
}

/// A JSON value. Objects keep their members in insertion order.
class Value
{
public:
  /// null
  Value() = default;
  /// A boolean.
  static Value boolean(bool b)
  {
    Value v;
    v.m_type = Type::Boolean;
    v.m_bool = b;
    return v;
  }
  /// A number (must be finite to be written).
  static Value number(double x)
  {
    Value v;
    v.m_type = Type::Number;
    v.m_number = x;
    return v;
  }
  /// A string.
  static Value string(std::string s)
  {
    Value v;
    v.m_type = Type::String;
    v.m_string = std::move(s);
    return v;
  }
  /// An empty array.
  static Value array()
  {
    Value v;
    v.m_type = Type::Array;
    return v;
  }
  /// An empty object.
  static Value object()
  {
    Value v;
    v.m_type = Type::Object;
    return v;
  }

  /// The kind of value.
  Type type() const { return m_type; }
  /// Whether the value is null.
  bool is_null() const { return m_type == Type::Null; }
  /// The boolean (only for Type::Boolean).
  bool as_boolean() const { return m_bool; }
  /// The number (only for Type::Number).
  double as_number() const { return m_number; }
  /// The string (only for Type::String).
  const std::string& as_string() const { return m_string; }

  /// The number of elements of an array or members of an object.
  std::size_t size() const { return m_values.size(); }
  /// Element `i` of an array, or the value of member `i` of an object.
  const Value& operator[](std::size_t i) const { return m_values.at(i); }
  /// The key of member `i` of an object.
  const std::string& key(std::size_t i) const { return m_keys.at(i); }
  /// The member `key` of an object, or null if there is none.
  const Value* find(const std::string& key) const
  {
    for(std::size_t i = 0; i < m_keys.size(); ++i)
      if(m_keys[i] == key)
        return &m_values[i];
    return nullptr;
  }

  /// Appends `v` to an array; returns *this.
  Value& push_back(Value v)
  {
    if(m_type != Type::Array)
      throw std::logic_error("json::Value::push_back: not an array");
    m_values.push_back(std::move(v));
    return *this;
  }
  /// Appends the member `key: v` to an object (`key` must be new); returns *this.
  Value& set(const std::string& key, Value v)
  {
    if(m_type != Type::Object)
      throw std::logic_error("json::Value::set: not an object");
    if(find(key))
      throw std::logic_error("json::Value::set: duplicate key '" + key + "'");
    m_keys.push_back(key);
    m_values.push_back(std::move(v));
    return *this;
  }

private:
  Type m_type = Type::Null;
  bool m_bool = false;
  double m_number = 0.;
  std::string m_string;
  std::vector<std::string> m_keys; // objects only
  std::vector<Value> m_values;     // array elements or member values
};

/// Limits of the parser.
struct Parse_limits
{
  std::size_t max_depth = 64;                  ///< arrays and objects nested deeper are an error
  std::size_t max_size = std::size_t(64) << 20; ///< larger inputs (bytes) are an error
};

/// The shortest decimal text that reads back as `x` (JSON number syntax).
/// \throws std::invalid_argument if `x` is not finite (JSON has no NaN or infinity)
inline std::string format_number(double x)
{
  if(!std::isfinite(x))
    throw std::invalid_argument("json: cannot write the non-finite number " + std::to_string(x) +
                                " (JSON has no NaN or infinity)");
#if defined(__cpp_lib_to_chars) && __cpp_lib_to_chars >= 201611L
  char buf[64];
  const std::to_chars_result r = std::to_chars(buf, buf + sizeof(buf), x);
  if(r.ec != std::errc())
    throw std::logic_error("json: std::to_chars failed");
  return std::string(buf, r.ptr);
#else
  std::ostringstream s;
  s.imbue(std::locale::classic());
  s.precision(17);
  s << x;
  return s.str();
#endif
}

namespace detail {

class Parser
{
public:
  Parser(const char* begin, const char* end, const Parse_limits& limits)
    : m_begin(begin), m_p(begin), m_end(end), m_limits(limits)
  {}

  Value parse_document()
  {
    if(std::size_t(m_end - m_begin) > m_limits.max_size)
      fail_at(m_begin, "the input is larger than " + std::to_string(m_limits.max_size) + " bytes");
    // An UTF-8 byte order mark is allowed (RFC 8259, sec. 8.1) and skipped.
    if(m_end - m_p >= 3 && std::memcmp(m_p, "\xEF\xBB\xBF", 3) == 0)
      m_p += 3;
    skip_space();
    if(m_p == m_end)
      fail("expected a JSON value, found end of input (the input is empty)");
    Value v = parse_value(0);
    skip_space();
    if(m_p != m_end)
      fail("expected end of input after the JSON document, found " + describe_here());
    return v;
  }

private:
  [[noreturn]] void fail(const std::string& what) const { fail_at(m_p, what); }

  [[noreturn]] void fail_at(const char* where, const std::string& what) const
  {
    std::size_t line = 1, column = 1;
    for(const char* q = m_begin; q < where; ++q)
    {
      if(*q == '\n')
      {
        ++line;
        column = 1;
      }
      else
        ++column;
    }
    throw Parse_error("line " + std::to_string(line) + ", column " + std::to_string(column) + ": " + what, line,
                      column);
  }

  std::string describe_here() const
  {
    if(m_p == m_end)
      return "end of input";
    const unsigned char c = static_cast<unsigned char>(*m_p);
    if(c >= 0x20 && c < 0x7f)
      return std::string("'") + char(c) + "'";
    std::ostringstream s;
    s << "byte 0x" << std::hex << unsigned(c);
    return s.str();
  }

  void skip_space()
  {
    while(m_p != m_end && (*m_p == ' ' || *m_p == '\t' || *m_p == '\n' || *m_p == '\r'))
      ++m_p;
  }

  bool literal(const char* word)
  {
    const std::size_t n = std::strlen(word), left = std::size_t(m_end - m_p);
    if(left >= n && std::memcmp(m_p, word, n) == 0)
    {
      m_p += n;
      return true;
    }
    if(left < n && std::memcmp(m_p, word, left) == 0)
      fail_at(m_end, std::string("expected '") + word + "', found end of input");
    return false;
  }

  Value parse_value(std::size_t depth)
  {
    skip_space();
    if(m_p == m_end)
      fail("expected a JSON value, found end of input");
    switch(*m_p)
    {
    case '{': return parse_object(depth + 1);
    case '[': return parse_array(depth + 1);
    case '"': return Value::string(parse_string());
    case 't':
      if(literal("true"))
        return Value::boolean(true);
      break;
    case 'f':
      if(literal("false"))
        return Value::boolean(false);
      break;
    case 'n':
      if(literal("null"))
        return Value();
      break;
    default:
      if(*m_p == '-' || (*m_p >= '0' && *m_p <= '9'))
        return Value::number(parse_number());
    }
    if(*m_p == 'N' || *m_p == 'I' || (*m_p == '-' && m_p + 1 != m_end && m_p[1] == 'I'))
      fail("expected a JSON value, found " + describe_here() + " (NaN and Infinity are not JSON numbers)");
    fail("expected a JSON value (object, array, string, number, true, false or null), found " + describe_here());
  }

  void check_depth(std::size_t depth) const
  {
    if(depth > m_limits.max_depth)
      fail("arrays and objects nested deeper than " + std::to_string(m_limits.max_depth) + " levels");
  }

  Value parse_array(std::size_t depth)
  {
    check_depth(depth);
    ++m_p; // '['
    Value a = Value::array();
    skip_space();
    if(m_p != m_end && *m_p == ']')
    {
      ++m_p;
      return a;
    }
    for(;;)
    {
      a.push_back(parse_value(depth));
      skip_space();
      if(m_p == m_end)
        fail("expected ',' or ']' after an array element, found end of input");
      if(*m_p == ',')
      {
        ++m_p;
        continue;
      }
      if(*m_p == ']')
      {
        ++m_p;
        return a;
      }
      fail("expected ',' or ']' after an array element, found " + describe_here());
    }
  }

  Value parse_object(std::size_t depth)
  {
    check_depth(depth);
    ++m_p; // '{'
    Value o = Value::object();
    skip_space();
    if(m_p != m_end && *m_p == '}')
    {
      ++m_p;
      return o;
    }
    for(;;)
    {
      skip_space();
      if(m_p == m_end || *m_p != '"')
        fail("expected a member name (a string in double quotes), found " + describe_here());
      const char* key_start = m_p;
      std::string key = parse_string();
      if(o.find(key))
        fail_at(key_start, "duplicate member name \"" + key + "\"");
      skip_space();
      if(m_p == m_end || *m_p != ':')
        fail("expected ':' after the member name \"" + key + "\", found " + describe_here());
      ++m_p;
      Value v = parse_value(depth);
      o.set(key, std::move(v));
      skip_space();
      if(m_p == m_end)
        fail("expected ',' or '}' after an object member, found end of input");
      if(*m_p == ',')
      {
        ++m_p;
        continue;
      }
      if(*m_p == '}')
      {
        ++m_p;
        return o;
      }
      fail("expected ',' or '}' after an object member, found " + describe_here());
    }
  }

  static void append_utf8(std::string& s, std::uint32_t c)
  {
    if(c < 0x80)
      s += char(c);
    else if(c < 0x800)
    {
      s += char(0xC0 | (c >> 6));
      s += char(0x80 | (c & 0x3F));
    }
    else if(c < 0x10000)
    {
      s += char(0xE0 | (c >> 12));
      s += char(0x80 | ((c >> 6) & 0x3F));
      s += char(0x80 | (c & 0x3F));
    }
    else
    {
      s += char(0xF0 | (c >> 18));
      s += char(0x80 | ((c >> 12) & 0x3F));
      s += char(0x80 | ((c >> 6) & 0x3F));
      s += char(0x80 | (c & 0x3F));
    }
  }

  std::uint32_t parse_hex4()
  {
    if(m_end - m_p < 4)
      fail("expected 4 hexadecimal digits after \\u, found end of input");
    std::uint32_t v = 0;
    for(int i = 0; i < 4; ++i, ++m_p)
    {
      const char c = *m_p;
      v <<= 4;
      if(c >= '0' && c <= '9')
        v |= std::uint32_t(c - '0');
      else if(c >= 'a' && c <= 'f')
        v |= std::uint32_t(c - 'a' + 10);
      else if(c >= 'A' && c <= 'F')
        v |= std::uint32_t(c - 'A' + 10);
      else
        fail("expected a hexadecimal digit in a \\u escape, found " + describe_here());
    }
    return v;
  }

  std::string parse_string()
  {
    ++m_p; // '"'
    std::string s;
    for(;;)
    {
      if(m_p == m_end)
        fail("expected '\"' to close the string, found end of input");
      const unsigned char c = static_cast<unsigned char>(*m_p);
      if(c == '"')
      {
        ++m_p;
        return s;
      }
      if(c < 0x20)
        fail("expected '\"' or a character of a string, found the control character " + describe_here() +
             " (escape it)");
      if(c != '\\')
      {
        s += char(c);
        ++m_p;
        continue;
      }
      ++m_p;
      if(m_p == m_end)
        fail("expected an escape character after '\\', found end of input");
      const char e = *m_p++;
      switch(e)
      {
      case '"': s += '"'; break;
      case '\\': s += '\\'; break;
      case '/': s += '/'; break;
      case 'b': s += '\b'; break;
      case 'f': s += '\f'; break;
      case 'n': s += '\n'; break;
      case 'r': s += '\r'; break;
      case 't': s += '\t'; break;
      case 'u':
      {
        std::uint32_t u = parse_hex4();
        if(u >= 0xD800 && u < 0xDC00)
        {
          if(!(m_end - m_p >= 2 && m_p[0] == '\\' && m_p[1] == 'u'))
            fail("expected a low surrogate \\uDC00-\\uDFFF after a high surrogate");
          m_p += 2;
          const std::uint32_t lo = parse_hex4();
          if(!(lo >= 0xDC00 && lo < 0xE000))
            fail("expected a low surrogate \\uDC00-\\uDFFF after a high surrogate");
          u = 0x10000 + ((u - 0xD800) << 10) + (lo - 0xDC00);
        }
        else if(u >= 0xDC00 && u < 0xE000)
          fail("unexpected low surrogate in a \\u escape");
        append_utf8(s, u);
        break;
      }
      default:
        --m_p;
        fail("invalid escape sequence: expected one of \\\" \\\\ \\/ \\b \\f \\n \\r \\t \\u after '\\', found " +
             describe_here());
      }
    }
  }

  static bool digit(char c) { return c >= '0' && c <= '9'; }

  // The grammar of RFC 8259 checked here; the exact token then goes to
  // std::from_chars (correctly rounded, locale independent).
  double parse_number()
  {
    const char* start = m_p;
    if(*m_p == '-')
      ++m_p;
    if(m_p != m_end && (*m_p == 'I' || *m_p == 'N' || *m_p == 'i' || *m_p == 'n'))
      fail("expected a digit in a number, found " + describe_here() + " (NaN and Infinity are not JSON numbers)");
    if(m_p == m_end || !digit(*m_p))
      fail("expected a digit in a number, found " + describe_here());
    if(*m_p == '0')
    {
      ++m_p;
      if(m_p != m_end && digit(*m_p))
        fail("expected '.', 'e' or the end of the number after a leading 0, found " + describe_here() +
             " (JSON numbers have no leading zeros)");
    }
    else
      while(m_p != m_end && digit(*m_p))
        ++m_p;
    if(m_p != m_end && *m_p == '.')
    {
      ++m_p;
      if(m_p == m_end || !digit(*m_p))
        fail("expected a digit after the decimal point, found " + describe_here());
      while(m_p != m_end && digit(*m_p))
        ++m_p;
    }
    if(m_p != m_end && (*m_p == 'e' || *m_p == 'E'))
    {
      ++m_p;
      if(m_p != m_end && (*m_p == '+' || *m_p == '-'))
        ++m_p;
      if(m_p == m_end || !digit(*m_p))
        fail("expected a digit in the exponent of a number, found " + describe_here());
      while(m_p != m_end && digit(*m_p))
        ++m_p;
    }
    const std::string token(start, m_p);
    double x = 0.;
#if defined(__cpp_lib_to_chars) && __cpp_lib_to_chars >= 201611L
    const std::from_chars_result r = std::from_chars(token.data(), token.data() + token.size(), x);
    const bool ok = (r.ec == std::errc() && r.ptr == token.data() + token.size());
#else
    std::istringstream in(token);
    in.imbue(std::locale::classic());
    in >> x;
    const bool ok = bool(in) && in.peek() == std::char_traits<char>::eof();
#endif
    if(!ok || !std::isfinite(x))
      fail_at(start, "the number " + token + " is out of the range of a double");
    return x;
  }

  const char* m_begin;
  const char* m_p;
  const char* m_end;
  Parse_limits m_limits;
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

inline bool is_container(const Value& v) { return v.type() == Type::Array || v.type() == Type::Object; }

inline void write_value(std::ostream& out, const Value& v, int indent)
{
  switch(v.type())
  {
  case Type::Null: out << "null"; return;
  case Type::Boolean: out << (v.as_boolean() ? "true" : "false"); return;
  case Type::Number: out << format_number(v.as_number()); return;
  case Type::String: write_string(out, v.as_string()); return;
  default: break;
  }
  const bool object = v.type() == Type::Object;
  const char open = object ? '{' : '[', close = object ? '}' : ']';
  if(v.size() == 0)
  {
    out << open << close;
    return;
  }
  // On one line: containers of scalars, and small containers of scalars and
  // containers of scalars (at most 8 numbers in all). Others: one element per line.
  bool flat = true, shallow = true;
  std::size_t scalars = 0;
  for(std::size_t i = 0; i < v.size(); ++i)
  {
    if(!is_container(v[i]) || v[i].size() == 0)
    {
      ++scalars;
      continue;
    }
    flat = false;
    for(std::size_t j = 0; j < v[i].size(); ++j)
      shallow = shallow && !is_container(v[i][j]);
    scalars += v[i].size();
  }
  flat = flat || (shallow && scalars <= 8);
  out << open;
  for(std::size_t i = 0; i < v.size(); ++i)
  {
    if(i > 0)
      out << ',';
    if(flat)
      out << (i > 0 ? " " : "");
    else
      out << '\n' << std::string(std::size_t(indent + 2), ' ');
    if(object)
    {
      write_string(out, v.key(i));
      out << ": ";
    }
    write_value(out, v[i], indent + 2);
  }
  if(!flat)
    out << '\n' << std::string(std::size_t(indent), ' ');
  out << close;
}

} // namespace detail

/// Parses the JSON document `text` (all of it).
/// \throws Parse_error on a syntax error, too deep nesting or a too large input
inline Value parse(const std::string& text, const Parse_limits& limits = Parse_limits())
{
  return detail::Parser(text.data(), text.data() + text.size(), limits).parse_document();
}

/// Writes `v` indented by two spaces per level, containers of scalars on
/// one line, and a final newline.
/// \throws std::invalid_argument if a number is not finite
inline void write(std::ostream& out, const Value& v)
{
  detail::write_value(out, v, 0);
  out << '\n';
}

} // namespace json
} // namespace internal
} // namespace Blended_shapes
} // namespace CGAL

#endif // CGAL_BLENDED_SHAPE_IO_INTERNAL_JSON_H
