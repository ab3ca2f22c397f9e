/* Unit tests of CSurf (libs/features): Fast-Hessian localisation and scale on
 * synthetic blobs, Laplacian sign, descriptor invariance to rotation, upright
 * and extended modes, feature cap, determinism and parameter validation. */
#include <gtest/gtest.h>
#include <roislam/features/CSurf.h>

#include <algorithm>
#include <cmath>
#include <opencv2/core/utility.hpp>
#include <opencv2/imgproc.hpp>
#include <random>

using roislam::features::CSurf;

namespace
{
/** Grey 8-bit image with one Gaussian blob (amplitude +-100 on grey 128). */
cv::Mat blobImage(double sigma, cv::Point2d c, bool bright, int size = 320)
{
  cv::Mat img(size, size, CV_32F, cv::Scalar(128));
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x)
    {
      const double r2 = (x - c.x) * (x - c.x) + (y - c.y) * (y - c.y);
      img.at<float>(y, x) +=
          static_cast<float>((bright ? 100 : -100) * std::exp(-r2 / (2 * sigma * sigma)));
    }
  cv::Mat u8;
  img.convertTo(u8, CV_8U);
  return u8;
}

/** Random texture of blurred blobs and rectangles, seeded (no file needed). */
cv::Mat texturedImage(int size, unsigned seed)
{
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  cv::Mat img(size, size, CV_8UC1, cv::Scalar(120));
  for (int k = 0; k < 260; ++k)
  {
    const cv::Point c(static_cast<int>(u(rng) * size), static_cast<int>(u(rng) * size));
    const int r = 2 + static_cast<int>(u(rng) * 14);
    const int v = static_cast<int>(u(rng) * 255);
    if (k % 3 == 0)
      cv::rectangle(img, cv::Rect(c.x, c.y, r * 2, r), cv::Scalar(v), cv::FILLED);
    else
      cv::circle(img, c, r, cv::Scalar(v), cv::FILLED, cv::LINE_AA);
  }
  cv::GaussianBlur(img, img, cv::Size(0, 0), 1.0);
  return img;
}

struct TDetection
{
  std::vector<cv::KeyPoint> kps;
  cv::Mat desc;
};

TDetection run(
    const cv::Mat& img, const CSurf::TParams& p = CSurf::TParams(), const cv::Mat& mask = cv::Mat())
{
  TDetection d;
  CSurf::create(p)->detectAndCompute(img, mask, d.kps, d.desc);
  return d;
}

/** Index of the keypoint nearest to pt within maxDist, or -1. */
int nearest(const std::vector<cv::KeyPoint>& kps, cv::Point2f pt, float maxDist)
{
  int best = -1;
  float bestD = maxDist;
  for (size_t i = 0; i < kps.size(); ++i)
  {
    const float d = static_cast<float>(cv::norm(kps[i].pt - pt));
    if (d <= bestD)
    {
      bestD = d;
      best = static_cast<int>(i);
    }
  }
  return best;
}

/** Checks descriptor invariance: keypoints of `a` mapped by the 2x3 affine M
 *  onto `b`; returns (pairs found, fraction whose true partner is the
 *  descriptor nearest neighbour among all of b, median angle error deg). */
struct TInvariance
{
  int pairs = 0;
  double nnCorrect = 0;
  double medianAngleErr = 0;
};

TInvariance invariance(
    const TDetection& a, const TDetection& b, const cv::Mat& M, double rotDeg, cv::Point2f centre,
    float radius)
{
  TInvariance r;
  int correct = 0;
  std::vector<double> angErr;
  for (size_t i = 0; i < a.kps.size(); ++i)
  {
    const cv::Point2f p = a.kps[i].pt;
    if (cv::norm(p - centre) > radius)
      continue;
    const cv::Point2f q(
        static_cast<float>(
            M.at<double>(0, 0) * p.x + M.at<double>(0, 1) * p.y + M.at<double>(0, 2)),
        static_cast<float>(
            M.at<double>(1, 0) * p.x + M.at<double>(1, 1) * p.y + M.at<double>(1, 2)));
    const int j = nearest(b.kps, q, 1.5f);
    if (j < 0 || std::abs(std::log(b.kps[j].size / a.kps[i].size)) > std::log(1.3))
      continue;
    ++r.pairs;
    const double dTrue = cv::norm(a.desc.row(static_cast<int>(i)), b.desc.row(j), cv::NORM_L2);
    bool isNN = true;
    for (int k = 0; k < b.desc.rows && isNN; ++k)
      if (k != j && cv::norm(a.desc.row(static_cast<int>(i)), b.desc.row(k), cv::NORM_L2) < dTrue)
        isNN = false;
    correct += isNN ? 1 : 0;
    double e = std::fmod(b.kps[j].angle - a.kps[i].angle - rotDeg + 720.0, 360.0);
    angErr.push_back(std::min(e, 360.0 - e));
  }
  if (r.pairs > 0)
  {
    r.nnCorrect = static_cast<double>(correct) / r.pairs;
    std::nth_element(angErr.begin(), angErr.begin() + angErr.size() / 2, angErr.end());
    r.medianAngleErr = angErr[angErr.size() / 2];
  }
  return r;
}
}  // namespace

