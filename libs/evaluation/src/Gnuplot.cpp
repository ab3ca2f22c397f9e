#include "Gnuplot.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <stdexcept>

extern char** environ;

namespace roislam::evaluation::gnuplot
{
namespace fs = std::filesystem;

namespace
{
/** Runs `program script`, output to log; returns the exit status or throws
 *  when the program cannot be started. */
int runProgram(const std::string& program, const fs::path& script, const fs::path& log)
{
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&actions, 1, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&actions, 1, 2);
  std::string arg0 = program, arg1 = script.string();
  char* argv[] = {arg0.data(), arg1.data(), nullptr};
  pid_t pid = 0;
  const int rc = ::posix_spawnp(&pid, program.c_str(), &actions, nullptr, argv, environ);
  posix_spawn_file_actions_destroy(&actions);
  if (rc == ENOENT)
    throw std::runtime_error(
        "'" + program + "' not found in PATH: plots need gnuplot (Debian package gnuplot-nox)");
  if (rc != 0)
    throw std::runtime_error("cannot run '" + program + "': " + std::strerror(rc));
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0)
  {
    if (errno != EINTR)
      throw std::runtime_error("waiting for '" + program + "' failed");
  }
  if (WIFEXITED(status))
    return WEXITSTATUS(status);
  return 128 + (WIFSIGNALED(status) ? WTERMSIG(status) : 0);
}

std::string firstErrorLine(const fs::path& log)
{
  std::ifstream in(log);
  std::string line, last;
  while (std::getline(in, line))
  {
    if (line.find_first_not_of(" \t^") == std::string::npos)
      continue;
    last = line;
    if (line.find("rror") != std::string::npos)
      return line;
  }
  return last;
}
}  // namespace

TTempDir::TTempDir()
{
  std::string tmpl = (fs::temp_directory_path() / "roislam_plot_XXXXXX").string();
  if (!::mkdtemp(tmpl.data()))
    throw std::runtime_error("cannot create a temporary folder: " + tmpl);
  path = tmpl;
}

TTempDir::~TTempDir()
{
  std::error_code ec;
  fs::remove_all(path, ec);
}

std::string quoted(const std::string& s)
{
  std::string out = "'";
  for (char c : s)
  {
    if (c == '\'')
      out += "''";
    else if (c == '\n' || c == '\r')
      out += ' ';
    else
      out += c;
  }
  return out + "'";
}

std::string pngTerminal(int width, int height, const fs::path& image)
{
  const std::string size = std::to_string(width) + "," + std::to_string(height);
  return "if (strstrt(GPVAL_TERMINALS, 'pngcairo') > 0) {\n"
         "  set terminal pngcairo size " +
         size +
         " noenhanced font 'sans,10'\n"
         "} else {\n"
         "  set terminal png size " +
         size +
         " noenhanced\n"
         "}\n"
         "set output " +
         quoted(image.string()) + "\n";
}

void renderPng(
    const std::string& program, const fs::path& script, const fs::path& image,
    const std::string& pngFile)
{
  const fs::path log = script.parent_path() / (script.stem().string() + ".log");
  const int status = runProgram(program, script, log);
  if (status != 0 || !fs::exists(image) || fs::file_size(image) == 0)
    throw std::runtime_error(
        pngFile + ": gnuplot failed (exit " + std::to_string(status) + "): " + firstErrorLine(log));

  const std::string partial = pngFile + ".tmp" + std::to_string(::getpid());
  std::error_code ec;
  fs::copy_file(image, partial, fs::copy_options::overwrite_existing, ec);
  if (!ec)
    fs::rename(partial, pngFile, ec);
  if (ec)
  {
    std::error_code ignored;
    fs::remove(partial, ignored);
    throw std::runtime_error(pngFile + ": cannot write (" + ec.message() + ")");
  }
}
}  // namespace roislam::evaluation::gnuplot
