/* Private: MRPT archive I/O of the OpenCV types a landmark holds. */
#pragma once

#include <mrpt/math/TPoint3D.h>
#include <mrpt/serialization/CArchive.h>
#include <roislam/features/TFeatureSet.h>

#include <opencv2/core.hpp>

namespace roislam::landmarks::detail
{
void writeMat(mrpt::serialization::CArchive& out, const cv::Mat& m);
cv::Mat readMat(mrpt::serialization::CArchive& in);
void writeRect(mrpt::serialization::CArchive& out, const cv::Rect& r);
cv::Rect readRect(mrpt::serialization::CArchive& in);
/** x, y, z by value: MRPT's TPoint3D is packed (#pragma pack 1), so inside
 *  our structs its doubles can be misaligned, and binding the archive's
 *  double& to them is undefined behaviour (UBSan, setup.sh sanitize). */
void writePoint(mrpt::serialization::CArchive& out, const mrpt::math::TPoint3D& p);
mrpt::math::TPoint3D readPoint(mrpt::serialization::CArchive& in);
/** Images as PNG bytes (lossless, compact). */
void writeImagePng(mrpt::serialization::CArchive& out, const cv::Mat& image);
cv::Mat readImagePng(mrpt::serialization::CArchive& in);
void writeFeatures(mrpt::serialization::CArchive& out, const features::TFeatureSet& f);
features::TFeatureSet readFeatures(mrpt::serialization::CArchive& in);
}  // namespace roislam::landmarks::detail