TEST(CSurf, GaussianBlobIsLocalisedAndScaleFollowsSigma)
{
  // An exact Gaussian-derivative detector finds a blob of sigma at s = sigma.
  // The paper's box filters with its mapping s = 1.2 L / 9 do not: integrating
  // the continuous box filters (paper proportions) over a Gaussian blob, the
  // normalised determinant peaks at L = 5.35 sigma, i.e. s = 0.713 sigma (the
  // 9x9 box acts like a Gaussian of 1.68, not 1.2, on blobs). What matters
  // for matching is that the ratio is the same at every scale.
  std::vector<double> ratios;
  for (double sigma : {3.0, 5.0, 8.0, 12.0, 20.0})
  {
    const cv::Point2d c(160.3, 158.7);
    const TDetection d = run(blobImage(sigma, c, true));
    const int k = nearest(d.kps, cv::Point2f(c), 5.0f);
    ASSERT_GE(k, 0) << "blob of sigma " << sigma << " not detected";
    EXPECT_LT(cv::norm(d.kps[k].pt - cv::Point2f(c)), 1.0) << "sigma " << sigma;
    const double s = 1.2 * d.kps[k].size / 9.0;
    ratios.push_back(s / sigma);
    EXPECT_NEAR(s / sigma, 0.713, 0.06) << "sigma " << sigma << " detected at scale " << s;
  }
  const auto [lo, hi] = std::minmax_element(ratios.begin(), ratios.end());
  EXPECT_LT(*hi / *lo, 1.15) << "detected scale not proportional to the blob's sigma";
}

namespace
{
/** An anisotropic Gaussian blob: centre, std along / across its axis (px),
 *  axis angle (rad) and amplitude (grey levels). */
struct TBlob
{
  cv::Point2d c;
  double sAlong = 1, sAcross = 1, theta = 0, amp = 0;
};

/** 8-bit image of blobs on grey 128, sampled analytically at the pixel
 *  centres, after rotating the scene by rotDeg (image axes, +x towards +y)
 *  about rc; no resampling, so the rotated image is exact. */
cv::Mat renderScene(const std::vector<TBlob>& blobs, cv::Size size, double rotDeg, cv::Point2d rc)
{
  const double a = rotDeg * CV_PI / 180, ca = std::cos(a), sa = std::sin(a);
  cv::Mat img(size, CV_32F, cv::Scalar(128));
  for (int y = 0; y < size.height; ++y)
    for (int x = 0; x < size.width; ++x)
    {
      const double dx = x - rc.x, dy = y - rc.y;
      const double u = rc.x + ca * dx + sa * dy, v = rc.y - sa * dx + ca * dy;
      double val = 128;
      for (const auto& b : blobs)
      {
        const double px = u - b.c.x, py = v - b.c.y;
        if (px * px + py * py > 36 * b.sAlong * b.sAlong)
          continue;
        const double p = std::cos(b.theta) * px + std::sin(b.theta) * py;
        const double q = -std::sin(b.theta) * px + std::cos(b.theta) * py;
        val += b.amp *
               std::exp(-0.5 * (p * p / (b.sAlong * b.sAlong) + q * q / (b.sAcross * b.sAcross)));
      }
      img.at<float>(y, x) = static_cast<float>(val);
    }
  cv::Mat u8;
  img.convertTo(u8, CV_8U);
  return u8;
}

cv::Point2f rotateAbout(cv::Point2f p, double rotDeg, cv::Point2d rc)
{
  const double a = rotDeg * CV_PI / 180, dx = p.x - rc.x, dy = p.y - rc.y;
  return {
      static_cast<float>(rc.x + std::cos(a) * dx - std::sin(a) * dy),
      static_cast<float>(rc.y + std::sin(a) * dx + std::cos(a) * dy)};
}
}  // namespace

