#include "SerializationHelpers.h"

#include <opencv2/imgcodecs.hpp>
#include <stdexcept>
#include <vector>

namespace roislam::landmarks::detail
{
void writeMat(mrpt::serialization::CArchive& out, const cv::Mat& m)
{
  const cv::Mat c = m.isContinuous() ? m : m.clone();
  out << static_cast<int32_t>(c.type()) << static_cast<int32_t>(c.rows)
      << static_cast<int32_t>(c.cols);
  const std::size_t bytes = c.total() * c.elemSize();
  if (bytes)
    out.WriteBuffer(c.data, bytes);
}

cv::Mat readMat(mrpt::serialization::CArchive& in)
{
  int32_t type = 0, rows = 0, cols = 0;
  in >> type >> rows >> cols;
  if (rows < 0 || cols < 0 || rows > (1 << 24) || cols > (1 << 24))
    throw std::runtime_error("corrupt matrix header in archive");
  cv::Mat m(rows, cols, type);
  const std::size_t bytes = m.total() * m.elemSize();
  if (bytes)
    in.ReadBuffer(m.data, bytes);
  return m;
}

void writeRect(mrpt::serialization::CArchive& out, const cv::Rect& r)
{
  out << static_cast<int32_t>(r.x) << static_cast<int32_t>(r.y) << static_cast<int32_t>(r.width)
      << static_cast<int32_t>(r.height);
}

cv::Rect readRect(mrpt::serialization::CArchive& in)
{
  int32_t x, y, w, h;
  in >> x >> y >> w >> h;
  return {x, y, w, h};
}

void writeImagePng(mrpt::serialization::CArchive& out, const cv::Mat& image)
{
  std::vector<uchar> png;
  if (!image.empty() && !cv::imencode(".png", image, png))
    throw std::runtime_error("cannot encode landmark patch as PNG");
  out << static_cast<uint64_t>(png.size());
  if (!png.empty())
    out.WriteBuffer(png.data(), png.size());
}

cv::Mat readImagePng(mrpt::serialization::CArchive& in)
{
  uint64_t n = 0;
  in >> n;
  if (n == 0)
    return {};
  if (n > (uint64_t(1) << 32))
    throw std::runtime_error("corrupt image size in archive");
  std::vector<uchar> png(n);
  in.ReadBuffer(png.data(), n);
  cv::Mat img = cv::imdecode(png, cv::IMREAD_UNCHANGED);
  if (img.empty())
    throw std::runtime_error("corrupt PNG patch in archive");
  return img;
}

void writeFeatures(mrpt::serialization::CArchive& out, const features::TFeatureSet& f)
{
  out << static_cast<uint8_t>(f.type) << static_cast<uint64_t>(f.keypoints.size());
  for (const auto& k : f.keypoints)
    out << k.pt.x << k.pt.y << k.size << k.angle << k.response << static_cast<int32_t>(k.octave)
        << static_cast<int32_t>(k.class_id);
  writeMat(out, f.descriptors);
}

features::TFeatureSet readFeatures(mrpt::serialization::CArchive& in)
{
  features::TFeatureSet f;
  uint8_t type = 0;
  uint64_t n = 0;
  in >> type >> n;
  if (type > static_cast<uint8_t>(features::EFeatureType::ORB) || n > (1u << 24))
    throw std::runtime_error("corrupt feature set in archive");
  f.type = static_cast<features::EFeatureType>(type);
  f.keypoints.resize(n);
  for (auto& k : f.keypoints)
  {
    int32_t octave, classId;
    in >> k.pt.x >> k.pt.y >> k.size >> k.angle >> k.response >> octave >> classId;
    k.octave = octave;
    k.class_id = classId;
  }
  f.descriptors = readMat(in);
  if (static_cast<uint64_t>(f.descriptors.rows) != n)
    throw std::runtime_error("corrupt feature set in archive (descriptor rows)");
  return f;
}
void writePoint(mrpt::serialization::CArchive& out, const mrpt::math::TPoint3D& p)
{
  const double x = p.x, y = p.y, z = p.z;
  out << x << y << z;
}

mrpt::math::TPoint3D readPoint(mrpt::serialization::CArchive& in)
{
  double x = 0, y = 0, z = 0;
  in >> x >> y >> z;
  return {x, y, z};
}
}  // namespace roislam::landmarks::detail
