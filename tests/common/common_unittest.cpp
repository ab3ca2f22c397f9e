#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <roislam/common/IniErrors.h>
#include <roislam/common/IniKeyCheck.h>
#include <roislam/common/IniRead.h>
#include <roislam/common/ProcessTuning.h>
#include <roislam/common/StringLists.h>

#include <cstdlib>
#include <stdexcept>
#if defined(__GLIBC__)
#include <malloc.h>
#endif
#include <vector>

using namespace roislam::common;

TEST(StringLists, SplitTrimsAndDropsEmptyItems)
{
  const std::vector<std::string> expected{"sift", "orb", "surf x"};
  EXPECT_EQ(splitList(" sift,\torb ,, surf x ,"), expected);
  EXPECT_TRUE(splitList("").empty());
  EXPECT_TRUE(splitList(" , \t,").empty());
}

TEST(StringLists, JoinIsTheInverseOfSplit)
{
  const std::vector<std::string> items{"1", "2", "3"};
  EXPECT_EQ(joinList(items), "1,2,3");
  EXPECT_EQ(splitList(joinList(items)), items);
  EXPECT_EQ(joinList({}), "");
}

TEST(IniErrors, MessageNamesSectionAndKey)
{
  try
  {
    throwBadIniKey("FrontEnd", "min_inliers", "must be >= 3");
    FAIL() << "no exception";
  }
  catch (const std::invalid_argument& e)
  {
    EXPECT_STREQ(e.what(), "[FrontEnd] min_inliers: must be >= 3");
  }
}

namespace
{
// Options that, like the front end's, save a sub-component into a fixed section.
struct TNested : public mrpt::config::CLoadableOptions
{
  void loadFromConfigFile(const mrpt::config::CConfigFileBase&, const std::string&) override {}
  void saveToConfigFile(mrpt::config::CConfigFileBase& c, const std::string& s) const override
  {
    c.write(s, "alpha", 1);
    c.write(s, "Beta", 2);
    c.write("Child", "gamma", 3);
  }
};
}  // namespace

TEST(IniKeyCheck, KnownKeysOfTheOwnAndOfAFixedSubSection)
{
  const TNested o;
  EXPECT_EQ(knownIniKeys(o), (std::vector<std::string>{"alpha", "Beta"}));
  EXPECT_EQ(knownIniKeys(o, "Parent"), (std::vector<std::string>{"alpha", "Beta"}));
  EXPECT_EQ(knownIniKeys(o, "Parent", "Child"), (std::vector<std::string>{"gamma"}));
  EXPECT_TRUE(knownIniKeys(o, "Parent", "Other").empty());

  mrpt::config::CConfigFileMemory cfg;
  cfg.write("Parent", "ALPHA", 5);  // case-insensitive, as MRPT's reader
  EXPECT_NO_THROW(checkIniKeys(cfg, "Parent", knownIniKeys(o, "Parent"), "t.ini"));
  cfg.write("Child", "alpha", 5);
  EXPECT_THROW(
      checkIniKeys(cfg, "Child", knownIniKeys(o, "Parent", "Child"), "t.ini"), std::runtime_error);
}

TEST(IniRead, StrictValues)
{
  EXPECT_EQ(parseDouble("2.5e-3"), 2.5e-3);
  EXPECT_EQ(parseDouble("+4"), 4.0);
  for (const char* bad : {"", "abc", "1.5x", "inf", "nan", " 1", "--1"})
    EXPECT_FALSE(parseDouble(bad)) << bad;
  EXPECT_EQ(parseInt("-7"), -7);
  EXPECT_FALSE(parseInt("2.5"));
  EXPECT_FALSE(parseInt("99999999999"));
  EXPECT_EQ(parseUnsigned("4294967295"), 4294967295u);
  EXPECT_FALSE(parseUnsigned("-1"));
  EXPECT_FALSE(parseUnsigned("4294967296"));
  EXPECT_EQ(parseBool("Yes"), true);
  EXPECT_EQ(parseBool("off"), false);
  EXPECT_FALSE(parseBool("maybe"));

  mrpt::config::CConfigFileMemory cfg;
  cfg.write("S", "x", "  0.25 ");
  cfg.write("S", "n", "abc");
  cfg.write("S", "empty", "");
  EXPECT_EQ(readDouble(cfg, "S", "x", 1.0), 0.25);
  EXPECT_EQ(readDouble(cfg, "S", "absent", 1.0), 1.0);
  EXPECT_EQ(readInt(cfg, "S", "empty", 3), 3);
  try
  {
    readDouble(cfg, "S", "n", 0.0);
    FAIL() << "no exception";
  }
  catch (const std::invalid_argument& e)
  {
    EXPECT_STREQ(e.what(), "[S] n: not a number: 'abc'");
  }
  EXPECT_THROW(readBool(cfg, "S", "x", false), std::invalid_argument);
  EXPECT_NO_THROW(require(true, "S", "x", 0.25, "> 0"));
  try
  {
    require(false, "S", "x", -1, "> 0");
    FAIL() << "no exception";
  }
  catch (const std::invalid_argument& e)
  {
    EXPECT_STREQ(e.what(), "[S] x: must be > 0 (got -1)");
  }
}

TEST(ProcessTuning, LargeImageBuffersComeFromTheHeap)
{
#if defined(__GLIBC__)
  tuneAllocatorForImages();
  // A 20 MB buffer (an upsampled SIFT pyramid level is about that) must not be
  // a fresh mmap: that is what cost a page fault per page every frame.
  const auto before = mallinfo2().hblkhd;
  std::vector<float> buffer(5u * 1024u * 1024u, 1.0f);
  EXPECT_EQ(mallinfo2().hblkhd, before);
  EXPECT_FLOAT_EQ(buffer.back(), 1.0f);
#else
  GTEST_SKIP() << "allocator tuning applies to glibc only";
#endif
}