TEST(CSurf, BlobsAtNonIntegerPositionsAreLocalisedAndRotationInvariantAtEveryScale)
{
  // Every octave (filter sizes 15..141): position error < 0.1 s, and the
  // same position (mapped) and size when the scene is rotated by 30 degrees
  // about an arbitrary centre.
  const cv::Point2d c(300.37, 231.81), rc(271.3, 198.6);
  const double rot = 30;
  CSurf::TParams p;
  p.hessianThreshold = 10;
  for (double sigma : {3.0, 4.5, 6.0, 8.0, 11.0, 14.0, 17.0, 20.0})
    for (double amp : {80.0, -80.0})
    {
      const std::vector<TBlob> scene{{c, sigma, sigma, 0, amp}};
      const TDetection a = run(renderScene(scene, {640, 480}, 0, rc), p);
      const TDetection b = run(renderScene(scene, {640, 480}, rot, rc), p);
      const int ka = nearest(a.kps, cv::Point2f(c), 5.0f);
      ASSERT_GE(ka, 0) << "sigma " << sigma << " amp " << amp << " not detected";
      const cv::Point2f q = rotateAbout(a.kps[ka].pt, rot, rc);
      const int kb = nearest(b.kps, q, 5.0f);
      ASSERT_GE(kb, 0) << "sigma " << sigma << " amp " << amp << " not detected after rotation";
      const double s = 1.2 * a.kps[ka].size / 9.0;
      EXPECT_LT(cv::norm(a.kps[ka].pt - cv::Point2f(c)), 0.1 * s) << "sigma " << sigma;
      EXPECT_LT(cv::norm(b.kps[kb].pt - rotateAbout(cv::Point2f(c), rot, rc)), 0.1 * s)
          << "sigma " << sigma;
      EXPECT_LT(cv::norm(b.kps[kb].pt - q), 0.1 * s) << "sigma " << sigma;
      EXPECT_NEAR(b.kps[kb].size / a.kps[ka].size, 1.0, 0.05) << "sigma " << sigma;
    }
}

TEST(CSurf, CoarseKeypointsOfAnAsymmetricSceneFollowRotation)
{
  // Overlapping anisotropic blobs make asymmetric structures whose keypoint
  // positions depend on how isotropic the box-filter Hessian is. With lobes
  // 2 * lobe - 1 wide (instead of the paper's 5/9 L) only ~72 % of the coarse
  // keypoints (L >= 30) were found again within 0.3 s after a 30 degree
  // rotation of the exact scene, and those of L >= 60 had median errors of
  // ~5 px (measured 89 of 124 = 72 %); now 113 of 129 = 88 %.
  const cv::Point2d rc(271.3, 198.6);
  const double rot = 30;
  CSurf::TParams p;
  p.hessianThreshold = 20;
  int coarse = 0, found = 0;
  for (unsigned seed : {1u, 2u})
  {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(0, 1);
    std::vector<TBlob> scene;
    for (int k = 0; k < 150; ++k)
    {
      TBlob b;
      b.c = {120 + u(rng) * 400, 90 + u(rng) * 300};
      b.sAlong = 2 + u(rng) * 10;
      b.theta = u(rng) * CV_PI;
      b.amp = (u(rng) < 0.5 ? -1 : 1) * (30 + u(rng) * 40);
      scene.push_back(b);
    }
    for (auto& b : scene)
      b.sAcross = b.sAlong * (0.4 + 0.4 * u(rng));
    const TDetection a = run(renderScene(scene, {640, 480}, 0, rc), p);
    const TDetection b = run(renderScene(scene, {640, 480}, rot, rc), p);
    const cv::Rect2f inner(60, 60, 520, 360);
    for (const auto& ka : a.kps)
    {
      const cv::Point2f q = rotateAbout(ka.pt, rot, rc);
      if (ka.size < 30 || !inner.contains(ka.pt) || !inner.contains(q))
        continue;
      ++coarse;
      const double s = 1.2 * ka.size / 9.0;
      for (const auto& kb : b.kps)
        if (std::abs(std::log(kb.size / ka.size)) < std::log(1.2) && cv::norm(kb.pt - q) < 0.3 * s)
        {
          ++found;
          break;
        }
    }
  }
  ASSERT_GE(coarse, 60);
  EXPECT_GE(static_cast<double>(found) / coarse, 0.8) << found << " of " << coarse;
}

