#include "roislam/io/TumAccelerometer.h"

#include <algorithm>
#include <sstream>

#include "TumTextFile.h"

namespace roislam::io
{
mrpt::math::TVector3D accelerometerToOptical(const mrpt::math::TVector3D& kinect)
{
  return {-kinect.x, -kinect.y, kinect.z};
}

TAccelerometerLog loadTumAccelerometer(const std::string& file)
{
  TAccelerometerLog log;
  for (const auto& row : tumtext::readRows(file, 4, "timestamp ax ay az"))
    log.push_back({row[0], {row[1], row[2], row[3]}});
  std::stable_sort(
      log.begin(), log.end(),
      [](const auto& a, const auto& b) { return a.timestamp < b.timestamp; });
  return log;
}

void saveTumAccelerometer(
    const std::string& file, const TAccelerometerLog& log, const std::string& headerComment)
{
  using tumtext::formatDouble;
  std::ostringstream out;
  out << tumtext::commentLines(headerComment) << "# timestamp ax ay az\n";
  for (const auto& s : log)
    out << formatDouble(s.timestamp) << ' ' << formatDouble(s.acceleration.x) << ' '
        << formatDouble(s.acceleration.y) << ' ' << formatDouble(s.acceleration.z) << '\n';
  tumtext::writeAtomically(file, out.str());
}
}  // namespace roislam::io
