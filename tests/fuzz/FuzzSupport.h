/* Shared by the fuzz targets: a private scratch folder for inputs that the
 * parsers read from files, and the property every target checks on a
 * rejected input (a one-line message naming the file), so a fuzzer finds
 * unnamed or multi-line errors as well as crashes.
 */
#pragma once

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <string>

/** ASan settings of every fuzz and replay binary (one target per binary).
 *  An impossible malloc (MRPT sizing a matrix from a corrupt rawlog) returns
 *  null, as without ASan, so Eigen / MRPT throw std::bad_alloc and the reader
 *  reports a corrupt file. Leak checks are off: MRPT / libfyaml leak on their
 *  error paths (the unit tests under ASan check our own code for leaks). */
extern "C" const char* __asan_default_options()
{
  return "allocator_may_return_null=1:detect_leaks=0";
}

namespace roislam::fuzz
{
/** A folder of this process, on tmpfs when there is one. */
inline const std::filesystem::path& scratchDir()
{
  static const std::filesystem::path dir = []
  {
    namespace fs = std::filesystem;
    const fs::path base =
        fs::is_directory("/dev/shm") ? fs::path("/dev/shm") : fs::temp_directory_path();
    const fs::path d = base / ("roislam-fuzz-" + std::to_string(::getpid()));
    fs::create_directories(d);
    std::atexit(
        []
        {
          std::error_code ec;
          fs::remove_all(scratchDir(), ec);
        });
    return d;
  }();
  return dir;
}

inline std::string writeScratch(const std::string& name, const uint8_t* data, std::size_t size)
{
  const auto p = scratchDir() / name;
  std::ofstream(p, std::ios::binary | std::ios::trunc)
      .write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  return p.string();
}

/** A rejected input must be explained in one line that contains `mustName`
 *  (the file, usually); anything else aborts, which the fuzzer reports. */
inline void checkRejection(const std::exception& e, const std::string& mustName)
{
  const std::string what = e.what();
  if (what.empty() || what.find('\n') != std::string::npos ||
      (!mustName.empty() && what.find(mustName) == std::string::npos))
  {
    std::fprintf(
        stderr, "bad error message (must be one line naming '%s'):\n%s\n", mustName.c_str(),
        what.c_str());
    std::abort();
  }
}
}  // namespace roislam::fuzz
