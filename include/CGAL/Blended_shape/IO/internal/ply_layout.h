// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_BLENDED_SHAPE_IO_INTERNAL_PLY_LAYOUT_H
#define CGAL_BLENDED_SHAPE_IO_INTERNAL_PLY_LAYOUT_H

#include <CGAL/Blended_shape/IO/Input_error.h>

#include <cctype>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <istream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

namespace CGAL {
namespace Blended_shapes {
namespace internal {

// What a PLY header declares: the encoding and the elements with their
// properties, as the header says them (nothing of the data is read).
struct Ply_property
{
  std::string name;
  std::string type;            // of the value, or of a list's entries
  std::string count_type;      // of a list's length; empty for a scalar
  std::size_t size = 0;        // the bytes of `type`
  std::size_t count_size = 0;  // the bytes of `count_type`; 0 for a scalar
  bool signed_count = false;   // whether `count_type` is signed
  bool is_list() const { return count_size != 0; }
};

struct Ply_element
{
  std::string name;
  std::uintmax_t count = 0;
  std::vector<Ply_property> properties;
};

struct Ply_layout
{
  enum Encoding { Ascii, Binary_little_endian, Binary_big_endian };
  Encoding encoding = Ascii;
  std::vector<Ply_element> elements;
};

// The size in bytes of a PLY number type (the names CGAL's reader knows), 0 if unknown.
inline std::size_t ply_type_size(const std::string& type)
{
  if(type == "char" || type == "uchar" || type == "int8" || type == "uint8")
    return 1;
  if(type == "short" || type == "ushort" || type == "int16" || type == "uint16")
    return 2;
  if(type == "int" || type == "uint" || type == "int32" || type == "uint32" || type == "float" || type == "float32")
    return 4;
  if(type == "double" || type == "float64")
    return 8;
  return 0;
}

// Whether a PLY number type is a floating-point one (float, double and their aliases).
inline bool is_ply_floating_type(const std::string& type)
{
  return type == "float" || type == "float32" || type == "double" || type == "float64";
}

// Reads the header from the start of `in`, which is left at the first byte
// of the data. `where` starts the messages (the function and the file).
// Throws Input_error (Malformed_content) on a file that does not start with
// "ply", an unknown encoding or number type, a malformed element or
// property line, or a header without end_header.
inline Ply_layout read_ply_layout(std::istream& in, const std::string& where)
{
  const auto malformed = [&](const std::string& what) {
    return Input_error(Input_error::Malformed_content, where + ": " + what);
  };
  std::string line;
  std::getline(in, line);
  if(line != "ply" && line != "ply\r")
    throw Input_error(Input_error::Malformed_content,
                      where + " is not a PLY file (its first line is not 'ply'); check the file, or give it "
                              "the extension of its real format");
  Ply_layout layout;
  bool has_format = false;
  while(std::getline(in, line))
  {
    std::istringstream words(line);
    std::string keyword;
    words >> keyword;
    if(keyword == "end_header")
    {
      if(!has_format)
        throw malformed("the PLY header has no 'format' line; the file is corrupt");
      return layout;
    }
    if(keyword == "format")
    {
      std::string encoding;
      words >> encoding;
      if(encoding == "ascii")
        layout.encoding = Ply_layout::Ascii;
      else if(encoding == "binary_little_endian")
        layout.encoding = Ply_layout::Binary_little_endian;
      else if(encoding == "binary_big_endian")
        layout.encoding = Ply_layout::Binary_big_endian;
      else
        throw malformed("the PLY format '" + encoding + "' is unknown (ascii, binary_little_endian or "
                        "binary_big_endian)");
      has_format = true;
    }
    else if(keyword == "element")
    {
      Ply_element e;
      std::string count;
      words >> e.name >> count;
      char* end = nullptr;
      e.count = std::strtoull(count.c_str(), &end, 10);
      if(e.name.empty() || count.empty() || count[0] == '-' || *end != '\0' ||
         e.count == std::numeric_limits<unsigned long long>::max())
        throw malformed("the PLY header line '" + line + "' does not give an element's name and count");
      layout.elements.push_back(e);
    }
    else if(keyword == "property")
    {
      Ply_property p;
      words >> p.type;
      if(p.type == "list")
        words >> p.count_type >> p.type;
      words >> p.name;
      if(layout.elements.empty() || p.name.empty())
        throw malformed("the PLY header line '" + line + "' is not a property of an element");
      for(const std::string& type : {p.type, p.count_type})
        if(!type.empty() && ply_type_size(type) == 0)
          throw malformed("the PLY property '" + p.name + "' has the unknown type '" + type +
                          "' (known: char, uchar, short, ushort, int, uint, float, double and "
                          "int8 to float64)");
      p.size = ply_type_size(p.type);
      if(!p.count_type.empty())
      {
        if(is_ply_floating_type(p.count_type))
          throw malformed("the length of the PLY list '" + p.name + "' has the type '" + p.count_type +
                          "'; a list length must be an integer type");
        p.count_size = ply_type_size(p.count_type);
        p.signed_count = p.count_type == "char" || p.count_type == "int8" || p.count_type == "short" ||
                         p.count_type == "int16" || p.count_type == "int" || p.count_type == "int32";
      }
      layout.elements.back().properties.push_back(p);
    }
  }
  throw malformed("the PLY header has no 'end_header' line; the file is corrupt or truncated");
}

// Walks the data of a PLY file, `in` at its first byte, `bytes_left` the
// bytes from there to the end of the file: every element the header
// declares must be there, and each list no longer than what is left of the
// file could hold. CGAL's reader trusts a list's length: it allocates it,
// then reads that many values, so a corrupt length (2^31 in a 60-byte file)
// takes gigabytes and minutes before the reader fails. This walk costs one
// pass over the data without converting a value (binary: only the lists'
// lengths are read).
inline void check_ply_data(std::istream& in, std::uintmax_t bytes_left, const Ply_layout& layout,
                           const std::string& where)
{
  const auto truncated = [&](const Ply_element& e, std::uintmax_t k) {
    return Input_error(Input_error::Malformed_content,
                       where + ": the PLY data ends inside " + e.name + " " + std::to_string(k) +
                         " (counting from 0) of the " + std::to_string(e.count) +
                         " the header declares; the file is truncated or its header is wrong");
  };
  const auto too_long = [&](const Ply_element& e, std::uintmax_t k, const Ply_property& p, const std::string& length) {
    return Input_error(Input_error::Malformed_content,
                       where + ": the list '" + p.name + "' of " + e.name + " " + std::to_string(k) +
                         " (counting from 0) claims " + length + " entries, more than the rest of the "
                         "file holds; the file is corrupt");
  };
  if(layout.encoding == Ply_layout::Ascii)
  {
    std::streambuf& buffer = *in.rdbuf();
    const int eof = std::char_traits<char>::eof();
    // the next word of the data, or false at the end of the file
    std::string word;
    const auto next_word = [&]() {
      int c = buffer.sgetc();
      while(c != eof && std::isspace(static_cast<unsigned char>(c)))
        c = buffer.snextc();
      word.clear();
      while(c != eof && !std::isspace(static_cast<unsigned char>(c)))
      {
        word.push_back(char(c));
        c = buffer.snextc();
      }
      return !word.empty();
    };
    for(const Ply_element& e : layout.elements)
      for(std::uintmax_t k = 0; k < e.count; ++k)
        for(const Ply_property& p : e.properties)
        {
          if(!next_word())
            throw truncated(e, k);
          if(!p.is_list())
            continue;
          char* end = nullptr;
          const std::uintmax_t length = std::strtoull(word.c_str(), &end, 10);
          if(word[0] == '-' || *end != '\0')
            throw Input_error(Input_error::Malformed_content,
                              where + ": the list '" + p.name + "' of " + e.name + " " + std::to_string(k) +
                                " has the length '" + word + "', not a count; the file is corrupt");
          const std::string length_word = word;
          for(std::uintmax_t j = 0; j < length; ++j)
            if(!next_word()) // (an entry takes at least two bytes: a digit and a space)
              throw length > bytes_left / 2 ? too_long(e, k, p, length_word) : truncated(e, k);
        }
    return;
  }
  const bool big_endian = layout.encoding == Ply_layout::Binary_big_endian;
  for(const Ply_element& e : layout.elements)
  {
    std::uintmax_t record = 0; // the bytes of one instance, if it has no list
    bool has_list = false;
    for(const Ply_property& p : e.properties)
    {
      has_list = has_list || p.is_list();
      record += p.size;
    }
    if(!has_list)
    {
      if(record != 0 && e.count > bytes_left / record)
        throw truncated(e, bytes_left / record);
      bytes_left -= e.count * record;
      in.ignore(std::streamsize(e.count * record));
      continue;
    }
    std::uintmax_t pending = 0; // the bytes passed over since the last list length read
    for(std::uintmax_t k = 0; k < e.count; ++k)
      for(const Ply_property& p : e.properties)
      {
        const std::size_t head = p.is_list() ? p.count_size : p.size;
        if(bytes_left < head)
          throw truncated(e, k);
        bytes_left -= head;
        if(!p.is_list())
        {
          pending += head;
          continue;
        }
        in.ignore(std::streamsize(pending));
        pending = 0;
        unsigned char bytes[4] = {0, 0, 0, 0};
        in.read(reinterpret_cast<char*>(bytes), std::streamsize(head));
        std::uintmax_t length = 0;
        for(std::size_t b = 0; b < head; ++b) // the bytes from the most significant one
          length = (length << 8) | bytes[big_endian ? b : head - 1 - b];
        if(p.signed_count && (length >> (8 * head - 1)) != 0)
          throw Input_error(Input_error::Malformed_content,
                            where + ": the list '" + p.name + "' of " + e.name + " " + std::to_string(k) +
                              " has a negative length; the file is corrupt");
        if(length > bytes_left / p.size)
          throw too_long(e, k, p, std::to_string(length));
        bytes_left -= length * p.size;
        pending += length * p.size;
      }
    in.ignore(std::streamsize(pending));
  }
}

} // namespace internal
} // namespace Blended_shapes
} // namespace CGAL

#endif // CGAL_BLENDED_SHAPE_IO_INTERNAL_PLY_LAYOUT_H
