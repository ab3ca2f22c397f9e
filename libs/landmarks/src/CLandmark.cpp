#include "roislam/landmarks/CLandmark.h"

#include <mrpt/serialization/CArchive.h>

#include "SerializationHelpers.h"

namespace roislam::landmarks
{
IMPLEMENTS_SERIALIZABLE(CLandmark, CSerializable, roislam::landmarks)

uint8_t CLandmark::serializeGetVersion() const
{
  return 0;
}

void CLandmark::serializeTo(mrpt::serialization::CArchive& out) const
{
  out << id;
  detail::writeFeatures(out, features);
  out << static_cast<uint64_t>(featurePoints.size());
  for (const auto& p : featurePoints)
    detail::writePoint(out, p);
  detail::writeRect(out, box);
  out << static_cast<int32_t>(imageSize.width) << static_cast<int32_t>(imageSize.height);
  detail::writeImagePng(out, patch);
  detail::writePoint(out, positionCamera);
  out << hasPositionCamera;
  detail::writePoint(out, positionWorld);
  out << hasPositionWorld;
  out << static_cast<uint64_t>(sightings.size());
  for (const auto& s : sightings)
  {
    out << s.frame << s.timestamp;
    detail::writeRect(out, s.box);
    detail::writePoint(out, s.position);
    out << s.hasPosition << static_cast<int32_t>(s.inliers);
  }
}

void CLandmark::serializeFrom(mrpt::serialization::CArchive& in, uint8_t version)
{
  switch (version)
  {
    case 0:
    {
      in >> id;
      features = detail::readFeatures(in);
      uint64_t np = 0;
      in >> np;
      if (np > (1u << 24))
        throw std::runtime_error("corrupt landmark points in archive");
      featurePoints.resize(np);
      for (auto& p : featurePoints)
        p = detail::readPoint(in);
      box = detail::readRect(in);
      int32_t w, h;
      in >> w >> h;
      imageSize = cv::Size(w, h);
      patch = detail::readImagePng(in);
      positionCamera = detail::readPoint(in);
      in >> hasPositionCamera;
      positionWorld = detail::readPoint(in);
      in >> hasPositionWorld;
      uint64_t n = 0;
      in >> n;
      if (n > (1u << 28))
        throw std::runtime_error("corrupt landmark sightings in archive");
      sightings.resize(n);
      for (auto& s : sightings)
      {
        int32_t inliers;
        in >> s.frame >> s.timestamp;
        s.box = detail::readRect(in);
        s.position = detail::readPoint(in);
        in >> s.hasPosition >> inliers;
        s.inliers = inliers;
      }
      break;
    }
    default:
      MRPT_THROW_UNKNOWN_SERIALIZATION_VERSION(version);
  }
}
}  // namespace roislam::landmarks
