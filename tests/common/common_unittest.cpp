#include <gtest/gtest.h>
#include <roislam/common/IniErrors.h>
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
