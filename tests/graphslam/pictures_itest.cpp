/* roi-graphslam's pictures on the synthetic textured loop (a room with a known
 * floor at z = 0 of the ground truth's world), run as users run it, three
 * ways: with ground truth, with only the accelerometer, with neither.
 *  - orientation: the scene's floor points (found through the ground truth)
 *    fit a plane whose normal is +z within 5 degrees (ground truth and
 *    accelerometer; the first-camera fallback is as tilted as that camera),
 *    and they land in the lower part of the snapshot's 3-D view;
 *    map.bt's occupied voxels span the same box as the scene's cloud;
 *  - framing: the map covers a minimum fraction of each snapshot panel;
 *  - plots: ate.png and errors.png exist and are non-empty with ground
 *    truth, and are absent, without any error or warning, without it. */
#include <gtest/gtest.h>
#include <mrpt/img/CImage.h>
#include <mrpt/opengl/COpenGLScene.h>
#include <mrpt/opengl/CPointCloud.h>
#include <mrpt/opengl/CPointCloudColoured.h>
#include <mrpt/opengl/CSetOfLines.h>
#include <octomap/OcTree.h>
#include <roislam/evaluation/CTrajectoryEvaluator.h>
#include <roislam/io/TumTrajectory.h>
#include <roislam/testing/TestData.h>
#include <roislam/viz/CSnapshotRenderer.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <sstream>

namespace fs = std::filesystem;
using mrpt::math::TPoint3D;

namespace
{
/** A copy of the sequence (linked, not copied) without some of its files. */
std::string variant(const std::string& seq, const std::string& dir, bool gt, bool accel)
{
  fs::create_directories(dir);
  for (const auto& e : fs::directory_iterator(seq))
  {
    const auto name = e.path().filename().string();
    if ((name == "groundtruth.txt" && !gt) || (name == "accelerometer.txt" && !accel))
      continue;
    fs::create_symlink(fs::absolute(e.path()), fs::path(dir) / name);
  }
  return dir;
}

struct TRun
{
  int exitCode = -1;
  std::string err;
  nlohmann::json summary;
};

TRun runApp(const std::string& input, const std::string& out, const std::string& extra = "")
{
  const std::string exe = roislam::testing::binaryDir() + "/apps/roi-graphslam/roi-graphslam";
  const std::string ini = roislam::testing::sourceDir() + "/config/roi_big.ini";
  const std::string errFile = out + ".stderr";
  const int rc = std::system((exe + " --ini " + ini + " --feature orb --input " + input +
                              " --output-dir " + out + " " + extra + " > /dev/null 2> " + errFile)
                                 .c_str());
  TRun r;
  r.exitCode = WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
  std::stringstream ss;
  ss << std::ifstream(errFile).rdbuf();
  r.err = ss.str();
  if (fs::exists(out + "/summary.json"))
    r.summary = nlohmann::json::parse(std::ifstream(out + "/summary.json"));
  return r;
}

/** What scene.3Dscene holds, in the pictures' (display) frame. */
struct TScene
{
  std::vector<TPoint3D> cloud, trajectory, groundTruth, keyframes;
};

std::vector<TPoint3D> polyline(const mrpt::opengl::CSetOfLines& lines)
{
  std::vector<TPoint3D> pts;
  double x0, y0, z0, x1, y1, z1;
  for (std::size_t i = 0; i < lines.getLineCount(); ++i)
  {
    lines.getLineByIndex(i, x0, y0, z0, x1, y1, z1);
    if (i == 0)
      pts.emplace_back(x0, y0, z0);
    pts.emplace_back(x1, y1, z1);
  }
  return pts;
}

TScene loadScene(const std::string& file)
{
  mrpt::opengl::COpenGLScene scene;
  EXPECT_TRUE(scene.loadFromFile(file)) << file;
  TScene s;
  if (auto c = scene.getByClass<mrpt::opengl::CPointCloudColoured>())
    for (std::size_t i = 0; i < c->size(); ++i)
    {
      const auto p = c->getPoint3Df(i);
      s.cloud.emplace_back(p.x, p.y, p.z);
    }
  if (auto t = std::dynamic_pointer_cast<mrpt::opengl::CSetOfLines>(scene.getByName("trajectory")))
    s.trajectory = polyline(*t);
  if (auto g =
          std::dynamic_pointer_cast<mrpt::opengl::CSetOfLines>(scene.getByName("ground_truth")))
    s.groundTruth = polyline(*g);
  if (auto k = std::dynamic_pointer_cast<mrpt::opengl::CPointCloud>(scene.getByName("keyframes")))
    for (std::size_t i = 0; i < k->size(); ++i)
    {
      const auto p = k->getPoint3Df(i);
      s.keyframes.emplace_back(p.x, p.y, p.z);
    }
  return s;
}

/** The rigid transform that maps `from` positions onto `to` positions (same
 *  stamps), as the ATE alignment computes it. */
mrpt::poses::CPose3D rigidFit(
    const roislam::io::TTrajectory& stamps, const std::vector<TPoint3D>& from,
    const std::vector<TPoint3D>& to)
{
  roislam::io::TTrajectory a, b;
  for (std::size_t i = 0; i < stamps.size(); ++i)
  {
    a.push_back(
        {stamps[i].timestamp, mrpt::poses::CPose3D(from[i].x, from[i].y, from[i].z, 0, 0, 0)});
    b.push_back({stamps[i].timestamp, mrpt::poses::CPose3D(to[i].x, to[i].y, to[i].z, 0, 0, 0)});
  }
  return roislam::evaluation::CTrajectoryEvaluator().evaluate(b, a).ate.alignment;
}

/** Unit normal of the least-squares plane through the points. */
Eigen::Vector3d planeNormal(const std::vector<TPoint3D>& pts)
{
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const auto& p : pts)
    mean += Eigen::Vector3d(p.x, p.y, p.z);
  mean /= static_cast<double>(pts.size());
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (const auto& p : pts)
  {
    const Eigen::Vector3d d = Eigen::Vector3d(p.x, p.y, p.z) - mean;
    cov += d * d.transpose();
  }
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(cov);
  return es.eigenvectors().col(0);  // smallest eigenvalue
}

