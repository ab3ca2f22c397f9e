#include "roislam/bench/TPairedCost.h"

#include <roislam/common/ErrorText.h>
#include <roislam/common/TextFiles.h>

#include <filesystem>
#include <stdexcept>

namespace roislam::bench
{
namespace
{
const char* kFormat = "roi-bench paired cost 1";

nlohmann::json overridesToJson(const std::vector<TIniOverride>& ov)
{
  nlohmann::json a = nlohmann::json::array();
  for (const auto& o : ov)
    a.push_back({{"section", o.section}, {"key", o.key}, {"value", o.value}});
  return a;
}
}  // namespace

nlohmann::json TPairedCost::toJson() const
{
  nlohmann::json vs = nlohmann::json::array();
  for (const auto& v : versions)
    vs.push_back(
        {{"key", v.key},
         {"label", v.label},
         {"ini", v.iniFile},
         {"ini_overrides", overridesToJson(v.overrides)},
         {"frames", v.frames},
         {"lost_frames", v.lostFrames},
         {"wall_ms_per_frame", v.wallMsPerFrame},
         {"cpu_ms_per_frame", v.cpuMsPerFrame},
         {"frontend_ms_per_frame", v.frontEndMsPerFrame},
         {"fps", v.fps},
         {"ate_rmse", v.ateRmse ? nlohmann::json(*v.ateRmse) : nlohmann::json()},
         {"wall_ratio", v.wallRatio},
         {"cpu_ratio", v.cpuRatio},
         {"frontend_ratio", v.frontEndRatio}});
  nlohmann::json lo = nlohmann::json::array();
  for (const auto& [key, why] : leftOut)
    lo.push_back({{"key", key}, {"why", why}});
  return {{"sequence", sequence}, {"sequence_path", sequencePath},
          {"feature", feature},   {"max_features", maxFeatures},
          {"passes", passes},     {"max_frames", maxFrames},
          {"versions", vs},       {"left_out", lo},
          {"error", error}};
}

TPairedCost TPairedCost::fromJson(const nlohmann::json& j)
{
  TPairedCost c;
  try
  {
    c.sequence = j.at("sequence").get<std::string>();
    c.sequencePath = j.value("sequence_path", "");
    c.feature = j.at("feature").get<std::string>();
    c.maxFeatures = j.value("max_features", 0);
    c.passes = j.at("passes").get<int>();
    c.maxFrames = j.value("max_frames", std::size_t{0});
    c.error = j.value("error", "");
    for (const auto& v : j.at("versions"))
    {
      TVersion t;
      t.key = v.at("key").get<std::string>();
      t.label = v.value("label", "");
      t.iniFile = v.value("ini", "");
      for (const auto& o : v.value("ini_overrides", nlohmann::json::array()))
        t.overrides.push_back(
            {o.at("section").get<std::string>(), o.at("key").get<std::string>(),
             o.at("value").get<std::string>()});
      t.frames = v.at("frames").get<std::size_t>();
      t.lostFrames = v.value("lost_frames", std::size_t{0});
      t.wallMsPerFrame = v.at("wall_ms_per_frame").get<double>();
      t.cpuMsPerFrame = v.at("cpu_ms_per_frame").get<double>();
      t.frontEndMsPerFrame = v.at("frontend_ms_per_frame").get<double>();
      t.fps = v.at("fps").get<double>();
      if (v.contains("ate_rmse") && v.at("ate_rmse").is_number())
        t.ateRmse = v.at("ate_rmse").get<double>();
      t.wallRatio = v.at("wall_ratio").get<double>();
      t.cpuRatio = v.at("cpu_ratio").get<double>();
      t.frontEndRatio = v.at("frontend_ratio").get<double>();
      c.versions.push_back(std::move(t));
    }
    for (const auto& l : j.value("left_out", nlohmann::json::array()))
      c.leftOut.emplace_back(l.at("key").get<std::string>(), l.at("why").get<std::string>());
  }
  catch (const nlohmann::json::exception& e)
  {
    throw std::runtime_error(std::string("paired cost entry: ") + e.what());
  }
  return c;
}

std::vector<TPairedCost> loadPairedCosts(const std::string& file)
{
  if (!std::filesystem::exists(file))
    throw std::runtime_error(file + ": no such file");
  const std::string text = common::readFile(file);
  std::vector<TPairedCost> out;
  try
  {
    const auto j = nlohmann::json::parse(text);
    if (!j.is_object() || j.value("format", "") != kFormat)
      throw std::runtime_error(
          std::string("not a paired cost file (\"format\": \"") + kFormat + "\" expected)");
    for (const auto& r : j.at("runs"))
      out.push_back(TPairedCost::fromJson(r));
  }
  catch (const std::exception& e)
  {
    // nlohmann's messages may span lines: keep the error one line.
    throw std::runtime_error(file + ": " + common::printableExcerpt(e.what(), 200));
  }
  return out;
}

void savePairedCosts(const std::vector<TPairedCost>& costs, const std::string& file)
{
  nlohmann::json runs = nlohmann::json::array();
  for (const auto& c : costs)
    runs.push_back(c.toJson());
  common::writeFileAtomically(
      file, nlohmann::json{{"format", kFormat}, {"runs", runs}}.dump(2) + "\n");
}
}  // namespace roislam::bench
