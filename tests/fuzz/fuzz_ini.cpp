/* Fuzz target: our ini layer. CStrictIniFile checks the text; what it
 * accepts goes to MRPT's parser (with its @define / ${} / $eval{}
 * preprocessing), every value is read as each type our loaders use, and the
 * TOptions of the libraries in the fuzz build load their sections strictly. */
#include <roislam/bench/CExperimentPlan.h>
#include <roislam/common/CStrictIniFile.h>
#include <roislam/common/IniKeyCheck.h>
#include <roislam/io/CRawlogFrameSource.h>
#include <roislam/io/CTumFrameSource.h>

#include <string>
#include <vector>

#include "FuzzSupport.h"

namespace
{
template <typename T>
void load(const roislam::common::CStrictIniFile& cfg, T options, const std::string& section)
{
  try
  {
    roislam::common::checkIniKeys(
        cfg, section, roislam::common::knownIniKeys(options), cfg.label());
    options.loadFromConfigFile(cfg, section);
  }
  catch (const std::exception& e)
  {
    roislam::fuzz::checkRejection(e, "");
  }
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
  const std::string text(reinterpret_cast<const char*>(data), size);
  try
  {
    const auto cfg = roislam::common::CStrictIniFile::fromText(text, "fuzz.ini");
    std::vector<std::string> sections;
    cfg.getAllSections(sections);
    for (const auto& s : sections)
    {
      std::vector<std::string> keys;
      cfg.getAllKeys(s, keys);
      for (const auto& k : keys)
      {
        try
        {
          cfg.read_string(s, k, "");
          cfg.read_double(s, k, 0.0);
          cfg.read_int(s, k, 0);
          cfg.read_bool(s, k, false);
          std::vector<double> v;
          cfg.read_vector(s, k, std::vector<double>(), v);
        }
        catch (const std::exception&)
        {
          // MRPT's own conversions: wrapped by our loaders, not checked here.
        }
      }
    }
    load(cfg, roislam::io::CTumFrameSource::TOptions(), "TumFrameSource");
    load(cfg, roislam::io::CRawlogFrameSource::TOptions(), "RawlogFrameSource");
    load(cfg, roislam::bench::CExperimentPlan::TOptions(), "Bench");
  }
  catch (const std::exception& e)
  {
    roislam::fuzz::checkRejection(e, "fuzz.ini:");
  }
  return 0;
}
