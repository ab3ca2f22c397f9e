/* graph.graph written and read back without loss (GraphText.h): every
 * number of a graph with full information matrices comes back as it was,
 * MRPT's own reader still opens the file, and a bad file gives one line
 * naming the file and the line. */
#include <gtest/gtest.h>
#include <roislam/common/TextFiles.h>
#include <roislam/io/GraphText.h>
#include <roislam/testing/TestData.h>

#include <Eigen/Cholesky>
#include <algorithm>
#include <filesystem>
#include <random>
#include <string>

namespace fs = std::filesystem;
using roislam::io::loadGraphText;
using roislam::io::saveGraphText;
using TGraph = mrpt::graphs::CNetworkOfPoses3DInf;

namespace
{
/** A positive-definite information with every entry non-zero, of the
 *  spread of a real edge's (1e2 to 1e6). */
mrpt::math::CMatrixDouble66 randomInformation(std::mt19937& rng)
{
  std::normal_distribution<double> n(0, 1);
  Eigen::Matrix<double, 6, 6> A;
  for (int r = 0; r < 6; ++r)
    for (int c = 0; c < 6; ++c)
      A(r, c) = n(rng) * (r < 3 ? 300.0 : 1000.0);
  return mrpt::math::CMatrixDouble66(Eigen::Matrix<double, 6, 6>(A.transpose() * A));
}

/** Largest difference of two poses' rotation matrix and translation entries. */
double poseDifference(const mrpt::poses::CPose3D& a, const mrpt::poses::CPose3D& b)
{
  return std::max(
      (a.getRotationMatrix().asEigen() - b.getRotationMatrix().asEigen()).cwiseAbs().maxCoeff(),
      (a.translation() - b.translation()).norm());
}

TGraph sampleGraph()
{
  std::mt19937 rng(7);
  TGraph g;
  g.nodes[0] = mrpt::poses::CPose3D();
  // Far out, with large and awkward angles, and digits beyond the sixth.
  g.nodes[1] = mrpt::poses::CPose3D(2.000001234567, -0.3141592653589, 1.23456789012, 0.1, 0.2, 0.3);
  g.nodes[4] = mrpt::poses::CPose3D(-3.9876543210123, 5.5, 0.000012345678, 3.0, -1.2, -2.9);
  g.root = 0;
  for (const auto& [a, b] : {std::pair<int, int>{0, 1}, {1, 4}, {0, 4}})
  {
    mrpt::poses::CPose3DPDFGaussianInf e;
    e.mean = g.nodes[b] - g.nodes[a] + mrpt::poses::CPose3D(1e-7, -2e-7, 3e-7, 1e-6, 2e-6, -3e-6);
    e.cov_inv = randomInformation(rng);
    g.insertEdge(a, b, e);
  }
  return g;
}

std::string tempFile(const std::string& name, const std::string& content)
{
  const std::string dir = roislam::testing::makeTempDir("graph_text");
  const std::string f = dir + "/" + name;
  roislam::common::writeFileAtomically(f, content);
  return f;
}

std::string loadError(const std::string& content)
{
  const std::string f = tempFile("bad.graph", content);
  try
  {
    loadGraphText(f);
  }
  catch (const std::runtime_error& e)
  {
    fs::remove_all(fs::path(f).parent_path());
    return e.what();
  }
  fs::remove_all(fs::path(f).parent_path());
  return "";
}
}  // namespace

TEST(GraphText, RoundTripKeepsEveryNumber)
{
  const TGraph g = sampleGraph();
  const std::string dir = roislam::testing::makeTempDir("graph_text");
  saveGraphText(g, dir + "/g.graph");
  const TGraph h = loadGraphText(dir + "/g.graph");
  EXPECT_EQ(h.root, g.root);
  ASSERT_EQ(h.nodes.size(), g.nodes.size());
  for (const auto& [id, p] : g.nodes)
  {
    ASSERT_TRUE(h.nodes.count(id)) << id;
    // Poses go through roll / pitch / yaw: equal to rounding.
    EXPECT_LT(poseDifference(h.nodes.at(id), p), 1e-14) << id;
  }
  ASSERT_EQ(h.edges.size(), g.edges.size());
  for (const auto& [ids, e] : g.edges)
  {
    const auto it = h.edges.find(ids);
    ASSERT_NE(it, h.edges.end());
    EXPECT_LT(poseDifference(it->second.mean, e.mean), 1e-14);
    // The information, every entry, bit for bit (17 digits).
    EXPECT_EQ(it->second.cov_inv.asEigen(), e.cov_inv.asEigen())
        << "written\n"
        << e.cov_inv.asEigen() << "\nread\n"
        << it->second.cov_inv.asEigen();
  }
  fs::remove_all(dir);
}

