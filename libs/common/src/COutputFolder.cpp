#include "roislam/common/COutputFolder.h"

#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <stdexcept>

namespace fs = std::filesystem;

namespace roislam::common
{
namespace
{
fs::path normalTarget(const std::string& target)
{
  if (target.empty())
    throw std::runtime_error("output dir: no folder given");
  fs::path p = fs::absolute(fs::path(target)).lexically_normal();
  if (p.filename().empty())
    p = p.parent_path();  // trailing '/'
  return p;
}

/** The entries an earlier commit() listed in the folder's manifest. */
std::vector<std::string> manifestEntries(const fs::path& dir)
{
  std::vector<std::string> names;
  std::ifstream in(dir / COutputFolder::kManifest);
  for (std::string line; std::getline(in, line);)
    if (!line.empty() && line[0] != '#')
      names.push_back(line);
  return names;
}

bool isKnown(const std::string& name, const COutputFolder::TOptions& o)
{
  if (o.ownsEverything || name == COutputFolder::kManifest ||
      std::find(o.known.begin(), o.known.end(), name) != o.known.end())
    return true;
  return std::any_of(
      o.knownPrefixes.begin(), o.knownPrefixes.end(),
      [&](const std::string& p) { return !p.empty() && name.rfind(p, 0) == 0; });
}
}  // namespace

void COutputFolder::checkReplaceable(const std::string& dir, const TOptions& options)
{
  std::error_code ec;
  const auto st = fs::status(dir, ec);
  if (!fs::exists(st))
    return;
  if (!fs::is_directory(st))
    throw std::runtime_error("output dir " + dir + ": exists and is not a folder");
  fs::directory_iterator it(dir, ec);
  if (ec)
    throw std::runtime_error("output dir " + dir + ": cannot list (" + ec.message() + ")");
  std::vector<std::string> names;
  for (; it != fs::directory_iterator(); it.increment(ec))
    names.push_back(it->path().filename().string());
  if (names.empty())
    return;
  std::sort(names.begin(), names.end());
  if (!options.overwrite)
    throw std::runtime_error(
        "output dir " + dir + ": not empty (holds " + names.front() +
        "); use --overwrite to replace an earlier output");
  // What an earlier run of ours wrote (its manifest) is ours to replace too.
  TOptions withEarlier = options;
  for (const auto& n : manifestEntries(dir))
    withEarlier.known.push_back(n);
  for (const auto& n : names)
    if (!isKnown(n, withEarlier))
      throw std::runtime_error(
          "output dir " + dir + ": holds " + n +
          ", which this app does not write; not replaced (choose another folder)");
}

COutputFolder::COutputFolder(const std::string& target, const TOptions& options)
    : m_options(options)
{
  const fs::path t = normalTarget(target);
  m_target = t.string();
  m_given = target;
  checkReplaceable(m_given, m_options);
  std::error_code ec;
  fs::create_directories(t.parent_path(), ec);
  if (ec || !fs::is_directory(t.parent_path()))
    throw std::runtime_error(
        "output dir " + target + ": cannot create " + t.parent_path().string() +
        (ec ? " (" + ec.message() + ")" : std::string()));
  const fs::path staging =
      t.parent_path() / ("." + t.filename().string() + ".partial-" + std::to_string(::getpid()));
  fs::remove_all(staging, ec);  // left by an earlier process with our pid
  if (!fs::create_directory(staging, ec) || ec)
    throw std::runtime_error(
        "output dir " + target + ": not writable (cannot create " + staging.string() +
        (ec ? ": " + ec.message() : std::string()) + ")");
  m_staging = staging.string();
  // Creating a folder can succeed where writing a file does not (quota).
  const fs::path probe = staging / ".write-test";
  if (!std::ofstream(probe) || !fs::remove(probe, ec))
  {
    fs::remove_all(staging, ec);
    throw std::runtime_error("output dir " + target + ": not writable");
  }
}

void COutputFolder::writeManifest() const
{
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(m_staging))
    names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  std::ofstream out(fs::path(m_staging) / kManifest);
  out << "# written by roislam (common::COutputFolder): the entries of this output;\n"
         "# --overwrite replaces a folder holding only these\n";
  for (const auto& n : names)
    out << n << "\n";
  out.close();
  if (!out)
    throw std::runtime_error("output dir " + m_given + ": cannot write " + kManifest);
}

COutputFolder::~COutputFolder()
{
  if (m_committed)
    return;
  std::error_code ec;
  fs::remove_all(m_staging, ec);
}

void COutputFolder::commit()
{
  if (m_committed)
    return;
  // The earlier output may have changed while we wrote: check it again.
  checkReplaceable(m_given, m_options);
  std::error_code ec;
  writeManifest();
  const fs::path target(m_target);
  fs::path old;
  if (fs::exists(target))
  {
    old = target.parent_path() /
          ("." + target.filename().string() + ".old-" + std::to_string(::getpid()));
    fs::remove_all(old, ec);
    fs::rename(target, old, ec);
    if (ec)
      throw std::runtime_error(
          "output dir " + m_given + ": cannot move the earlier output aside (" + ec.message() +
          ")");
  }
  fs::rename(m_staging, target, ec);
  if (ec)
  {
    std::error_code ec2;
    if (!old.empty())
      fs::rename(old, target, ec2);  // put the earlier output back
    throw std::runtime_error(
        "output dir " + m_given + ": cannot rename into place (" + ec.message() + ")");
  }
  m_committed = true;
  m_staging = m_target;
  if (!old.empty())
    fs::remove_all(old, ec);
}
}  // namespace roislam::common
