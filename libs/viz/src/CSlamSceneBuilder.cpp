#include <mrpt/opengl/CGridPlaneXY.h>
#include <mrpt/opengl/CPointCloud.h>
#include <mrpt/opengl/CPointCloudColoured.h>
#include <mrpt/opengl/CSetOfLines.h>
#include <roislam/viz/CSlamSceneBuilder.h>
#include <roislam/viz/SceneBounds.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace roislam::viz
{
namespace
{
mrpt::opengl::CSetOfLines::Ptr makePolyline(
    const std::vector<mrpt::math::TPoint3D>& points, const mrpt::img::TColor& colour, float width,
    const std::string& name)
{
  auto lines = mrpt::opengl::CSetOfLines::Create();
  lines->setName(name);
  lines->setColor_u8(colour);
  lines->setLineWidth(width);
  for (std::size_t i = 1; i < points.size(); ++i)
    lines->appendLine(
        points[i - 1].x, points[i - 1].y, points[i - 1].z, points[i].x, points[i].y, points[i].z);
  return lines;
}

mrpt::opengl::CPointCloudColoured::Ptr makeCloud(
    const mrpt::maps::CColouredPointsMap& map, float pointSize, double maxHeight)
{
  auto cloud = mrpt::opengl::CPointCloudColoured::Create();
  cloud->setName("map_cloud");
  if (std::isinf(maxHeight))
    cloud->loadFromPointsMap(&map);
  else
  {
    mrpt::maps::CColouredPointsMap cut;
    for (std::size_t i = 0; i < map.size(); ++i)
    {
      float x, y, z, r, g, b;
      map.getPointRGB(i, x, y, z, r, g, b);
      if (z <= maxHeight)
        cut.insertPointRGB(x, y, z, r, g, b);
    }
    cloud->loadFromPointsMap(&cut);
  }
  cloud->setPointSize(pointSize);
  return cloud;
}
}  // namespace

double CSlamSceneBuilder::gridSpacing(const TSceneContent& content) const
{
  if (m_options.gridSpacing > 0)
    return m_options.gridSpacing;
  const auto bb = robustBounds(content);
  if (!bb)
    return 1.0;
  return niceGridSpacing(std::max(bb->max.x - bb->min.x, bb->max.y - bb->min.y));
}

mrpt::opengl::COpenGLScene::Ptr CSlamSceneBuilder::build(const TSceneContent& content) const
{
  auto scene = mrpt::opengl::COpenGLScene::Create();
  if (content.cloud.size() > 0)
    scene->insert(makeCloud(content.cloud, m_options.pointSize, m_options.maxPointHeight));
  if (content.mapObject)
  {
    content.mapObject->setName("map_object");
    scene->insert(content.mapObject);
  }
  if (m_options.showTrajectories)
  {
    if (content.groundTruth.size() > 1)
      scene->insert(makePolyline(
          content.groundTruth, mrpt::img::TColor(0, 160, 0), m_options.trajectoryWidth,
          "ground_truth"));
    if (content.trajectory.size() > 1)
      scene->insert(makePolyline(
          content.trajectory, mrpt::img::TColor(0, 60, 220), m_options.trajectoryWidth,
          "trajectory"));
    if (!content.keyframes.empty())
    {
      auto kf = mrpt::opengl::CPointCloud::Create();
      kf->setName("keyframes");
      for (const auto& p : content.keyframes)
        kf->insertPoint(p.x, p.y, p.z);
      kf->setColor_u8(mrpt::img::TColor(0, 30, 120));
      kf->setPointSize(m_options.keyframeSize);
      scene->insert(kf);
    }
  }

  const auto bb = robustBounds(content);
  if (m_options.showGrid && bb)
  {
    const double s = gridSpacing(content);
    auto grid = mrpt::opengl::CGridPlaneXY::Create(
        static_cast<float>(s * std::floor(bb->min.x / s)),
        static_cast<float>(s * std::ceil(bb->max.x / s)),
        static_cast<float>(s * std::floor(bb->min.y / s)),
        static_cast<float>(s * std::ceil(bb->max.y / s)), static_cast<float>(bb->min.z),
        static_cast<float>(s));
    grid->setName("grid");
    grid->setColor_u8(mrpt::img::TColor(180, 180, 180));
    scene->insert(grid);
  }
  return scene;
}

void CSlamSceneBuilder::save(const mrpt::opengl::COpenGLScene& scene, const std::string& file)
{
  const std::string tmp = file + ".tmp";
  bool ok = false;
  try
  {
    ok = scene.saveToFile(tmp);
  }
  catch (const std::exception&)
  {
    ok = false;
  }
  if (!ok || std::rename(tmp.c_str(), file.c_str()) != 0)
  {
    std::remove(tmp.c_str());
    throw std::runtime_error(file + ": cannot write the 3-D scene");
  }
}
}  // namespace roislam::viz
