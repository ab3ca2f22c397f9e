#include "roislam/bench/CBenchRunner.h"

#include <roislam/bench/ProcessUtils.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <ctime>
#include <filesystem>
#include <map>
#include <mutex>
#include <stdexcept>
#include <thread>

namespace fs = std::filesystem;

namespace roislam::bench
{
namespace
{
std::string utcNow()
{
  const std::time_t t = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&t, &tm);
  char buf[32];
  std::strftime(buf, sizeof(buf), "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
}

std::string hostName()
{
  char buf[256] = {0};
  if (gethostname(buf, sizeof(buf) - 1) != 0)
    return {};
  return buf;
}

std::string firstLine(const std::string& s)
{
  // The last non-empty line of a stderr tail is usually the error message.
  std::string last;
  std::size_t pos = 0;
  while (pos < s.size())
  {
    const auto e = s.find('\n', pos);
    const std::string l = s.substr(pos, e == std::string::npos ? std::string::npos : e - pos);
    if (!l.empty())
      last = l;
    if (e == std::string::npos)
      break;
    pos = e + 1;
  }
  return last;
}
}  // namespace

CBenchRunner::CBenchRunner() : CBenchRunner(TOptions()) {}

CBenchRunner::CBenchRunner(const TOptions& options) : m_options(options)
{
  if (m_options.jobs < 1)
    throw std::invalid_argument("jobs: must be >= 1");
}

std::optional<TRunRecord> CBenchRunner::loadCompleted(const std::string& runDir)
{
  const fs::path file = fs::path(runDir) / "run.json";
  if (!fs::exists(file))
    return std::nullopt;
  try
  {
    auto rec = TRunRecord::fromJson(nlohmann::json::parse(readFile(file.string())));
    // Folders may have been moved (merge from another machine): re-root them.
    rec.run.runDir = runDir;
    rec.run.appOutputDir = (fs::path(runDir) / "output").string();
    return rec;
  }
  catch (const std::exception& e)
  {
    throw std::runtime_error(file.string() + ": corrupt run record: " + e.what());
  }
}

TRunRecord CBenchRunner::runOne(const TBenchRun& run) const
{
  const fs::path dir(run.runDir);
  fs::create_directories(dir);
  // A previous interrupted attempt may have left partial output behind.
  fs::remove_all(dir / "output");
  fs::remove(dir / "stdout.log");
  fs::remove(dir / "stderr.log");
  fs::remove(dir / "run.json");
  writeFileAtomically((dir / "command.sh").string(), "#!/bin/sh\n" + shellJoin(run.argv) + "\n");

  TRunRecord rec;
  rec.run = run;
  rec.startedUtc = utcNow();
  rec.host = hostName();
  const std::string errLog = (dir / "stderr.log").string();
  const auto p = runProcess(run.argv, (dir / "stdout.log").string(), errLog, m_options.timeout_s);
  rec.exitCode = p.exitCode;
  rec.signal = p.signal;
  rec.timedOut = p.timedOut;
  rec.wallS = p.wallS;
  rec.cpuS = p.cpuS;
  rec.maxRssMb = p.maxRssMb;
  rec.stderrTail = fileTail(errLog, static_cast<std::size_t>(m_options.stderr_tail_lines));

  const fs::path summaryFile = fs::path(run.appOutputDir) / "summary.json";
  if (fs::exists(summaryFile))
  {
    try
    {
      rec.summary = nlohmann::json::parse(readFile(summaryFile.string()));
    }
    catch (const std::exception& e)
    {
      rec.failureReason = summaryFile.string() + ": unreadable: " + e.what();
    }
  }

  if (!p.started)
    rec.failureReason = p.error;
  else if (p.timedOut)
    rec.failureReason = "timed out after " + std::to_string(m_options.timeout_s) + " s";
  else if (p.signal != 0)
  {
    const std::string msg = firstLine(rec.stderrTail);
    rec.failureReason =
        "killed by signal " + std::to_string(p.signal) + (msg.empty() ? "" : ": " + msg);
  }
  else if (p.exitCode != 0)
  {
    const std::string msg = firstLine(rec.stderrTail);
    rec.failureReason = "exit code " + std::to_string(p.exitCode) + (msg.empty() ? "" : ": " + msg);
  }
  else if (rec.failureReason.empty() && rec.summary.is_null())
    rec.failureReason = "no summary.json written";
  else if (rec.summary.is_object() && rec.summary.value("failed", false))
  {
    const auto it = rec.summary.find("error");
    rec.failureReason = "summary says failed" + (it != rec.summary.end() && it->is_string()
                                                     ? ": " + it->get<std::string>()
                                                     : std::string());
  }
  rec.ok = rec.failureReason.empty();
  writeFileAtomically((dir / "run.json").string(), rec.toJson().dump(2) + "\n");
  return rec;
}

std::vector<TRunRecord> CBenchRunner::run(
    const std::vector<TBenchRun>& runs, const TProgressCallback& progress) const
{
  std::vector<TRunRecord> records(runs.size());
  std::vector<std::size_t> todo;
  TProgress prog;
  prog.total = runs.size();
  for (std::size_t i = 0; i < runs.size(); ++i)
  {
    auto done = loadCompleted(runs[i].runDir);
    if (done && (done->ok || !m_options.retry_failed))
    {
      records[i] = *done;
      ++prog.done;
      ++prog.skipped;
      if (!done->ok)
        ++prog.failed;
    }
    else
      todo.push_back(i);
  }

  const auto t0 = std::chrono::steady_clock::now();
  std::mutex mtx;
  std::map<std::string, std::pair<double, int>> timeByApp;  // app -> (sum wall, count)
  std::atomic<std::size_t> next{0};
  std::vector<std::size_t> running;  // indices in flight, for the ETA
  if (progress)
  {
    std::lock_guard<std::mutex> lock(mtx);
    progress(prog);
  }

  const auto estimate = [&](std::size_t idx) -> std::optional<double>
  {
    const auto it = timeByApp.find(runs[idx].app);
    if (it != timeByApp.end())
      return it->second.first / it->second.second;
    double sum = 0;
    int n = 0;
    for (const auto& [app, v] : timeByApp)
    {
      sum += v.first;
      n += v.second;
    }
    if (n == 0)
      return std::nullopt;
    return sum / n;
  };

  const auto worker = [&]()
  {
    for (;;)
    {
      const std::size_t k = next++;
      if (k >= todo.size())
        return;
      const std::size_t i = todo[k];
      TRunRecord rec;
      try
      {
        rec = runOne(runs[i]);
      }
      catch (const std::exception& e)
      {
        rec.run = runs[i];
        rec.ok = false;
        rec.failureReason = e.what();
      }
      std::lock_guard<std::mutex> lock(mtx);
      records[i] = rec;
      auto& t = timeByApp[runs[i].app];
      t.first += rec.wallS;
      t.second += 1;
      ++prog.done;
      if (!rec.ok)
        ++prog.failed;
      prog.lastId = runs[i].id;
      prog.elapsedS = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      double remaining = 0;
      bool known = true;
      for (std::size_t q = next; q < todo.size(); ++q)
      {
        const auto e = estimate(todo[q]);
        if (!e)
          known = false;
        remaining += e.value_or(0);
      }
      // Runs in flight are counted as half done.
      const std::size_t inFlight =
          std::min<std::size_t>(todo.size(), next) - (prog.done - prog.skipped);
      for (std::size_t q = 0; q < inFlight; ++q)
        remaining += 0.5 * estimate(i).value_or(0);
      prog.etaS = known ? std::optional<double>(remaining / m_options.jobs) : std::nullopt;
      if (progress)
        progress(prog);
    }
  };
  std::vector<std::thread> threads;
  const int n = std::min<int>(m_options.jobs, static_cast<int>(todo.size()));
  for (int t = 0; t < n; ++t)
    threads.emplace_back(worker);
  for (auto& th : threads)
    th.join();
  return records;
}
}  // namespace roislam::bench
