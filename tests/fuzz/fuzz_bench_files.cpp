/* Fuzz target: roi-bench's plan and results files. The first byte chooses:
 * a plan ini ([Bench], through CStrictIniFile), a run record (run.json, as a
 * resumed bench reads it, then its results.csv row), the reference numbers
 * (dissertation.json) or a variant spec (--variant). */
#include <roislam/bench/CBenchRunner.h>
#include <roislam/bench/CDissertationReference.h>
#include <roislam/bench/CExperimentPlan.h>
#include <roislam/bench/CResultsCollector.h>
#include <roislam/bench/TVariant.h>
#include <roislam/common/CStrictIniFile.h>
#include <roislam/common/IniKeyCheck.h>

#include <filesystem>

#include "FuzzSupport.h"

namespace
{
void plan(const uint8_t* data, size_t size)
{
  const std::string file = roislam::fuzz::writeScratch("plan.ini", data, size);
  try
  {
    const roislam::common::CStrictIniFile cfg(file);
    roislam::bench::CExperimentPlan::TOptions o;
    roislam::common::checkIniKeys(cfg, "Bench", roislam::common::knownIniKeys(o), file);
    o.loadFromConfigFile(cfg, "Bench");
  }
  catch (const std::exception& e)
  {
    // Syntax errors name the file; value errors name "[Bench] key".
    roislam::fuzz::checkRejection(e, "");
  }
}

void runRecord(const uint8_t* data, size_t size)
{
  const auto dir = roislam::fuzz::scratchDir() / "run";
  std::filesystem::create_directories(dir);
  const std::string file = roislam::fuzz::writeScratch("run/run.json", data, size);
  try
  {
    if (const auto rec = roislam::bench::CBenchRunner::loadCompleted(dir.string()))
      roislam::bench::CResultsCollector::toCsv({*rec});
  }
  catch (const std::exception& e)
  {
    roislam::fuzz::checkRejection(e, file);
  }
}

void reference(const uint8_t* data, size_t size)
{
  const std::string file = roislam::fuzz::writeScratch("dissertation.json", data, size);
  try
  {
    const auto ref = roislam::bench::CDissertationReference::fromFile(file);
    for (const char* f : {"surf", "sift", "orb"})
    {
      for (int id = 0; id < 9; ++id)
        ref.test1(id, f);
      ref.test1Average(f);
      ref.test1TruePositiveRate(f);
      ref.test1TrueNegativeRate(f);
      ref.test1Fps(f);
      for (const char* m : {"traditional", "roi_small", "roi_big"})
        for (int test : {2, 3})
        {
          ref.ate(test, m, f);
          ref.scalar(test, m, f, "rpe_trans");
        }
    }
    ref.sequenceId("rgbd_dataset_freiburg1_xyz");
    ref.sequenceShortName(1);
  }
  catch (const std::exception& e)
  {
    roislam::fuzz::checkRejection(e, "");
  }
}

void variant(const uint8_t* data, size_t size)
{
  try
  {
    roislam::bench::TVariant::parse(std::string(reinterpret_cast<const char*>(data), size));
  }
  catch (const std::exception& e)
  {
    roislam::fuzz::checkRejection(e, "variant '");
  }
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
  if (size == 0)
    return 0;
  switch (data[0] % 4)
  {
    case 0:
      plan(data + 1, size - 1);
      break;
    case 1:
      runRecord(data + 1, size - 1);
      break;
    case 2:
      reference(data + 1, size - 1);
      break;
    default:
      variant(data + 1, size - 1);
  }
  return 0;
}
