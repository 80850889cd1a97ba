#include "jobs/cluster_table_cache.h"

#include <gtest/gtest.h>

#include "core/error.h"
#include "io/superpixel_io.h"
#include "tests/support/test_support.h"

namespace sacfuse {
namespace {

// A w x h map with one cluster per row.
std::string WriteRowClusters(const testing::TempDir& dir, const std::string& name, int w, int h) {
  SuperpixelMap map;
  map.width = w;
  map.height = h;
  std::vector<int32_t> labels;
  for (int r = 0; r < h; ++r) {
    for (int c = 0; c < w; ++c) labels.push_back(r);
    SuperpixelCluster cl;
    cl.centroid_col = w / 2.0f;
    cl.centroid_row = r + 0.5f;
    cl.depth_m = 10.0f + r;
    cl.pixel_count = static_cast<uint32_t>(w);
    cl.valid_count = static_cast<uint32_t>(w);
    map.clusters.push_back(cl);
  }
  map.labels = SuperpixelLabels(w, h, labels);
  const std::string path = (dir / name).string();
  WriteSuperpixels(path, map, 1);
  return path;
}

TEST(ClusterTableCacheTest, HitsReuseTheTableAndTheBudgetEvictsLeastRecentlyUsed) {
  testing::TempDir dir;
  const std::string a = WriteRowClusters(dir, "a.spx", 4, 10), b = WriteRowClusters(dir, "b.spx", 4, 10),
                    c = WriteRowClusters(dir, "c.spx", 4, 10);
  const uint64_t table_bytes = 10 * sizeof(SuperpixelCluster);
  ClusterTableCache cache(2 * table_bytes);  // room for two tables
  const auto ta = cache.Get(a);
  ASSERT_EQ(ta->size(), 10u);
  EXPECT_EQ((*ta)[3].depth_m, 13.0f);
  EXPECT_EQ(cache.Get(a).get(), ta.get());  // hit: the same table
  cache.Get(b);
  cache.Get(a);  // a is now the most recent
  cache.Get(c);  // evicts b
  EXPECT_EQ(cache.bytes(), 2 * table_bytes);
  EXPECT_EQ(cache.misses(), 3u);
  EXPECT_EQ(cache.hits(), 2u);
  EXPECT_EQ(cache.Get(a).get(), ta.get());
  EXPECT_EQ(cache.misses(), 3u);
  cache.Get(b);  // was evicted: read again
  EXPECT_EQ(cache.misses(), 4u);
  EXPECT_LE(cache.bytes(), 2 * table_bytes);
  EXPECT_THROW(cache.Get((dir / "missing.spx").string()), InputError);
}

}  // namespace
}  // namespace sacfuse
