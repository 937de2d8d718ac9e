// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_BLENDED_SHAPE_INTERNAL_WRITE_FILE_ATOMICALLY_H
#define CGAL_BLENDED_SHAPE_INTERNAL_WRITE_FILE_ATOMICALLY_H

#include <atomic>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <system_error>

namespace CGAL {
namespace Blended_shapes {
namespace internal {

// A name next to `filename` (same directory, so the final rename stays on one
// file system) that no other writer of this process or another one is using.
inline std::string temporary_name_for(const std::string& filename)
{
  static std::atomic<unsigned long> counter(0);
  std::ostringstream s;
  s << filename << ".partial-" << std::hex
    << std::chrono::steady_clock::now().time_since_epoch().count() << '-'
    << counter.fetch_add(1);
  return s.str();
}

/// Calls `write(std::ostream&)` on a temporary file beside `filename`, then
/// renames it to `filename`: readers never see a half-written file, and a
/// failure (an exception from `write`, a full disk) leaves no file behind.
/// \throws std::runtime_error if the file cannot be created, written or renamed;
///         rethrows what `write` throws.
template <class Writer>
void write_file_atomically(const std::string& filename, Writer&& write)
{
  if(filename.empty())
    throw std::invalid_argument("write_file_atomically: empty output file name; give a path");

  const std::string tmp = temporary_name_for(filename);
  std::error_code ignored;
  {
    std::ofstream out(tmp, std::ios::out | std::ios::trunc);
    if(!out)
      throw std::runtime_error("cannot create '" + tmp + "' to write '" + filename +
                               "': check that the directory exists and is writable");
    try
    {
      write(static_cast<std::ostream&>(out));
      out.flush();
    }
    catch(...)
    {
      out.close();
      std::filesystem::remove(tmp, ignored);
      throw;
    }
    const bool ok = bool(out);
    out.close();
    if(!ok || out.fail())
    {
      std::filesystem::remove(tmp, ignored);
      throw std::runtime_error("writing '" + filename +
                               "' failed (disk full or I/O error); nothing was written");
    }
  }
  std::error_code ec;
  std::filesystem::rename(tmp, filename, ec);
  if(ec)
  {
    std::filesystem::remove(tmp, ignored);
    throw std::runtime_error("cannot rename '" + tmp + "' to '" + filename + "': " + ec.message());
  }
}

} // namespace internal
} // namespace Blended_shapes
} // namespace CGAL

#endif // CGAL_BLENDED_SHAPE_INTERNAL_WRITE_FILE_ATOMICALLY_H
