#include "io/colmap_patch_match_config.h"

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/error.h"
#include "tests/support/test_support.h"

namespace sacfuse {
namespace {

using sacfuse::testing::TempDir;

std::string Write(const TempDir& tmp, const std::string& contents) {
  const std::string path = (tmp.path() / "patch-match.cfg").string();
  std::ofstream(path, std::ios::binary) << contents;
  return path;
}

std::vector<View> Views(const std::vector<std::string>& names) {
  std::vector<View> views(names.size());
  for (size_t i = 0; i < names.size(); ++i) {
    views[i].index = static_cast<uint32_t>(i);
    views[i].name = names[i];
  }
  return views;
}

std::string ErrorOf(const std::string& path) {
  try {
    ReadPatchMatchConfig(path);
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), path);
    return e.message();
  }
  ADD_FAILURE() << "expected an InputError for " << path;
  return "";
}

TEST(PatchMatchConfigTest, ReadsNamedAndAutomaticSources) {
  TempDir tmp;
  // Whitespace, CRLF and empty lines as COLMAP tolerates them; image names with sub-folders and spaces.
  const std::string path = Write(tmp, "a/x 1.jpg\r\n  b.jpg , c.jpg\n\nb.jpg\n__auto__, 20\nc.jpg\n__all__\n");
  const std::vector<PatchMatchEntry> entries = ReadPatchMatchConfig(path);
  ASSERT_EQ(entries.size(), 3u);
  EXPECT_EQ(entries[0].image, "a/x 1.jpg");
  EXPECT_EQ(entries[0].sources, (std::vector<std::string>{"b.jpg", "c.jpg"}));
  EXPECT_FALSE(entries[0].automatic);
  EXPECT_EQ(entries[0].line, 1);
  EXPECT_EQ(entries[1].image, "b.jpg");
  EXPECT_TRUE(entries[1].automatic);
  EXPECT_TRUE(entries[1].sources.empty());
  EXPECT_EQ(entries[1].line, 4);
  EXPECT_TRUE(entries[2].automatic);
}

TEST(PatchMatchConfigTest, MalformedFilesNameTheLine) {
  TempDir tmp;
  EXPECT_NE(ErrorOf(Write(tmp, "a.jpg\nb.jpg\nb.jpg\n")).find("line 3: image \"b.jpg\" has no sources line"),
            std::string::npos);
  EXPECT_NE(ErrorOf(Write(tmp, "a.jpg\nb.jpg\na.jpg\nc.jpg\n")).find("line 3: image \"a.jpg\" is listed twice"),
            std::string::npos);
  EXPECT_NE(ErrorOf(Write(tmp, "a.jpg\nb.jpg,,c.jpg\n")).find("line 2 (sources of \"a.jpg\"): an empty image name"),
            std::string::npos);
  EXPECT_NE(ErrorOf(Write(tmp, "a.jpg\nb.jpg, a.jpg\n")).find("listed among its own sources"), std::string::npos);
  EXPECT_NE(ErrorOf(Write(tmp, "a.jpg\n__auto__, x\n")).find("is not \"__auto__, N\""), std::string::npos);
  EXPECT_NE(ErrorOf(Write(tmp, "a.jpg\n__auto__\n")).find("is not \"__auto__, N\""), std::string::npos);
  EXPECT_NE(ErrorOf((tmp.path() / "absent.cfg").string()).find("missing"), std::string::npos);
}

TEST(PatchMatchConfigTest, PartnersAreSymmetricAndSkipImagesNotFused) {
  // a lists b and d; c lists b; d is not fused (left out): a-b, b-c.
  const std::vector<PatchMatchEntry> entries = {
      {"a", {"b", "d"}, false, 1}, {"c", {"b"}, false, 3}, {"d", {"a", "c"}, false, 5}};
  const std::vector<std::vector<uint32_t>> partners = MatchingPartners(entries, Views({"c", "b", "a"}));
  ASSERT_EQ(partners.size(), 3u);
  EXPECT_EQ(partners[0], (std::vector<uint32_t>{1}));     // c: b
  EXPECT_EQ(partners[1], (std::vector<uint32_t>{0, 2}));  // b: c, a (sorted by view index)
  EXPECT_EQ(partners[2], (std::vector<uint32_t>{1}));     // a: b
}

TEST(PatchMatchConfigTest, AutomaticSourcesLeaveEveryViewUnknown) {
  const std::vector<PatchMatchEntry> entries = {{"a", {"b"}, false, 1}, {"b", {}, true, 3}};
  for (const auto& p : MatchingPartners(entries, Views({"a", "b"}))) EXPECT_TRUE(p.empty());
  // An automatic entry of an image that is not fused (left out) says nothing about the fused ones.
  const std::vector<PatchMatchEntry> left_out = {{"a", {"c"}, false, 1}, {"b", {}, true, 3}};
  const std::vector<std::vector<uint32_t>> partners = MatchingPartners(left_out, Views({"a", "c"}));
  EXPECT_EQ(partners[0], (std::vector<uint32_t>{1}));
  EXPECT_EQ(partners[1], (std::vector<uint32_t>{0}));
}

}  // namespace
}  // namespace sacfuse
