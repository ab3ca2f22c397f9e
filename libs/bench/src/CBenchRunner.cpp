#include "roislam/bench/CBenchRunner.h"

#include <roislam/bench/ProcessUtils.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <ctime>
#include <filesystem>
#include <map>
#include <mutex>
#include <optional>
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

namespace
{
// ------------------------------------------------------------ runOne stages

void prepareRunDir(const fs::path& dir, const TBenchRun& run)
{
  fs::create_directories(dir);
  // A previous interrupted attempt may have left partial output behind.
  fs::remove_all(dir / "output");
  fs::remove(dir / "stdout.log");
  fs::remove(dir / "stderr.log");
  fs::remove(dir / "run.json");
  writeFileAtomically((dir / "command.sh").string(), "#!/bin/sh\n" + shellJoin(run.argv) + "\n");
}

void recordProcess(TRunRecord& rec, const TProcessResult& p)
{
  rec.exitCode = p.exitCode;
  rec.signal = p.signal;
  rec.timedOut = p.timedOut;
  rec.wallS = p.wallS;
  rec.cpuS = p.cpuS;
  rec.maxRssMb = p.maxRssMb;
}

/** The app's summary.json if it wrote one; an unreadable one is the failure. */
void readSummary(TRunRecord& rec, const fs::path& summaryFile)
{
  if (!fs::exists(summaryFile))
    return;
  try
  {
    rec.summary = nlohmann::json::parse(readFile(summaryFile.string()));
  }
  catch (const std::exception& e)
  {
    rec.failureReason = summaryFile.string() + ": unreadable: " + e.what();
  }
}

/** Why the run failed, first cause first; rec.failureReason as it is if none. */
std::string failureReason(const TProcessResult& p, const TRunRecord& rec, double timeoutS)
{
  if (!p.started)
    return p.error;
  if (p.timedOut)
    return "timed out after " + std::to_string(timeoutS) + " s";
  if (p.signal != 0)
  {
    const std::string msg = firstLine(rec.stderrTail);
    return "killed by signal " + std::to_string(p.signal) + (msg.empty() ? "" : ": " + msg);
  }
  if (p.exitCode != 0)
  {
    const std::string msg = firstLine(rec.stderrTail);
    return "exit code " + std::to_string(p.exitCode) + (msg.empty() ? "" : ": " + msg);
  }
  if (rec.failureReason.empty() && rec.summary.is_null())
    return "no summary.json written";
  if (rec.summary.is_object() && rec.summary.value("failed", false))
  {
    const auto it = rec.summary.find("error");
    return "summary says failed" + (it != rec.summary.end() && it->is_string()
                                        ? ": " + it->get<std::string>()
                                        : std::string());
  }
  return rec.failureReason;
}
}  // namespace

TRunRecord CBenchRunner::runOne(const TBenchRun& run) const
{
  const fs::path dir(run.runDir);
  prepareRunDir(dir, run);

  TRunRecord rec;
  rec.run = run;
  rec.startedUtc = utcNow();
  rec.host = hostName();
  const std::string errLog = (dir / "stderr.log").string();
  const auto p = runProcess(run.argv, (dir / "stdout.log").string(), errLog, m_options.timeout_s);
  recordProcess(rec, p);
  rec.stderrTail = fileTail(errLog, static_cast<std::size_t>(m_options.stderr_tail_lines));

  readSummary(rec, fs::path(run.appOutputDir) / "summary.json");
  rec.failureReason = failureReason(p, rec, m_options.timeout_s);
  rec.ok = rec.failureReason.empty();
  writeFileAtomically((dir / "run.json").string(), rec.toJson().dump(2) + "\n");
  return rec;
}

namespace
{
/** The batch's shared state while worker threads run it: the queue of
 *  runs to do, the records, and the progress with its ETA from the wall
 *  times measured so far (per app, else over all apps). */
class CBatch
{
 public:
  using TProgress = CBenchRunner::TProgress;