/** map.bt is in the same (gravity-up) frame as the scene: the scene's map
 *  points fall in its occupied voxels (it was built from the same points). */
void checkOctoMapFrame(const std::string& out, const std::vector<TPoint3D>& cloud)
{
  octomap::OcTree tree(0.05);
  ASSERT_TRUE(tree.readBinary(out + "/map.bt")) << out;
  std::size_t inside = 0, tried = 0;
  for (std::size_t i = 0; i < cloud.size(); i += 10, ++tried)
  {
    const auto* node = tree.search(cloud[i].x, cloud[i].y, cloud[i].z);
    inside += node && tree.isNodeOccupied(node);
  }
  ASSERT_GT(tried, 100u);
  EXPECT_GT(static_cast<double>(inside) / tried, 0.8) << out;
  std::printf(
      "%s: %.0f %% of the scene's points in map.bt's occupied voxels\n", out.c_str(),
      100.0 * inside / tried);
}

int median(std::vector<int> v)
{
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

/** Checks one run's pictures; returns the floor normal's angle to +z (deg). */
double checkOrientationAndFraming(
    const std::string& out, const roislam::io::TTrajectory& groundTruth)
{
  const auto estimate = roislam::io::loadTumTrajectory(out + "/trajectory.txt");
  const TScene scene = loadScene(out + "/scene.3Dscene");
  EXPECT_EQ(scene.trajectory.size(), estimate.size());
  checkOctoMapFrame(out, scene.cloud);
  std::vector<TPoint3D> estimated;
  for (const auto& p : estimate)
    estimated.push_back(p.pose.translation());
  // Where the scene is in the ground truth's world (floor at z = 0): the
  // scene's trajectory onto the ground truth, through the estimate's stamps.
  const auto aligned = roislam::evaluation::CTrajectoryEvaluator().evaluate(groundTruth, estimate);
  std::vector<TPoint3D> gtPositions;
  for (const auto& p : aligned.aligned)
    gtPositions.push_back(p.pose.translation());
  const auto sceneToWorld = rigidFit(estimate, scene.trajectory, gtPositions);

  std::vector<TPoint3D> floor;
  std::vector<bool> isFloor;
  double floorZ = 0, otherZ = 0;
  for (const auto& p : scene.cloud)
  {
    const auto w = sceneToWorld.composePoint(p);
    isFloor.push_back(std::abs(w.z) < 0.03);
    (isFloor.back() ? floorZ : otherZ) += p.z;
    if (isFloor.back())
      floor.push_back(p);
  }
  EXPECT_GT(floor.size(), 1000u) << out;
  if (floor.size() < 10)
    return 180;
  const Eigen::Vector3d n = planeNormal(floor);
  const double angle = mrpt::RAD2DEG(std::acos(std::min(1.0, std::abs(n.z()))));
  // +z, not -z: the floor lies below the rest of the map.
  EXPECT_LT(floorZ / floor.size(), otherZ / (scene.cloud.size() - floor.size())) << out;

  // The snapshot's 3-D view of the same content with the floor in red and
  // everything else grey: the floor is in the lower part.
  roislam::viz::TSceneContent c;
  for (std::size_t i = 0; i < scene.cloud.size(); ++i)
  {
    const auto& p = scene.cloud[i];
    const float g = isFloor[i] ? 0.f : 0.5f;
    c.cloud.insertPointRGB(
        static_cast<float>(p.x), static_cast<float>(p.y), static_cast<float>(p.z),
        isFloor[i] ? 1.f : g, g, g);
  }
  c.trajectory = scene.trajectory;
  c.groundTruth = scene.groundTruth;
  c.keyframes = scene.keyframes;
  // The cameras' mean view direction, as the writer hands it to the renderer.
  const auto estToScene = rigidFit(estimate, estimated, scene.trajectory);
  for (const auto& p : estimate)
  {
    const auto R = (estToScene + p.pose).getRotationMatrix();
    c.lookDirection = c.lookDirection + mrpt::math::TVector3D(R(0, 2), R(1, 2), R(2, 2));
  }
  roislam::viz::CSnapshotRenderer::TOptions ro;
  ro.overlays = false;
  const roislam::viz::CSnapshotRenderer renderer(ro);
  const auto img = renderer.render(c);
  const cv::Mat view = img.asCvMat<cv::Mat>(mrpt::img::SHALLOW_COPY)(cv::Rect(
      0, 0, static_cast<int>(renderer.panelWidth()), static_cast<int>(renderer.panelHeight())));
  std::vector<int> floorRows, otherRows;
  for (int r = 0; r < view.rows; ++r)
    for (int col = 0; col < view.cols; ++col)
    {
      const auto px = view.at<cv::Vec3b>(r, col);  // BGR
      if (px[2] > 200 && px[1] < 60 && px[0] < 60)
        floorRows.push_back(r);
      else if (
          std::abs(px[2] - 128) < 20 && std::abs(px[1] - 128) < 20 && std::abs(px[0] - 128) < 20)
        otherRows.push_back(r);
    }
  EXPECT_GT(floorRows.size(), 1000u) << out;
  EXPECT_GT(otherRows.size(), 1000u) << out;
  if (!floorRows.empty() && !otherRows.empty())
  {
    EXPECT_GT(median(floorRows), median(otherRows)) << out;
    EXPECT_GT(median(floorRows), view.rows / 2) << out;
  }

  // Framing of the snapshot itself: the map covers much of both panels
  // (below the legend strip). From above, the room shows only what the
  // cameras saw of the floor, the desk and the walls' edges, so less of the
  // top view is covered. (Before the framing, the map covered 17 % of the
  // whole snapshot here, 4 % on fr1/xyz; now 51 % / 42 % of the 3-D view,
  // 17 % / 14 % of the top view.)
  const double minCover[2] = {0.35, 0.10};
  mrpt::img::CImage snap;
  EXPECT_TRUE(snap.loadFromFile(out + "/snapshot.png"));
  const cv::Mat m = snap.asCvMat<cv::Mat>(mrpt::img::SHALLOW_COPY);
  const roislam::viz::CSnapshotRenderer app;
  for (int k = 0; k < 2; ++k)
  {
    const cv::Mat p = m(cv::Rect(
        static_cast<int>(k * app.panelWidth()), static_cast<int>(app.headerHeight()),
        static_cast<int>(app.panelWidth()), static_cast<int>(app.panelHeight())));
    int covered = 0;
    for (int r = 0; r < p.rows; ++r)
      for (int col = 0; col < p.cols; ++col)
      {
        const auto px = p.at<cv::Vec3b>(r, col);
        // Not background, not the grid's grey lines.
        const bool grid = px[0] == px[1] && px[1] == px[2] && px[0] >= 170;
        covered += !grid && (px[0] < 245 || px[1] < 245 || px[2] < 245);
      }
    const double f = static_cast<double>(covered) / (p.rows * p.cols);
    EXPECT_GT(f, minCover[k]) << out << " panel " << k;
    std::printf("%s panel %d: map covers %.0f %% of the pixels\n", out.c_str(), k, 100 * f);
  }
  std::printf(
      "%s: floor normal %.2f deg from +z (%zu floor points)\n", out.c_str(), angle, floor.size());
  return angle;
}

bool nonEmptyPng(const std::string& file)
{
  if (!fs::exists(file) || fs::file_size(file) < 10000)
    return false;
  std::ifstream in(file, std::ios::binary);
  char sig[4] = {};
  in.read(sig, 4);
  return std::string(sig + 1, 3) == "PNG";
}
}  // namespace

