#include <mrpt/opengl/CGridPlaneXY.h>
#include <mrpt/opengl/CPointCloudColoured.h>
#include <mrpt/opengl/CSetOfLines.h>
#include <roislam/viz/CSlamSceneBuilder.h>

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
}  // namespace

mrpt::opengl::COpenGLScene::Ptr CSlamSceneBuilder::build(const TSceneContent& content) const
{
  auto scene = mrpt::opengl::COpenGLScene::Create();
  // Bounding box of everything shown, for the grid.
  double lo[3] = {1e30, 1e30, 1e30}, hi[3] = {-1e30, -1e30, -1e30};
  auto grow = [&](double x, double y, double z)
  {
    const double p[3] = {x, y, z};
    for (int k = 0; k < 3; ++k)
    {
      lo[k] = std::min(lo[k], p[k]);
      hi[k] = std::max(hi[k], p[k]);
    }
  };

  if (content.cloud.size() > 0)
  {
    auto cloud = mrpt::opengl::CPointCloudColoured::Create();
    cloud->setName("map_cloud");
    cloud->loadFromPointsMap(&content.cloud);
    cloud->setPointSize(m_options.pointSize);
    scene->insert(cloud);
    const auto bb = content.cloud.boundingBox();
    grow(bb.min.x, bb.min.y, bb.min.z);
    grow(bb.max.x, bb.max.y, bb.max.z);
  }
  if (content.mapObject)
  {
    content.mapObject->setName("map_object");
    scene->insert(content.mapObject);
  }
  if (content.groundTruth.size() > 1)
    scene->insert(makePolyline(
        content.groundTruth, mrpt::img::TColor(0, 160, 0), m_options.trajectoryWidth,
        "ground_truth"));
  if (content.trajectory.size() > 1)
    scene->insert(makePolyline(
        content.trajectory, mrpt::img::TColor(0, 0, 220), m_options.trajectoryWidth, "trajectory"));
  for (const auto& p : content.trajectory)
    grow(p.x, p.y, p.z);
  for (const auto& p : content.groundTruth)
    grow(p.x, p.y, p.z);

  if (m_options.showGrid && lo[0] <= hi[0])
  {
    auto grid = mrpt::opengl::CGridPlaneXY::Create(
        std::floor(lo[0]), std::ceil(hi[0]), std::floor(lo[1]), std::ceil(hi[1]), lo[2], 1.0f);
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