TEST(CSurf, LaplacianSignSeparatesBrightAndDarkBlobs)
{
  const cv::Point2d c(150.5, 170.2);
  const TDetection bright = run(blobImage(6.0, c, true));
  const TDetection dark = run(blobImage(6.0, c, false));
  const int kb = nearest(bright.kps, cv::Point2f(c), 2.0f);
  const int kd = nearest(dark.kps, cv::Point2f(c), 2.0f);
  ASSERT_GE(kb, 0);
  ASSERT_GE(kd, 0);
  // Bright blob: negative second derivatives (trace < 0); dark: positive.
  EXPECT_EQ(bright.kps[kb].class_id, -1);
  EXPECT_EQ(dark.kps[kd].class_id, +1);
}

TEST(CSurf, DescriptorsAreInvariantToRotationBy90Degrees)
{
  const cv::Mat img = texturedImage(400, 7);
  cv::Mat rot;
  cv::rotate(img, rot, cv::ROTATE_90_CLOCKWISE);
  // ROTATE_90_CLOCKWISE maps (x, y) to (H-1-y, x): +90 degrees in image axes.
  const cv::Mat M = (cv::Mat_<double>(2, 3) << 0, -1, img.rows - 1, 1, 0, 0);
  const TDetection a = run(img), b = run(rot);
  ASSERT_GT(a.kps.size(), 100u);
  const TInvariance r = invariance(a, b, M, 90.0, cv::Point2f(200, 200), 150);
  EXPECT_GT(r.pairs, 50);
  EXPECT_GT(r.nnCorrect, 0.9) << r.pairs << " pairs";
  EXPECT_LT(r.medianAngleErr, 3.0);
}

TEST(CSurf, DescriptorsAreInvariantToRotationBy30Degrees)
{
  const cv::Mat img = texturedImage(400, 11);
  const cv::Mat M = cv::getRotationMatrix2D(cv::Point2f(199.5f, 199.5f), -30.0, 1.0);
  cv::Mat rot;
  cv::warpAffine(img, rot, M, img.size(), cv::INTER_LINEAR, cv::BORDER_REFLECT);
  const TDetection a = run(img), b = run(rot);
  const TInvariance r = invariance(a, b, M, 30.0, cv::Point2f(200, 200), 130);
  EXPECT_GT(r.pairs, 40);
  EXPECT_GT(r.nnCorrect, 0.7) << r.pairs << " pairs";
  EXPECT_LT(r.medianAngleErr, 8.0);
}

TEST(CSurf, SamePointIsMuchCloserThanDifferentPoints)
{
  const cv::Mat img = texturedImage(400, 3);
  const cv::Mat M = cv::getRotationMatrix2D(cv::Point2f(199.5f, 199.5f), -30.0, 1.0);
  cv::Mat rot;
  cv::warpAffine(img, rot, M, img.size(), cv::INTER_LINEAR, cv::BORDER_REFLECT);
  const TDetection a = run(img), b = run(rot);
  std::vector<double> same, different;
  for (size_t i = 0; i < a.kps.size(); ++i)
  {
    const cv::Point2f p = a.kps[i].pt;
    if (cv::norm(p - cv::Point2f(200, 200)) > 130)
      continue;
    const cv::Point2f q(
        static_cast<float>(
            M.at<double>(0, 0) * p.x + M.at<double>(0, 1) * p.y + M.at<double>(0, 2)),
        static_cast<float>(
            M.at<double>(1, 0) * p.x + M.at<double>(1, 1) * p.y + M.at<double>(1, 2)));
    const int j = nearest(b.kps, q, 1.5f);
    if (j < 0)
      continue;
    same.push_back(cv::norm(a.desc.row(static_cast<int>(i)), b.desc.row(j)));
    const int other = (j + static_cast<int>(b.kps.size()) / 2) % static_cast<int>(b.kps.size());
    different.push_back(cv::norm(a.desc.row(static_cast<int>(i)), b.desc.row(other)));
  }
  ASSERT_GT(same.size(), 30u);
  std::sort(same.begin(), same.end());
  std::sort(different.begin(), different.end());
  const double medSame = same[same.size() / 2], medDiff = different[different.size() / 2];
  EXPECT_LT(medSame, 0.4 * medDiff)
      << "median distance same " << medSame << " vs different " << medDiff;
}

