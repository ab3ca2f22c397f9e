/* Extent of a scene's content for framing views and placing the grid: the
 * map cloud's bounds without its outlying points (each axis cut to the
 * [fraction, 1 - fraction] quantiles; stray depth readings would otherwise
 * shrink the map to a corner of the picture), grown by every trajectory,
 * ground-truth and keyframe position. Used by CSlamSceneBuilder and
 * CSnapshotRenderer.
 */
#pragma once

#include <mrpt/math/TBoundingBox.h>
#include <roislam/viz/TSceneContent.h>

#include <optional>

namespace roislam::viz
{
/** nullopt when the content has no point at all. */
std::optional<mrpt::math::TBoundingBox> robustBounds(
    const TSceneContent& content, double fraction = 0.01);

/** A "round" grid spacing (0.1, 0.2, 0.5, 1, 2, 5 ... m) giving about 4 to
 *  10 cells along `extent` metres. */
double niceGridSpacing(double extent);
}  // namespace roislam::viz
