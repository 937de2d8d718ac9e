// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_BLENDED_SHAPE_INTERNAL_WRITE_FILE_ATOMICALLY_H
#define CGAL_BLENDED_SHAPE_INTERNAL_WRITE_FILE_ATOMICALLY_H

#include <atomic>
#include <chrono>
#include <csignal>
#include <cstddef>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <system_error>

#if !defined(_WIN32)
#include <unistd.h>
#endif

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

// The temporary files that write_file_atomically() is writing now, so that
// a program ended by a signal can remove them (see
// remove_partial_files_on_termination_signals()). A signal handler may
// only touch lock-free atomics and call async-signal-safe functions, hence
// fixed slots of static storage (zero-initialized, no guard) instead of a
// container and a mutex.
class Partial_files
{
public:
  static constexpr std::size_t no_slot = std::size_t(-1);

  // Records `path`; its slot, or no_slot where it cannot be recorded (all
  // slots busy, or a path too long): that file is then not removed on a signal.
  static std::size_t add(const std::string& path)
  {
    if(path.size() >= path_capacity)
      return no_slot;
    for(std::size_t i = 0; i < slot_count; ++i)
    {
      int expected = free_slot;
      if(state(i).compare_exchange_strong(expected, filling))
      {
        std::memcpy(name(i), path.c_str(), path.size() + 1);
        state(i).store(in_use);
        return i;
      }
    }
    return no_slot;
  }

  static void release(std::size_t slot)
  {
    if(slot != no_slot)
      state(slot).store(free_slot);
  }

  // Removes every recorded file (async-signal-safe).
  static void remove_all() noexcept
  {
    for(std::size_t i = 0; i < slot_count; ++i)
      if(state(i).load() == in_use)
      {
#if defined(_WIN32)
        std::remove(name(i));
#else
        ::unlink(name(i));
#endif
      }
  }

private:
  static constexpr std::size_t slot_count = 16;
  static constexpr std::size_t path_capacity = 4096;
  enum { free_slot = 0, filling = 1, in_use = 2 };
  static_assert(std::atomic<int>::is_always_lock_free, "a signal handler needs lock-free atomics");

  static std::atomic<int>& state(std::size_t i)
  {
    static std::atomic<int> states[slot_count];
    return states[i];
  }
  static char* name(std::size_t i)
  {
    static char names[slot_count][path_capacity];
    return names[i];
  }
};

// The handler of remove_partial_files_on_termination_signals(): the partial
// files go, then the signal ends the program as it would have (its exit
// status says which signal).
inline void remove_partial_files_and_reraise(int signal_number)
{
  Partial_files::remove_all();
  std::signal(signal_number, SIG_DFL);
  std::raise(signal_number);
}

// For programs (a library does not install signal handlers): on SIGINT
// (Ctrl-C) and SIGTERM (kill), remove the temporary files being written
// before the program ends, so that no `.partial-*` file is left beside the
// outputs. A signal the program ignores (started under `nohup`) stays ignored.
inline void remove_partial_files_on_termination_signals()
{
  for(const int signal_number : {SIGINT, SIGTERM})
    if(std::signal(signal_number, remove_partial_files_and_reraise) == SIG_IGN)
      std::signal(signal_number, SIG_IGN);
}

// Where writing `filename` lands: a symbolic link is followed (to its
// target, even a dangling one), so that the link stays a link.
inline std::filesystem::path final_target_of(const std::string& filename)
{
  namespace fs = std::filesystem;
  fs::path p(filename);
  std::error_code ec;
  for(int hops = 0; hops < 40 && fs::is_symlink(fs::symlink_status(p, ec)); ++hops)
  {
    const fs::path to = fs::read_symlink(p, ec);
    if(ec)
      break;
    p = to.is_absolute() ? to : p.parent_path() / to;
  }
  return p;
}

// Calls `write(out)` on `out`, opened on `path`; throws with `filename` in
// the message if the stream cannot be opened or fails.
template <class Writer>
void write_stream_to(const std::string& path, const std::string& filename, Writer&& write)
{
  std::ofstream out(path, std::ios::out | std::ios::trunc);
  if(!out)
    throw std::runtime_error("cannot create '" + path + "' to write '" + filename +
                             "': check that the directory exists and is writable");
  write(static_cast<std::ostream&>(out));
  out.flush();
  const bool ok = bool(out);
  out.close();
  if(!ok || out.fail())
    throw std::runtime_error("writing '" + filename + "' failed (disk full or I/O error)");
}

/// Calls `write(std::ostream&)` on a temporary file beside `filename`, then
/// renames it to `filename`: readers never see a half-written file, and a
/// failure (an exception from `write`, a full disk) leaves no file behind.
/// A symbolic link is written through (its target is replaced, the link
/// stays); a device or a pipe (`/dev/stdout`) is written directly.
/// \throws std::invalid_argument if `filename` is empty.
/// \throws std::runtime_error if `filename` is a directory, or the file cannot be created, written or renamed;
///         rethrows what `write` throws.
template <class Writer>
void write_file_atomically(const std::string& filename, Writer&& write)
{
  namespace fs = std::filesystem;
  if(filename.empty())
    throw std::invalid_argument("write_file_atomically: empty output file name; give a path");
  std::error_code ignored;
  const fs::file_status status = fs::status(filename, ignored); // (through the links)
  if(fs::is_directory(status))
    throw std::runtime_error("'" + filename + "' is a directory; give the name of a file to write");
  if(fs::exists(status) && !fs::is_regular_file(status))
  {
    write_stream_to(filename, filename, write); // nothing to rename onto a device or a pipe
    return;
  }
  const fs::path target = final_target_of(filename);

  const std::string tmp = temporary_name_for(target.string());
  // recorded before the file exists, released once it is renamed or removed
  struct Recorded
  {
    std::size_t slot;
    ~Recorded() { Partial_files::release(slot); }
  } recorded{Partial_files::add(tmp)};
  try
  {
    write_stream_to(tmp, filename, write);
  }
  catch(...)
  {
    fs::remove(tmp, ignored);
    throw;
  }
  std::error_code ec;
  fs::rename(tmp, target, ec);
  if(ec)
  {
    fs::remove(tmp, ignored);
    throw std::runtime_error("cannot rename '" + tmp + "' to '" + filename + "': " + ec.message());
  }
}

} // namespace internal
} // namespace Blended_shapes
} // namespace CGAL

#endif // CGAL_BLENDED_SHAPE_INTERNAL_WRITE_FILE_ATOMICALLY_H