TEST(CSurf, UprightGivesZeroAngleAndOrientedDoesNot)
{
  const cv::Mat img = texturedImage(300, 5);
  CSurf::TParams p;
  p.upright = true;
  const TDetection up = run(img, p);
  ASSERT_FALSE(up.kps.empty());
  for (const auto& kp : up.kps)
    EXPECT_EQ(kp.angle, 0.0f);
  const TDetection oriented = run(img);
  const auto nonZero = std::count_if(
      oriented.kps.begin(), oriented.kps.end(),
      [](const cv::KeyPoint& k) { return k.angle != 0.0f; });
  EXPECT_GT(nonZero, static_cast<long>(oriented.kps.size() / 2));
  for (const auto& kp : oriented.kps)
  {
    EXPECT_GE(kp.angle, 0.0f);
    EXPECT_LT(kp.angle, 360.0f);
  }
}

TEST(CSurf, DescriptorSizeUnitLengthAndExtended)
{
  const cv::Mat img = texturedImage(300, 9);
  const TDetection d64 = run(img);
  CSurf::TParams p;
  p.extended = true;
  const TDetection d128 = run(img, p);
  ASSERT_FALSE(d64.kps.empty());
  EXPECT_EQ(d64.desc.cols, 64);
  EXPECT_EQ(d128.desc.cols, 128);
  EXPECT_EQ(d64.desc.type(), CV_32F);
  EXPECT_EQ(d64.desc.rows, static_cast<int>(d64.kps.size()));
  EXPECT_EQ(d128.kps.size(), d64.kps.size());  // same detector
  EXPECT_EQ(CSurf::create(p)->descriptorSize(), 128);
  for (int r = 0; r < d128.desc.rows; ++r)
  {
    EXPECT_NEAR(cv::norm(d64.desc.row(r)), 1.0, 1e-4);
    EXPECT_NEAR(cv::norm(d128.desc.row(r)), 1.0, 1e-4);
  }
}

TEST(CSurf, CapKeepsTheStrongest)
{
  const cv::Mat img = texturedImage(400, 13);
  const TDetection all = run(img);
  ASSERT_GT(all.kps.size(), 60u);
  CSurf::TParams p;
  p.maxFeatures = 50;
  const TDetection capped = run(img, p);
  ASSERT_EQ(capped.kps.size(), 50u);
  std::vector<float> resp;
  for (const auto& k : all.kps)
    resp.push_back(k.response);
  std::sort(resp.begin(), resp.end(), std::greater<float>());
  const float fiftieth = resp[49];
  for (const auto& k : capped.kps)
    EXPECT_GE(k.response, fiftieth);
  for (size_t i = 1; i < capped.kps.size(); ++i)
    EXPECT_GE(capped.kps[i - 1].response, capped.kps[i].response);
  // The capped set is the head of the uncapped one, descriptors included.
  for (int i = 0; i < 50; ++i)
  {
    EXPECT_EQ(capped.kps[i].pt, all.kps[i].pt);
    EXPECT_EQ(cv::norm(capped.desc.row(i), all.desc.row(i), cv::NORM_INF), 0.0);
  }
}

TEST(CSurf, HigherThresholdGivesFewerKeypoints)
{
  const cv::Mat img = texturedImage(400, 17);
  CSurf::TParams p;
  p.hessianThreshold = 2000;
  const TDetection strict = run(img, p);
  const TDetection lax = run(img);
  EXPECT_LT(strict.kps.size(), lax.kps.size());
  for (const auto& k : strict.kps)
    EXPECT_GT(k.response, 2000.0f * 0.9f);
}

