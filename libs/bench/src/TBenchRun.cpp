#include "roislam/bench/TBenchRun.h"

#include <stdexcept>

namespace roislam::bench
{
nlohmann::json TBenchRun::toJson() const
{
  nlohmann::json ov = nlohmann::json::array();
  for (const auto& o : iniOverrides)
    ov.push_back({{"section", o.section}, {"key", o.key}, {"value", o.value}});
  return {
      {"id", id},
      {"test", test},
      {"sequence", sequence},
      {"sequence_path", sequencePath},
      {"app", app},
      {"mode", mode},
      {"feature", feature},
      {"max_features", maxFeatures},
      {"variant", variant},
      {"variant_label", variantLabel},
      {"base_ini", baseIni},
      {"ini", iniFile},
      {"ini_overrides", ov},
      {"argv", argv}};
}

TBenchRun TBenchRun::fromJson(const nlohmann::json& j)
{
  TBenchRun r;
  try
  {
    r.id = j.at("id").get<std::string>();
    r.test = j.at("test").get<int>();
    r.sequence = j.at("sequence").get<std::string>();
    r.sequencePath = j.value("sequence_path", "");
    r.app = j.at("app").get<std::string>();
    r.mode = j.value("mode", "");
    r.feature = j.at("feature").get<std::string>();
    r.maxFeatures = j.value("max_features", 0);
    r.variant = j.value("variant", "");
    r.variantLabel = j.value("variant_label", "");
    r.baseIni = j.value("base_ini", "");
    r.iniFile = j.value("ini", "");
    if (j.contains("ini_overrides"))
      for (const auto& o : j.at("ini_overrides"))
        r.iniOverrides.push_back(
            {o.at("section").get<std::string>(), o.at("key").get<std::string>(),
             o.at("value").get<std::string>()});
    r.argv = j.value("argv", std::vector<std::string>{});
  }
  catch (const nlohmann::json::exception& e)
  {
    throw std::runtime_error(std::string("run description: ") + e.what());
  }
  return r;
}
}  // namespace roislam::bench