  CBatch(
      const std::vector<TBenchRun>& runs, std::vector<TRunRecord>& records,
      std::vector<std::size_t> todo, TProgress progress, int jobs,
      const CBenchRunner::TProgressCallback& callback)
      : m_runs(runs),
        m_records(records),
        m_todo(std::move(todo)),
        m_prog(progress),
        m_jobs(jobs),
        m_callback(callback)
  {
    if (m_callback)
    {
      std::lock_guard<std::mutex> lock(m_mtx);
      m_callback(m_prog);
    }
  }

  std::size_t todo() const { return m_todo.size(); }

  /** The next run's index into `runs`, or nullopt when none is left. */
  std::optional<std::size_t> take()
  {
    const std::size_t k = m_next++;
    if (k >= m_todo.size())
      return std::nullopt;
    return m_todo[k];
  }

  /** Stores run i's record and reports the progress. */
  void finished(std::size_t i, const TRunRecord& rec)
  {
    std::lock_guard<std::mutex> lock(m_mtx);
    m_records[i] = rec;
    auto& t = m_timeByApp[m_runs[i].app];
    t.first += rec.wallS;
    t.second += 1;
    ++m_prog.done;
    if (!rec.ok)
      ++m_prog.failed;
    m_prog.lastId = m_runs[i].id;
    m_prog.elapsedS =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - m_t0).count();
    m_prog.etaS = eta(i);
    if (m_callback)
      m_callback(m_prog);
  }

 private:
  /** Mean wall time of the app's runs, else of all runs; nullopt before any. */
  std::optional<double> estimate(std::size_t idx) const
  {
    const auto it = m_timeByApp.find(m_runs[idx].app);
    if (it != m_timeByApp.end())
      return it->second.first / it->second.second;
    double sum = 0;
    int n = 0;
    for (const auto& [app, v] : m_timeByApp)
    {
      sum += v.first;
      n += v.second;
    }
    if (n == 0)
      return std::nullopt;
    return sum / n;
  }

  /** Remaining wall time over the jobs, after run `justDone` finished. */
  std::optional<double> eta(std::size_t justDone) const
  {
    double remaining = 0;
    bool known = true;
    for (std::size_t q = m_next; q < m_todo.size(); ++q)
    {
      const auto e = estimate(m_todo[q]);
      if (!e)
        known = false;
      remaining += e.value_or(0);
    }
    // Runs in flight are counted as half done.
    const std::size_t inFlight =
        std::min<std::size_t>(m_todo.size(), m_next) - (m_prog.done - m_prog.skipped);
    for (std::size_t q = 0; q < inFlight; ++q)
      remaining += 0.5 * estimate(justDone).value_or(0);
    return known ? std::optional<double>(remaining / m_jobs) : std::nullopt;
  }

  const std::vector<TBenchRun>& m_runs;
  std::vector<TRunRecord>& m_records;
  const std::vector<std::size_t> m_todo;
  TProgress m_prog;
  const int m_jobs;
  const CBenchRunner::TProgressCallback& m_callback;
  const std::chrono::steady_clock::time_point m_t0 = std::chrono::steady_clock::now();
  std::mutex m_mtx;
  std::map<std::string, std::pair<double, int>> m_timeByApp;  // app -> (sum wall, count)
  std::atomic<std::size_t> m_next{0};
};
}  // namespace

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

  CBatch batch(runs, records, std::move(todo), prog, m_options.jobs, progress);
  const auto worker = [&]()
  {
    while (const auto i = batch.take())
    {
      TRunRecord rec;
      try
      {
        rec = runOne(runs[*i]);
      }
      catch (const std::exception& e)
      {
        rec.run = runs[*i];
        rec.ok = false;
        rec.failureReason = e.what();
      }
      batch.finished(*i, rec);
    }
  };
  std::vector<std::thread> threads;
  const int n = std::min<int>(m_options.jobs, static_cast<int>(batch.todo()));
  for (int t = 0; t < n; ++t)
    threads.emplace_back(worker);
  for (auto& th : threads)
    th.join();
  return records;
}
}  // namespace roislam::bench
