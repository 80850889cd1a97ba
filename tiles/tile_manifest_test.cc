#include "tiles/tile_manifest.h"

#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "tests/support/test_support.h"

namespace sacfuse {
namespace {

using testing::TempDir;

TileManifest Example() {
  TileManifest m;
  m.config_hash = "0123456789abcdef";
  m.tile_size_m = 20.0;
  m.grid_x = 3;
  m.grid_y = 2;
  m.scale_m = 0.001;
  m.offset = {412000.0, 5411000.0, 0.0};
  m.tiles = {"0_0", "1_0", "0_1"};
  m.tiles_without_views = 3;
  return m;
}

TEST(TileManifestTest, WriteThenReadGivesTheSameManifest) {
  TempDir dir;
  const std::string d = dir.path().string();
  EXPECT_FALSE(TileManifest::Read(d).has_value());  // none yet
  Example().Write(d);
  EXPECT_EQ(TileManifest::Path(d), (dir / "manifest.json").string());
  const std::optional<TileManifest> m = TileManifest::Read(d);
  ASSERT_TRUE(m.has_value());
  EXPECT_EQ(m->config_hash, "0123456789abcdef");
  EXPECT_DOUBLE_EQ(m->tile_size_m, 20.0);
  EXPECT_EQ(m->grid_x, 3);
  EXPECT_EQ(m->grid_y, 2);
  EXPECT_DOUBLE_EQ(m->scale_m, 0.001);
  EXPECT_EQ(m->offset, Eigen::Vector3d(412000.0, 5411000.0, 0.0));
  EXPECT_EQ(m->tiles, (std::vector<std::string>{"0_0", "1_0", "0_1"}));
  EXPECT_EQ(m->tiles_without_views, 3u);
}

TEST(TileManifestTest, FileKeepsItsKeys) {
  TempDir dir;
  Example().Write(dir.path().string());
  std::ifstream in(dir / "manifest.json");
  const nlohmann::json j = nlohmann::json::parse(in);
  for (const char* key : {"config_hash", "tile_size_m", "grid", "scale_m", "offset", "tiles", "tiles_without_views"}) {
    EXPECT_TRUE(j.contains(key)) << key;
  }
  EXPECT_EQ(j.at("grid"), nlohmann::json({3, 2}));
}

TEST(TileManifestTest, OnlyTheTileListIsRequired) {
  TempDir dir;
  std::ofstream(dir / "manifest.json") << R"({"tile_size_m": 40.0, "tiles": ["2_3"]})";
  const std::optional<TileManifest> m = TileManifest::Read(dir.path().string());
  ASSERT_TRUE(m.has_value());
  EXPECT_DOUBLE_EQ(m->tile_size_m, 40.0);
  EXPECT_EQ(m->tiles, std::vector<std::string>{"2_3"});
  EXPECT_EQ(m->config_hash, "");
}

TEST(TileManifestTest, UnreadableManifestThrowsNamingTheFile) {
  TempDir dir;
  std::ofstream(dir / "manifest.json") << R"({"tile_size_m": 40.0)";  // cut short
  try {
    TileManifest::Read(dir.path().string());
    FAIL() << "no exception";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("manifest.json unreadable"), std::string::npos) << e.what();
  }
  std::ofstream(dir / "manifest.json") << R"({"tile_size_m": 40.0})";  // no tile list
  EXPECT_THROW(TileManifest::Read(dir.path().string()), Error);
}

}  // namespace
}  // namespace sacfuse
