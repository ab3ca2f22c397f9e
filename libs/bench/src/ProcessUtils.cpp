#include "roislam/bench/ProcessUtils.h"

#include <fcntl.h>
#include <mrpt/system/string_utils.h>
#include <signal.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/time.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <thread>

extern char** environ;

namespace fs = std::filesystem;

namespace roislam::bench
{
namespace
{
double toSeconds(const timeval& tv)
{
  return tv.tv_sec + tv.tv_usec * 1e-6;
}
}  // namespace

TProcessResult runProcess(
    const std::vector<std::string>& argv, const std::string& stdoutFile,
    const std::string& stderrFile, double timeoutS)
{
  if (argv.empty())
    throw std::invalid_argument("runProcess: empty command");
  TProcessResult result;

  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
  const int outFlags = O_WRONLY | O_CREAT | O_APPEND;
  posix_spawn_file_actions_addopen(
      &actions, 1, stdoutFile.empty() ? "/dev/null" : stdoutFile.c_str(), outFlags, 0644);
  posix_spawn_file_actions_addopen(
      &actions, 2, stderrFile.empty() ? "/dev/null" : stderrFile.c_str(), outFlags, 0644);

  std::vector<char*> cargv;
  for (const auto& a : argv)
    cargv.push_back(const_cast<char*>(a.c_str()));
  cargv.push_back(nullptr);

  const auto t0 = std::chrono::steady_clock::now();
  pid_t pid = 0;
  const int rc = posix_spawnp(&pid, cargv[0], &actions, nullptr, cargv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (rc != 0)
  {
    result.error = "cannot start " + argv[0] + ": " + std::strerror(rc);
    return result;
  }
  result.started = true;

  int status = 0;
  rusage usage{};
  for (;;)
  {
    const pid_t r = wait4(pid, &status, timeoutS > 0 ? WNOHANG : 0, &usage);
    if (r == pid)
      break;
    if (r < 0 && errno != EINTR)
    {
      result.error = std::string("wait4: ") + std::strerror(errno);
      return result;
    }
    if (r == 0)
    {
      const double elapsed =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      if (elapsed > timeoutS && !result.timedOut)
      {
        result.timedOut = true;
        kill(pid, SIGKILL);
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
  }
  result.wallS = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  result.cpuS = toSeconds(usage.ru_utime) + toSeconds(usage.ru_stime);
  result.maxRssMb = usage.ru_maxrss / 1024.0;  // ru_maxrss is in KiB on Linux
  if (WIFEXITED(status))
    result.exitCode = WEXITSTATUS(status);
  if (WIFSIGNALED(status))
    result.signal = WTERMSIG(status);
  return result;
}

std::string shellQuote(const std::string& word)
{
  if (word.empty())
    return "''";
  bool safe = true;
  for (char c : word)
  {
    const bool ok =
        std::isalnum(static_cast<unsigned char>(c)) || std::strchr("@%+=:,./_-", c) != nullptr;
    if (!ok)
    {
      safe = false;
      break;
    }
  }
  if (safe)
    return word;
  std::string out = "'";
  for (char c : word)
  {
    if (c == '\'')
      out += "'\\''";
    else
      out += c;
  }
  return out + "'";
}

std::string shellJoin(const std::vector<std::string>& argv)
{
  std::string out;
  for (const auto& a : argv)
  {
    if (!out.empty())
      out += ' ';
    out += shellQuote(a);
  }
  return out;
}

std::optional<std::string> findOnPath(const std::string& name)
{
  const char* path = std::getenv("PATH");
  if (!path || name.empty())
    return std::nullopt;
  std::vector<std::string> dirs;
  mrpt::system::tokenize(path, ":", dirs);
  for (const auto& dir : dirs)
  {
    const fs::path p = fs::path(dir) / name;
    if (fs::is_regular_file(p) && access(p.c_str(), X_OK) == 0)
      return p.string();
  }
  return std::nullopt;
}

std::string selfExecutablePath()
{
  std::error_code ec;
  const auto p = fs::read_symlink("/proc/self/exe", ec);
  return ec ? std::string() : p.string();
}

std::string fileTail(const std::string& file, std::size_t lines)
{
  std::ifstream in(file);
  if (!in)
    return {};
  std::deque<std::string> tail;
  std::string line;
  while (std::getline(in, line))
  {
    tail.push_back(line);
    if (tail.size() > lines)
      tail.pop_front();
  }
  std::string out;
  for (const auto& l : tail)
    out += l + "\n";
  return out;
}

}  // namespace roislam::bench
