/* roi-graphslam built without the live view (ROISLAM_WITH_GUI=OFF, or
 * MRPT without wxWidgets): --gui fails at once with one line saying so,
 * exit code 1, and writes nothing; without --gui the run is unchanged (the
 * other app tests of this build). Added by tests/gui/CMakeLists.txt only
 * in that configuration. */
#include <gtest/gtest.h>
#include <roislam/testing/TestData.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace fs = std::filesystem;

TEST(BuiltWithoutGui, GuiFlagSaysSoInOneLine)
{
  ROISLAM_REQUIRE_SYNTHETIC(seq, "textured");
  const std::string dir = roislam::testing::makeTempDir("nogui");
  const std::string exe = roislam::testing::binaryDir() + "/apps/roi-graphslam/roi-graphslam";
  for (const std::string& flag : {std::string("--gui"), "--gui-screenshot " + dir + "/w.png"})
  {
    const int rc = std::system((exe + " --input " + seq + " --output-dir " + dir + "/out " + flag +
                                " > /dev/null 2> " + dir + "/err")
                                   .c_str());
    ASSERT_TRUE(WIFEXITED(rc));
    EXPECT_EQ(WEXITSTATUS(rc), 1) << flag;
    std::ifstream f(dir + "/err");
    std::stringstream ss;
    ss << f.rdbuf();
    const std::string err = ss.str();
    EXPECT_EQ(
        err,
        "roi-graphslam: error: --gui: roi-graphslam was built without GUI (MRPT's "
        "wxWidgets windows were not found)\n");
    EXPECT_FALSE(fs::exists(dir + "/out")) << flag;
    EXPECT_FALSE(fs::exists(dir + "/w.png")) << flag;
  }
  fs::remove_all(dir);
}