TEST(CSurf, DeterministicAcrossRunsAndThreadCounts)
{
  const cv::Mat img = texturedImage(400, 21);
  const int threads = cv::getNumThreads();
  const TDetection a = run(img);
  const TDetection b = run(img);
  cv::setNumThreads(1);
  const TDetection c = run(img);
  cv::setNumThreads(threads);
  ASSERT_EQ(a.kps.size(), b.kps.size());
  ASSERT_EQ(a.kps.size(), c.kps.size());
  for (size_t i = 0; i < a.kps.size(); ++i)
  {
    EXPECT_EQ(a.kps[i].pt, c.kps[i].pt);
    EXPECT_EQ(a.kps[i].size, c.kps[i].size);
    EXPECT_EQ(a.kps[i].angle, c.kps[i].angle);
  }
  EXPECT_EQ(cv::norm(a.desc, b.desc, cv::NORM_INF), 0.0);
  EXPECT_EQ(cv::norm(a.desc, c.desc, cv::NORM_INF), 0.0);
}

TEST(CSurf, MaskRestrictsDetection)
{
  const cv::Mat img = texturedImage(400, 23);
  cv::Mat mask = cv::Mat::zeros(img.size(), CV_8UC1);
  const cv::Rect roi(100, 120, 180, 150);
  mask(roi).setTo(255);
  const TDetection d = run(img, CSurf::TParams(), mask);
  ASSERT_FALSE(d.kps.empty());
  const cv::Rect2f grown(roi.x - 0.5f, roi.y - 0.5f, roi.width + 1.0f, roi.height + 1.0f);
  for (const auto& k : d.kps)
    EXPECT_TRUE(grown.contains(k.pt)) << k.pt;
  EXPECT_LT(d.kps.size(), run(img).kps.size());
}

TEST(CSurf, ComputeOnProvidedKeypointsMatchesDetectAndCompute)
{
  const cv::Mat img = texturedImage(300, 29);
  auto surf = CSurf::create();
  std::vector<cv::KeyPoint> kps;
  surf->detect(img, kps);
  ASSERT_FALSE(kps.empty());
  cv::Mat desc;
  std::vector<cv::KeyPoint> kps2 = kps;
  surf->compute(img, kps2, desc);
  const TDetection full = run(img);
  ASSERT_EQ(kps2.size(), full.kps.size());
  EXPECT_EQ(cv::norm(desc, full.desc, cv::NORM_INF), 0.0);
  for (size_t i = 0; i < kps.size(); ++i)
    EXPECT_EQ(kps2[i].class_id, kps[i].class_id);
}

TEST(CSurf, ColourAndEmptyImages)
{
  const cv::Mat grey = texturedImage(200, 31);
  cv::Mat bgr;
  cv::cvtColor(grey, bgr, cv::COLOR_GRAY2BGR);
  EXPECT_EQ(run(bgr).kps.size(), run(grey).kps.size());
  EXPECT_TRUE(run(cv::Mat()).kps.empty());
  // A flat image has no interest points.
  EXPECT_TRUE(run(cv::Mat(240, 320, CV_8UC1, cv::Scalar(77))).kps.empty());
  // Too small for even one octave: no keypoints, no crash.
  EXPECT_TRUE(run(texturedImage(20, 1)).kps.empty());
  const cv::Mat f32(100, 100, CV_32F, cv::Scalar(0));
  EXPECT_THROW(run(f32), std::invalid_argument);
}

TEST(CSurf, InvalidParametersThrowNamingTheParameter)
{
  const auto expectThrow = [](const CSurf::TParams& p, const std::string& name)
  {
    try
    {
      CSurf::create(p);
      ADD_FAILURE() << "no exception for bad " << name;
    }
    catch (const std::invalid_argument& e)
    {
      EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
    }
  };
  CSurf::TParams p;
  p.hessianThreshold = -1;
  expectThrow(p, "hessianThreshold");
  p = CSurf::TParams();
  p.hessianThreshold = std::nan("");
  expectThrow(p, "hessianThreshold");
  p = CSurf::TParams();
  p.nOctaves = 0;
  expectThrow(p, "nOctaves");
  p = CSurf::TParams();
  p.nOctaveLayers = 0;
  expectThrow(p, "nOctaveLayers");
  p = CSurf::TParams();
  p.maxFeatures = -5;
  expectThrow(p, "maxFeatures");
  EXPECT_NO_THROW(CSurf::create());
  EXPECT_EQ(CSurf::create()->params().hessianThreshold, 100);
  EXPECT_EQ(CSurf::create()->params().nOctaves, 4);
  EXPECT_EQ(CSurf::create()->params().nOctaveLayers, 3);
}
