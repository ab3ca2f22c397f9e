/* Test helper: config/graphslam-engine.ini (mode roi_big, ORB) with another
 * mode and extractor, as roi-graphslam's --mode / --feature would set them. */
#pragma once

#include <roislam/testing/TestData.h>

#include <fstream>
#include <regex>
#include <sstream>
#include <string>

namespace roislam::testing
{
/** Writes <dir>/engine-<mode>-<feature>.ini and returns its path. */
inline std::string engineIniVariant(
    const std::string& dir, const std::string& mode, const std::string& feature)
{
  std::ifstream in(sourceDir() + "/config/graphslam-engine.ini");
  std::stringstream ss;
  ss << in.rdbuf();
  std::string text =
      std::regex_replace(ss.str(), std::regex("\nmode = roi_big\n"), "\nmode = " + mode + "\n");
  text = std::regex_replace(
      text, std::regex("\nfeature_type = orb\n"), "\nfeature_type = " + feature + "\n");
  const std::string file = dir + "/engine-" + mode + "-" + feature + ".ini";
  std::ofstream(file) << text;
  return file;
}
}  // namespace roislam::testing
