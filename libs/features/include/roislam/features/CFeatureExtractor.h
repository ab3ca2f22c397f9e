/* Stage 2: one interface over SIFT, SURF and ORB with OpenCV's default
 * parameters and an optional cap on the number of features (strongest kept).
 * The only place in roislam that creates OpenCV feature classes. Called by the
 * ROI pipeline, the SLAM front end and feature-bench.
 */
#pragma once

#include <mrpt/config/CLoadableOptions.h>
#include <roislam/features/TFeatureSet.h>

#include <opencv2/features2d.hpp>

namespace roislam::features
{
class CFeatureExtractor
{
 public:
  /** ini section (default "FeatureExtractor"):
   *  - feature_type   sift|surf|orb           (default orb)
   *  - max_features   int >= 0, 0 = no cap     (default 0; SIFT/SURF keep all,
   *                   ORB uses OpenCV's default 500)
   *  - surf_hessian_threshold  double > 0      (default 100, as OpenCV SURF)
   *  - surf_octaves            int >= 1        (default 4)
   *  - surf_octave_layers      int >= 1        (default 3)
   *  - surf_extended           bool            (default false: 64-D)
   *  - surf_upright            bool            (default false)
   */
  struct TOptions : public mrpt::config::CLoadableOptions
  {
    EFeatureType feature_type = EFeatureType::ORB;
    int max_features = 0;
    double surf_hessian_threshold = 100;
    int surf_octaves = 4;
    int surf_octave_layers = 3;
    bool surf_extended = false;
    bool surf_upright = false;

    void loadFromConfigFile(
        const mrpt::config::CConfigFileBase& source, const std::string& section) override;
    void saveToConfigFile(
        mrpt::config::CConfigFileBase& target, const std::string& section) const override;
  };

  // Two constructors rather than a default argument: GCC rejects TOptions()
  // as a default argument inside the enclosing class.
  CFeatureExtractor();
  explicit CFeatureExtractor(const TOptions& options);

  /** Detects and describes features on a grey (CV_8UC1) or BGR image. When
   *  max_features > 0, at most that many are returned, strongest response first.
   *  mask (optional, CV_8UC1) restricts detection. */
  TFeatureSet extract(const cv::Mat& image, const cv::Mat& mask = cv::Mat()) const;

  /** As extract() but without the cap (ORB: at most 10x max_features, at
   *  least 5000, since ORB needs a budget): every detection, strongest first.
   *  Pair with capWithRegion() to cap per region after extracting once. */
  TFeatureSet extractAll(const cv::Mat& image) const;

  /** From a strongest-first set (extractAll()), the max_features strongest of
   *  the whole image together with the max_features strongest whose keypoint
   *  lies inside region, strongest first. This is the dissertation's cap "N
   *  features in the ROI" without its second extraction. max_features = 0:
   *  the set unchanged. */
  TFeatureSet capWithRegion(const TFeatureSet& strongestFirst, const cv::Rect& region) const;

  /** Features whose keypoint lies inside `region` (clamped to the image),
   *  in image coordinates, strongest first, at most `cap` (0 = all). The
   *  detector runs on `region` padded by supportPx() on each side (clamped):
   *  the pixels a keypoint's detection and descriptor read around it, so
   *  that its border rules do not empty the region's rim. Its work scales
   *  with that padded area, returned in describedPixels. The crop, rather
   *  than a mask, is what makes it cheap: OpenCV's detectors build their
   *  whole-image pyramid and run FAST/DoG everywhere whatever the mask. */
  TFeatureSet extractIn(
      const cv::Mat& image, const cv::Rect& region, int cap,
      std::size_t* describedPixels = nullptr) const;

  /** Pixels around a keypoint, at the finest scale, that detection and
   *  description read (ORB: its edge threshold and patch, 31; SIFT: its
   *  border of 5 px per octave at the first octaves and descriptor window;
   *  SURF: half the filter size of the first octaves). */
  int supportPx() const;

  const TOptions& options() const { return m_options; }

 private:
  TOptions m_options;
  cv::Ptr<cv::Feature2D> m_detector;
  /** Same detector without the cap (extractAll). */
  cv::Ptr<cv::Feature2D> m_uncapped;
  /** A detector of this type keeping at most `cap` features (0 = all). */
  cv::Ptr<cv::Feature2D> detectorWithCap(int cap) const;
};
}  // namespace roislam::features