TEST(RoiGraphSlamPictures, GravityUpFramedAndPlottedWithWhatTheSequenceHas)
{
  ROISLAM_REQUIRE_SYNTHETIC(seq, "textured");
  const auto groundTruth = roislam::io::loadTumTrajectory(seq + "/groundtruth.txt");
  const std::string tmp = roislam::testing::makeTempDir("gs_pictures");

  // Ground truth known: its frame, and the error plots.
  auto r = runApp(seq, tmp + "/gt");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_EQ(r.summary["display_frame"]["up"], "ground_truth");
  EXPECT_LT(r.summary["display_frame"]["accelerometer_vs_ground_truth_deg"].get<double>(), 2.0);
  EXPECT_LT(checkOrientationAndFraming(tmp + "/gt", groundTruth), 5.0);
  EXPECT_TRUE(nonEmptyPng(tmp + "/gt/ate.png"));
  EXPECT_TRUE(nonEmptyPng(tmp + "/gt/errors.png"));
  EXPECT_FALSE(r.summary.contains("plot_error"));

  // Only the accelerometer: levelled with it; no plots, and no complaint.
  const std::string accelOnly = variant(seq, tmp + "/seq_accel", false, true);
  r = runApp(accelOnly, tmp + "/accel");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_EQ(r.summary["display_frame"]["up"], "accelerometer");
  EXPECT_LT(checkOrientationAndFraming(tmp + "/accel", groundTruth), 5.0);
  for (const char* f : {"ate.png", "errors.png"})
    EXPECT_FALSE(fs::exists(tmp + "/accel/" + f)) << f;
  EXPECT_FALSE(r.summary.contains("plot_error"));
  EXPECT_EQ(r.err.find("warning"), std::string::npos) << r.err;

  // Neither: the first camera's -y is up (that camera looks 17 deg down, so
  // the floor is tilted about as much, but still at the bottom).
  const std::string bare = variant(seq, tmp + "/seq_bare", false, false);
  r = runApp(bare, tmp + "/bare");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_EQ(r.summary["display_frame"]["up"], "first_camera");
  EXPECT_LT(checkOrientationAndFraming(tmp + "/bare", groundTruth), 30.0);
  for (const char* f : {"ate.png", "errors.png"})
    EXPECT_FALSE(fs::exists(tmp + "/bare/" + f)) << f;
  EXPECT_EQ(r.err.find("warning"), std::string::npos) << r.err;

  // A corrupt accelerometer log: the first camera's frame, and one line
  // naming the file and line (the run itself succeeds).
  const std::string broken = variant(seq, tmp + "/seq_broken", false, false);
  std::ofstream(broken + "/accelerometer.txt") << "# timestamp ax ay az\n1000000000 0 9.8\n";
  r = runApp(broken, tmp + "/broken", "--max-frames 20 --no-snapshot");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_EQ(r.summary["display_frame"]["up"], "first_camera");
  const std::string where = broken + "/accelerometer.txt:2:";
  EXPECT_NE(r.summary["display_frame"]["note"].get<std::string>().find(where), std::string::npos);
  EXPECT_NE(
      r.err.find("roi-graphslam: warning: pictures not levelled by the accelerometer: " + where),
      std::string::npos)
      << r.err;
  fs::remove_all(tmp);
}
