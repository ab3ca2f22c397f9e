/* Stage 1: the region of interest, i.e. the most highly detailed patch of a
 * colour image: Canny edges -> 3x3 morphology (erosions, then dilations) ->
 * the largest connected component's bounding box. Called per frame by the
 * landmark pipeline and the ROI modes of the SLAM front end.
 */
#pragma once

#include <mrpt/config/CLoadableOptions.h>

#include <opencv2/core.hpp>
#include <optional>
#include <string>

namespace roislam::roi
{
struct TRoi
{
  cv::Rect box;
  /** Pixels of the connected component (<= box.area()). */
  int componentArea = 0;
};

class CRoiDetector
{
 public:
  /** Morphology convention. The dissertation treats edges as black foreground
   *  on a white background, so its "erosion" grows the edges and its
   *  "dilation" shrinks them. We keep its counts and that meaning: `erosions`
   *  = iterations that grow the edge pixels (OpenCV dilate on our white-edge
   *  mask), `dilations` = iterations that shrink them (OpenCV erode), applied
   *  in that order. Read literally on white edges, 6 erosions would delete
   *  every 1-px Canny edge and no ROI would ever exist. The "big" preset keeps
   *  the 6 edge-growing iterations and shrinks by only 2, so the merged patches
   *  stay bigger than "small" (6 / 7): measured on fr1/rpy, see README.
   *
   *  ini section (default "RoiDetector"):
   *  - preset            small|big|custom (default big); small = 6 erosions +
   *                      7 dilations, big = 6 erosions + 2 dilations;
   *                      custom uses the two keys below
   *  - erosions, dilations   int >= 0, only read with preset=custom
   *  - canny_low, canny_high double (default 250 / 300), aperture 3
   *  - min_area_fraction     double in [0,1): components smaller than this
   *                          fraction of the image are "no ROI" (default 0.002)
   */
  struct TOptions : public mrpt::config::CLoadableOptions
  {
    std::string preset = "big";
    int erosions = 6;
    int dilations = 2;
    double canny_low = 250;
    double canny_high = 300;
    double min_area_fraction = 0.002;

    /** Sets preset and the matching erosion/dilation counts; throws on an unknown name. */
    void setPreset(const std::string& name);
    void loadFromConfigFile(
        const mrpt::config::CConfigFileBase& source, const std::string& section) override;
    void saveToConfigFile(
        mrpt::config::CConfigFileBase& target, const std::string& section) const override;
  };

  // Two constructors rather than a default argument: GCC rejects TOptions()
  // as a default argument inside the enclosing class.
  CRoiDetector();
  explicit CRoiDetector(const TOptions& options);

  /** The ROI of a grey (CV_8UC1) or BGR image, or nullopt when none. */
  std::optional<TRoi> detect(const cv::Mat& image) const;

  /** The binary foreground mask after morphology (for debugging/tests). */
  cv::Mat foregroundMask(const cv::Mat& image) const;

  const TOptions& options() const { return m_options; }

 private:
  TOptions m_options;
};
}  // namespace roislam::roi
