#include "roislam/bench/TRunRecord.h"

#include <stdexcept>

namespace roislam::bench
{
namespace
{
const nlohmann::json* fieldOf(const nlohmann::json& object, const std::string& key)
{
  if (!object.is_object())
    return nullptr;
  if (const auto it = object.find(key); it != object.end())
    return &*it;
  // "a.b...": field b... of the object a.
  const auto dot = key.find('.');
  if (dot == std::string::npos)
    return nullptr;
  const auto parent = object.find(key.substr(0, dot));
  return parent == object.end() ? nullptr : fieldOf(*parent, key.substr(dot + 1));
}
}  // namespace

const nlohmann::json* TRunRecord::field(const std::string& key) const
{
  return fieldOf(summary, key);
}

std::optional<double> TRunRecord::number(const std::string& key) const
{
  const nlohmann::json* node = field(key);
  if (!node || !node->is_number())
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
