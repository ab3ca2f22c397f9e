#include "roislam/bench/TRunRecord.h"

#include <stdexcept>

namespace roislam::bench
{
std::optional<double> TRunRecord::number(const std::string& key) const
{
  // "a.b": field b of the object a.
  const nlohmann::json* node = &summary;
  std::size_t start = 0;
  for (;;)
  {
    if (!node->is_object())
      return std::nullopt;
    const auto dot = key.find('.', start);
    const auto it = node->find(key.substr(start, dot == std::string::npos ? dot : dot - start));
    if (it == node->end())
      return std::nullopt;
    node = &*it;
    if (dot == std::string::npos)
      break;
    start = dot + 1;
  }
  if (!node->is_number())
    return std::nullopt;
  return node->get<double>();
}

nlohmann::json TRunRecord::toJson() const
{
  return {{"run", run.toJson()},       {"ok", ok},         {"failure_reason", failureReason},
          {"exit_code", exitCode},     {"signal", signal}, {"timed_out", timedOut},
          {"wall_s", wallS},           {"cpu_s", cpuS},    {"max_rss_mb", maxRssMb},
          {"started_utc", startedUtc}, {"host", host},     {"stderr_tail", stderrTail},
          {"summary", summary}};
}

TRunRecord TRunRecord::fromJson(const nlohmann::json& j)
{
  TRunRecord r;
  try
  {
    r.run = TBenchRun::fromJson(j.at("run"));
    r.ok = j.at("ok").get<bool>();
    r.failureReason = j.value("failure_reason", "");
    r.exitCode = j.value("exit_code", -1);
    r.signal = j.value("signal", 0);
    r.timedOut = j.value("timed_out", false);
    r.wallS = j.value("wall_s", 0.0);
    r.cpuS = j.value("cpu_s", 0.0);
    r.maxRssMb = j.value("max_rss_mb", 0.0);
    r.startedUtc = j.value("started_utc", "");
    r.host = j.value("host", "");
    r.stderrTail = j.value("stderr_tail", "");
    r.summary = j.contains("summary") ? j.at("summary") : nlohmann::json();
  }
  catch (const nlohmann::json::exception& e)
  {
    throw std::runtime_error(std::string("run record: ") + e.what());
  }
  return r;
}
}  // namespace roislam::bench