TEST(GraphText, MrptOpensTheFile)
{
  // MRPT's graph-slam tool reads it: nodes, root, edges and their means
  // (its reader drops the rotation block's off-diagonal information, which
  // is why loadGraphText exists: compare the diagonal only).
  const TGraph g = sampleGraph();
  const std::string dir = roislam::testing::makeTempDir("graph_text");
  saveGraphText(g, dir + "/g.graph");
  TGraph m;
  m.loadFromTextFile(dir + "/g.graph");
  EXPECT_EQ(m.root, g.root);
  ASSERT_EQ(m.nodes.size(), g.nodes.size());
  ASSERT_EQ(m.edges.size(), g.edges.size());
  for (const auto& [ids, e] : g.edges)
  {
    const auto it = m.edges.find(ids);
    ASSERT_NE(it, m.edges.end());
    EXPECT_LT(poseDifference(it->second.mean, e.mean), 1e-12);
    for (int k = 0; k < 6; ++k)
      EXPECT_EQ(it->second.cov_inv(k, k), e.cov_inv(k, k));
  }
  fs::remove_all(dir);
}

TEST(GraphText, SixDigitsWouldNotDo)
{
  // What MRPT's own writer (6 significant digits) loses, ours keeps.
  const TGraph g = sampleGraph();
  const std::string dir = roislam::testing::makeTempDir("graph_text");
  g.saveToTextFile(dir + "/mrpt.graph");
  EXPECT_NE(loadGraphText(dir + "/mrpt.graph").nodes.at(1).x(), g.nodes.at(1).x());
  saveGraphText(g, dir + "/ours.graph");
  EXPECT_DOUBLE_EQ(loadGraphText(dir + "/ours.graph").nodes.at(1).x(), g.nodes.at(1).x());
  fs::remove_all(dir);
}

TEST(GraphText, BadFilesGiveOneLineNamingFileAndLine)
{
  const std::string v0 = "VERTEX3 0 0 0 0 0 0 0\n", v1 = "VERTEX3 1 1 0 0 0 0 0\n";
  std::string inf;
  for (int k = 0; k < 21; ++k)
    inf += (k == 0 || k == 6 || k == 11 || k == 15 || k == 18 || k == 20) ? " 1" : " 0";
  const std::string edge = "EDGE3 0 1 1 0 0 0 0 0" + inf + "\n";
  // A good file first: comments and blank lines are allowed.
  const std::string good = tempFile("good.graph", "# a graph\n\n" + v0 + "FIX 0\n" + v1 + edge);
  EXPECT_EQ(loadGraphText(good).edges.size(), 1u);
  fs::remove_all(fs::path(good).parent_path());

  const auto expectError =
      [](const std::string& err, const std::string& where, const std::string& what)
  {
    EXPECT_NE(err.find("bad.graph" + where), std::string::npos) << err;
    EXPECT_NE(err.find(what), std::string::npos) << err;
    EXPECT_EQ(err.find('\n'), std::string::npos) << err;
  };
  expectError(loadError(v0 + "VERTEX2 1 0 0 0\n"), ":2:", "unknown line 'VERTEX2'");
  expectError(loadError(v0 + "VERTEX3 1 0 0 zero 0 0 0\n"), ":2:", "malformed VERTEX3");
  expectError(loadError(v0 + "VERTEX3 1 0 0 0 0 0 0 7\n"), ":2:", "malformed VERTEX3");
  expectError(loadError(v0 + "VERTEX3 0 1 0 0 0 0 0\n"), ":2:", "node 0 listed twice");
  expectError(loadError(v0 + "FIX\n"), ":2:", "malformed FIX");
  expectError(
      loadError(v0 + v1 + "EDGE3 0 1 1 0 0 0 0 0" + inf.substr(2) + "\n"),
      ":3:", "malformed EDGE3");
  expectError(
      loadError(v0 + v1 + "EDGE3 0 1 1 0 0 0 nan 0" + inf + "\n"), ":3:", "malformed EDGE3");
  expectError(loadError(v0 + "EDGE3 0 7 1 0 0 0 0 0" + inf + "\n"), ": EDGE3 0 7", "no node 7");
  expectError(loadError(v0 + "FIX 3\n"), ": FIX 3", "no such node");
  expectError(loadError(v0 + "EDGE3 0 0 1 0 0 0 0 0" + inf + "\n"), ":2:", "to itself");
  expectError(loadError("# nothing\n"), ": no nodes", "VERTEX3");
  const std::string missing = roislam::testing::makeTempDir("graph_text") + "/none.graph";
  try
  {
    loadGraphText(missing);
    ADD_FAILURE() << "no error for a missing file";
  }
  catch (const std::runtime_error& e)
  {
    EXPECT_NE(std::string(e.what()).find(missing), std::string::npos) << e.what();
  }
  fs::remove_all(fs::path(missing).parent_path());
}
