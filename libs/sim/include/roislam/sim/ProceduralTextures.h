/* Procedural textures for the synthetic scenes of CSceneModel: printed-text
 * pages, posters, checkerboards and multi-scale noise (wallpaper, wood, cork).
 * Everything is generated at run time from a seeded generator, so a scene is
 * reproducible and nothing is downloaded or shipped. All images are CV_8UC3 BGR.
 */
#pragma once

#include <mrpt/random/RandomGenerators.h>

#include <opencv2/core/mat.hpp>

namespace roislam::sim
{
/** Sum of value-noise octaves (cell sizes finestCellPx, 2x, 4x ... up to a
 *  quarter of the image), grey noise of amplitude +-contrast around base. */
cv::Mat makeNoiseTexture(
    mrpt::random::CRandomGenerator& rng, cv::Size size, const cv::Scalar& base, double contrast,
    int finestCellPx);

/** A printed page: lines of random words (cv::putText) of about lineHeightPx,
 *  with headings, paragraph breaks and small figures, dark ink on paper. */
cv::Mat makeTextPage(mrpt::random::CRandomGenerator& rng, cv::Size size, double lineHeightPx);

/** A poster: colour gradient, random filled shapes and a large title. */
cv::Mat makePoster(mrpt::random::CRandomGenerator& rng, cv::Size size);

/** A checkerboard of square cells (cellPx), two random contrasting colours. */
cv::Mat makeCheckerboard(mrpt::random::CRandomGenerator& rng, cv::Size size, int cellPx);

/** Wooden planks along the image columns: stripes of plankWidthPx with grain. */
cv::Mat makeWoodTexture(mrpt::random::CRandomGenerator& rng, cv::Size size, int plankWidthPx);

/** Copies patch into dst with its top-left corner at topLeft, clipped to dst. */
void pasteTexture(cv::Mat& dst, const cv::Mat& patch, cv::Point topLeft);
}  // namespace roislam::sim
