// CopcWriter (io/copc_writer.h) on hand-made clouds: the cube and node keys (io/copc_octree.h) on known numbers,
// the per-cell choice, and whole files read back: every point exactly once (the same multiset as written), every
// point inside its node's cube as readers compute it, the upper levels one point per cell of their 128^3 grid
// (checked with the readers' floating-point bounds, not with the writer's integer cells), leaves within
// max_node_points, hierarchy pages, `sacfuse validate`'s rules (io/copc_validate.h) passing; the out-of-core path
// (buckets of a few thousand points); the parallel choice of a node's points against a serial one; the same bytes
// for one, two and four threads; empty and 1-point files; refused
// options; no file or work folder left by a writer destroyed before Close(); and broken files found by the
// validator.
#include "io/copc_writer.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <set>
#include <tuple>

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include "core/error.h"
#include "io/copc_format.h"
#include "io/copc_hierarchy.h"
#include "io/copc_octree.h"
#include "io/copc_validate.h"
#include "io/las_format.h"
#include "io/las_reader.h"
#include "io/las_validate.h"
#include "io/laz_chunk_codec.h"
#include "io/laz_vlr.h"
#include "tests/support/log_capture.h"
#include "tests/support/test_support.h"

namespace sacfuse {
namespace {

namespace fs = std::filesystem;
namespace lf = las_format;
using copc::Entry;
using copc::VoxelKey;
using testing::TempDir;

// An aerial-like 2.5D cloud: a terrain with blocks of buildings and a few walls, ~0.15 m spacing, UTM numbers.
std::vector<LasPoint> AerialPoints(size_t n, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<LasPoint> pts(n);
  for (size_t i = 0; i < n; ++i) {
    LasPoint& p = pts[i];
    const double x = 391000.0 + 180.0 * u(rng), y = 5706000.0 + 120.0 * u(rng);
    double z = 95.0 + 3.0 * std::sin(x / 40.0) + 2.0 * std::cos(y / 25.0);
    if (std::fmod(x, 30.0) < 12.0 && std::fmod(y, 25.0) < 10.0) z += 12.0;  // roofs
    if (i % 10 == 0) z += 12.0 * u(rng);                                     // walls and trees
    p.xyz = {x, y, z};
    p.rgb = {static_cast<uint16_t>(256 * (i % 256)), static_cast<uint16_t>(256 * ((i / 7) % 256)),
             static_cast<uint16_t>(256 * ((i / 13) % 256))};
    p.point_source_id = static_cast<uint16_t>(1 + i % 59);
    p.gps_time = 1000.0 + 0.001 * static_cast<double>(i);
    p.intensity = static_cast<uint16_t>(i % 1000);
  }
  return pts;
}

// Buckets of at most `bucket_points` points (memory_bytes: the out-of-core path for larger clouds), nodes of at most
// `node_points`.
CopcOptions SmallBuild(size_t bucket_points, size_t node_points) {
  CopcOptions o;
  o.memory_bytes = 96 * bucket_points;
  o.max_node_points = node_points;
  return o;
}

LasWriterOptions UtmOptions() {
  LasWriterOptions o;
  o.offset = Eigen::Vector3d(391000, 5706000, 0);
  return o;
}

void WriteCopc(const std::string& path, const std::vector<LasPoint>& pts, const LasWriterOptions& las,
               const CopcOptions& copc) {
  CopcWriter w(path, las, copc);
  for (size_t at = 0; at < pts.size(); at += 7777) {
    w.WritePoints(pts.data() + at, std::min<size_t>(7777, pts.size() - at));
  }
  w.Close();
  EXPECT_EQ(w.num_points(), pts.size());
}

using PointKey = std::tuple<int64_t, int64_t, int64_t, uint16_t, uint16_t, double, uint16_t>;
std::vector<PointKey> Keys(const std::vector<LasPoint>& pts, double scale) {
  std::vector<PointKey> keys;
  for (const LasPoint& p : pts) {
    keys.emplace_back(std::llround(p.xyz.x() / scale), std::llround(p.xyz.y() / scale), std::llround(p.xyz.z() / scale),
                      p.point_source_id, p.rgb[0], p.gps_time, p.intensity);
  }
  std::sort(keys.begin(), keys.end());
  return keys;
}

// What the file says: header, info, every node and its decoded records.
struct CopcContents {
  LasHeader header;
  copc::Info info;
  copc::HierarchyWalk walk;
  std::map<VoxelKey, std::vector<LasPoint>> points;  // by node
};

CopcContents ReadCopc(const std::string& path) {
  CopcContents c;
  {
    LasReader reader(path);
    c.header = reader.header();
  }
  for (const LasVlr& v : c.header.vlrs) {
    if (v.user_id == "copc" && v.record_id == 1) {
      EXPECT_EQ(copc::DecodeInfo(v.data, &c.info), "");
    }
  }
  std::ifstream in(path, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const auto read = [&](uint64_t at, size_t n, std::vector<uint8_t>* out) {
    if (at + n > bytes.size()) return false;
    out->assign(bytes.begin() + static_cast<std::ptrdiff_t>(at), bytes.begin() + static_cast<std::ptrdiff_t>(at + n));
    return true;
  };
  c.walk = copc::WalkHierarchy(read, c.info.root_hier_offset, c.info.root_hier_size, 0, bytes.size());
  EXPECT_TRUE(c.walk.problems.empty()) << c.walk.problems.front();
  // The laszip VLR follows the info VLR and the others; LasReader keeps it apart.
  const uint32_t vlrs = lf::GetU32(reinterpret_cast<const uint8_t*>(&bytes[lf::kOffNumVlrs]));
  size_t at = lf::kHeaderSize14;
  laz::LazVlr vlr;
  for (uint32_t i = 0; i < vlrs; ++i) {
    const auto* head = reinterpret_cast<const uint8_t*>(&bytes[at]);
    const uint16_t length = lf::GetU16(head + 20);
    if (lf::GetPaddedString(head + 2, 16) == "laszip encoded") {
      vlr = laz::LazVlr::Parse(std::vector<uint8_t>(head + 54, head + 54 + length));
    }
    at += 54 + length;
  }
  EXPECT_EQ(vlr.chunk_size, laz::kVariableChunkSize);
  laz::ChunkDecoder decoder(vlr, c.header.point_record_length);
  std::vector<uint8_t> record(c.header.point_record_length);
  for (const Entry& e : c.walk.nodes) {
    if (e.point_count <= 0) continue;
    std::vector<LasPoint>& node = c.points[e.key];
    decoder.Start(reinterpret_cast<const uint8_t*>(&bytes[e.offset]), static_cast<size_t>(e.byte_size),
                  static_cast<uint64_t>(e.point_count));
    for (int32_t i = 0; i < e.point_count; ++i) {
      decoder.Next(record.data());
      node.emplace_back();
      lf::DecodePointRecord(record.data(), c.header.point_format, c.header.scale, c.header.offset, &node.back());
    }
  }
  return c;
}

// Every point once, inside its node; nodes with children one point per cell of their 128^3 grid; leaves within
// `max_points`. Returns the number of levels.
int ExpectWellFormedOctree(const CopcContents& c, const std::vector<LasPoint>& written, size_t max_points) {
  std::vector<LasPoint> all;
  std::set<VoxelKey> keys;
  for (const Entry& e : c.walk.nodes) keys.insert(e.key);
  int levels = 0;
  size_t bad_cells = 0, outside = 0;
  for (const auto& [key, pts] : c.points) {
    levels = std::max(levels, key.level + 1);
    const std::array<double, 6> b = copc::NodeBounds(c.info, key);
    bool has_children = false;
    for (int o = 0; o < 8; ++o) has_children = has_children || keys.count(key.Child(o)) > 0;
    std::set<std::tuple<int64_t, int64_t, int64_t>> cells;
    const double cell = (b[3] - b[0]) / copc::kCells;
    for (const LasPoint& p : pts) {
      for (int a = 0; a < 3; ++a) outside += (p.xyz[a] < b[a] || p.xyz[a] > b[a + 3]) ? 1 : 0;
      const auto idx = [&](int a) { return static_cast<int64_t>(std::floor((p.xyz[a] - b[a]) / cell)); };
      if (has_children && !cells.insert({idx(0), idx(1), idx(2)}).second) ++bad_cells;
      all.push_back(p);
    }
    if (!has_children) {
      EXPECT_LE(pts.size(), max_points) << key.ToString();
    }
  }
  EXPECT_EQ(outside, 0u);
  EXPECT_EQ(bad_cells, 0u) << "nodes with children hold more than one point in a cell of their grid";
  EXPECT_TRUE(keys.count(VoxelKey{}));
  for (const VoxelKey& k : keys) {
    if (k.level > 0) {
      EXPECT_TRUE(keys.count(k.Parent())) << k.ToString() << " unreachable";
    }
  }
  EXPECT_EQ(all.size(), written.size());
  EXPECT_TRUE(Keys(all, 0.001) == Keys(written, 0.001)) << "the nodes do not hold the points written";
  return levels;
}

TEST(CopcOctreeTest, CubeHoldsEveryPointStrictlyInsideItsNodes) {
  const std::vector<LasPoint> pts = AerialPoints(3000, 1);
  std::array<int32_t, 3> lo{}, hi{};
  std::vector<std::array<int32_t, 3>> stored;
  for (const LasPoint& p : pts) {
    std::array<int32_t, 3> s{};
    for (int a = 0; a < 3; ++a) ASSERT_TRUE(lf::Quantise(p.xyz[a], 0.001, UtmOptions().offset->coeff(a), &s[a]));
    stored.push_back(s);
  }
  for (int a = 0; a < 3; ++a) {
    lo[a] = std::min_element(stored.begin(), stored.end(), [a](auto& p, auto& q) { return p[a] < q[a]; })->at(a);
    hi[a] = std::max_element(stored.begin(), stored.end(), [a](auto& p, auto& q) { return p[a] < q[a]; })->at(a);
  }
  const copc::Cube cube = copc::Cube::Around(lo, hi);
  const copc::Info info = cube.ToInfo(0.001, *UtmOptions().offset);
  const double extent = 0.001 * (hi[0] - lo[0]);  // x is the longest axis (180 m)
  EXPECT_GE(2 * info.halfsize, extent);
  EXPECT_LE(2 * info.halfsize, 1.126 * extent + 0.02);  // side = c 2^k, 8 <= c < 16: at most 1/8 over
  EXPECT_NEAR(info.spacing, 2 * info.halfsize / 128, 1e-12);
  EXPECT_GE(cube.max_node_level(), 10);
  for (size_t i = 0; i < stored.size(); ++i) {
    const LasPoint& p = pts[i];
    for (int level = 0; level <= cube.max_node_level(); ++level) {
      const VoxelKey key = cube.KeyOf(stored[i].data(), level);
      ASSERT_TRUE(key.Valid()) << key.ToString();
      if (level > 0) {
        ASSERT_EQ(key.Parent(), cube.KeyOf(stored[i].data(), level - 1));
      }
      const std::array<double, 6> b = copc::NodeBounds(info, key);
      for (int a = 0; a < 3; ++a) {
        const double x = lf::Dequantise(stored[i][a], 0.001, UtmOptions().offset->coeff(a));
        // Boundaries lie between quantisation steps: at least a third of a step away (float margin included).
        ASSERT_GT(x - b[a], 0.00033) << "level " << level << " axis " << a << " point " << p.xyz.transpose();
        ASSERT_GT(b[a + 3] - x, 0.00033) << "level " << level << " axis " << a;
      }
    }
  }
  // The centre lies inside the points' bounds (COPC validators require it).
  for (int a = 0; a < 3; ++a) {
    EXPECT_GT(info.center[a], lf::Dequantise(lo[a], 0.001, UtmOptions().offset->coeff(a)));
    EXPECT_LT(info.center[a], lf::Dequantise(hi[a], 0.001, UtmOptions().offset->coeff(a)));
  }
}

TEST(CopcOctreeTest, KnownCubeAndTheNearestPointOfEachCell) {
  // Stored integers 0..1023 on every axis: the root cube is exactly [0, 1024) steps (2048 half-steps = 8 x 2^8),
  // its cells 8 steps wide; the centre of cell (0, 0, 0) lies at 3.5 steps.
  const copc::Cube cube = copc::Cube::Around({0, 0, 0}, {1023, 1023, 1023});
  const copc::Info info = cube.ToInfo(1.0, Eigen::Vector3d::Zero());
  EXPECT_EQ(info.halfsize, 512.0);
  EXPECT_EQ(info.center, Eigen::Vector3d(511.5, 511.5, 511.5));  // stored 511.5: between 511 and 512
  EXPECT_EQ(info.spacing, 8.0);
  const std::vector<int32_t> xyz = {0, 0, 0, 4, 3, 3, 3, 3, 3, 100, 100, 100, 9, 9, 9, 1023, 0, 1023};
  std::vector<uint8_t> records(xyz.size() / 3 * 12);
  for (size_t i = 0; i < xyz.size(); ++i) lf::PutI32(&records[4 * i], xyz[i]);
  const copc::RecordView view{records.data(), 12};
  std::vector<uint32_t> own, rest;
  copc::SelectOnePerCell(cube, VoxelKey{}, view, {0, 1, 2, 3, 4, 5}, &own, &rest);
  // Cell (0,0,0): (0,0,0) is 3.5 steps off on every axis, (4,3,3) and (3,3,3) 0.5: a tie, the first wins.
  EXPECT_EQ(own, (std::vector<uint32_t>{1, 3, 4, 5}));
  EXPECT_EQ(rest, (std::vector<uint32_t>{0, 2}));
  const int32_t corner[3] = {1023, 0, 1023};
  EXPECT_EQ(cube.KeyOf(corner, 1), (VoxelKey{1, 1, 0, 1}));
  EXPECT_EQ(cube.OctantOf(corner, VoxelKey{}), 1 | 4);
  const int32_t low[3] = {511, 512, 0};
  EXPECT_EQ(cube.KeyOf(low, 1), (VoxelKey{1, 0, 1, 0}));
}

// The parallel choice of one point per cell (cells chosen in groups, points sorted by parallel counting) is a
// serial pass's: the nearest point to each cell's centre, ties to the first, checked against a map over every
// cell on a dense cloud (~5 points per cell, ties among them: integer coordinates), at 1, 2 and 4 threads;
// the subtree built from it keeps every point once.
TEST(CopcOctreeTest, ParallelChoiceIsTheSerialOne) {
  std::mt19937 rng(5);
  std::uniform_int_distribution<int32_t> xy(0, 1023), z(7000, 7015);
  std::vector<uint8_t> records;
  const size_t n = 150000;
  for (size_t i = 0; i < n; ++i) {
    uint8_t r[12];
    lf::PutI32(r, xy(rng));
    lf::PutI32(r + 4, xy(rng));
    lf::PutI32(r + 8, z(rng));
    records.insert(records.end(), r, r + 12);
  }
  const copc::RecordView view{records.data(), 12};
  std::array<int32_t, 3> lo{}, hi{};
  for (int a = 0; a < 3; ++a) {
    lo[a] = a == 2 ? 7000 : 0;
    hi[a] = lo[a] + 2000;
  }
  const copc::Cube cube = copc::Cube::Around(lo, hi);
  const VoxelKey node = cube.KeyOf(std::array<int32_t, 3>{100, 100, 7005}.data(), 1);
  std::vector<uint32_t> points;
  std::map<uint32_t, std::pair<double, uint32_t>> nearest;  // cell -> distance, first point at it
  for (uint32_t i = 0; i < n; ++i) {
    int32_t stored[3];
    view.Stored(i, stored);
    if (!(cube.KeyOf(stored, 1) == node)) continue;
    points.push_back(i);
    double d2 = 0.0;
    const uint32_t cell = cube.CellOf(stored, node, &d2);
    const auto it = nearest.find(cell);
    if (it == nearest.end() || d2 < it->second.first) nearest[cell] = {d2, i};
  }
  ASSERT_GT(points.size(), n / 2);
  std::set<uint32_t> expected_own;
  for (const auto& [cell, best] : nearest) expected_own.insert(best.second);
  ASSERT_LT(expected_own.size(), points.size() / 2) << "too few points per cell to test the ties";
  for (int threads : {1, 2, 4}) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    std::vector<uint32_t> own, rest;
    copc::SelectOnePerCell(cube, node, view, points, &own, &rest);
    EXPECT_TRUE(std::is_sorted(own.begin(), own.end()) && std::is_sorted(rest.begin(), rest.end()));
    EXPECT_TRUE(std::set<uint32_t>(own.begin(), own.end()) == expected_own) << threads << " threads";
    EXPECT_EQ(own.size() + rest.size(), points.size());
    const copc::BuiltSubtree tree = copc::BuildSubtree(cube, node, view, points, 5000);
    EXPECT_EQ(tree.own, own) << threads << " threads";
    size_t total = tree.own.size();
    for (const copc::BuiltNode& d : tree.descendants) total += d.points.size();
    EXPECT_EQ(total, points.size());
  }
}

// Out of core: 60,000 points in buckets of at most 5,000 (memory_bytes), nodes of at most 2,000, a hierarchy
// page for every subtree of at least 3 nodes.
TEST(CopcWriterTest, WritesAValidCopcWithEveryPointOnce) {
  TempDir dir;
  const std::vector<LasPoint> pts = AerialPoints(60000, 2);
  CopcOptions copc = SmallBuild(5000, 2000);
  copc.page_levels = 1;
  copc.min_page_entries = 3;
  const std::string path = (dir / "cloud.copc.laz").string();
  testing::LogCapture log;
  WriteCopc(path, pts, UtmOptions(), copc);
  EXPECT_NE(log.text().find("60000 points sorted into "), std::string::npos) << "not built out of core: " << log.text();
  EXPECT_EQ(std::distance(fs::directory_iterator(dir.path()), fs::directory_iterator()), 1) << "work files left";

  const CopcContents c = ReadCopc(path);
  EXPECT_EQ(c.header.version_minor, 4);
  EXPECT_EQ(c.header.point_format, 7);
  EXPECT_EQ(c.header.point_count, pts.size());
  EXPECT_EQ(c.info.gpstime_minimum, 1000.0);
  EXPECT_EQ(c.info.gpstime_maximum, 1000.0 + 0.001 * 59999);
  const int levels = ExpectWellFormedOctree(c, pts, copc.max_node_points);
  EXPECT_GE(levels, 3);
  EXPECT_GT(c.walk.pages, 1u);
  // Our reader reads the file as LAZ with variable chunks too (what eval, report and merge use).
  EXPECT_TRUE(Keys(ReadAllLasPoints(path), 0.001) == Keys(pts, 0.001));
  const std::vector<std::string> findings = ValidateLasFile(path);
  EXPECT_TRUE(findings.empty()) << findings.front();
  EXPECT_NE(DescribeCopc(path).find("COPC 1.0, " + std::to_string(c.walk.nodes.size()) + " nodes"), std::string::npos)
      << DescribeCopc(path);
  std::printf("[ copc     ] %zu points: %zu nodes in %d levels, %zu hierarchy pages, root %zu points\n", pts.size(),
              c.walk.nodes.size(), levels, c.walk.pages, c.points.at(VoxelKey{}).size());
}

// Out of core (buckets of 8,000 points) and in one bucket: the same bytes for 1, 2 and 4 threads.
TEST(CopcWriterTest, SameBytesForOneTwoAndFourThreads) {
  TempDir dir;
  const std::vector<LasPoint> pts = AerialPoints(30000, 3);
  for (const size_t bucket : {size_t{8000}, size_t{100000}}) {
    const CopcOptions copc = SmallBuild(bucket, 1000);
    for (int threads : {1, 2, 4}) {
      tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
      WriteCopc((dir / ("t" + std::to_string(threads) + ".copc.laz")).string(), pts, UtmOptions(), copc);
    }
    const std::string one = testing::ReadFileBytes(dir / "t1.copc.laz");
    EXPECT_TRUE(one == testing::ReadFileBytes(dir / "t2.copc.laz")) << "buckets of " << bucket;
    EXPECT_TRUE(one == testing::ReadFileBytes(dir / "t4.copc.laz")) << "buckets of " << bucket;
  }
}

TEST(CopcWriterTest, EmptyAndOnePointFilesAreValid) {
  TempDir dir;
  for (size_t n : {0, 1}) {
    const std::string path = (dir / ("n" + std::to_string(n) + ".copc.laz")).string();
    const std::vector<LasPoint> pts = AerialPoints(n, 4);
    WriteCopc(path, pts, UtmOptions(), {});
    const std::vector<std::string> findings = ValidateLasFile(path);
    EXPECT_TRUE(findings.empty()) << n << ": " << findings.front();
    EXPECT_EQ(ReadAllLasPoints(path).size(), n);
  }
}

TEST(CopcWriterTest, RefusesOptionsCopcCannotHold) {
  TempDir dir;
  const std::string path = (dir / "x.copc.laz").string();
  LasWriterOptions las12 = UtmOptions();
  las12.version_minor = 2;
  EXPECT_THROW(CopcWriter(path, las12), Error);
  LasWriterOptions format3 = UtmOptions();
  format3.point_format = 3;
  EXPECT_THROW(CopcWriter(path, format3), Error);
  LasWriterOptions skewed = UtmOptions();
  skewed.scale_xyz = Eigen::Vector3d(0.001, 0.001, 0.01);
  EXPECT_THROW(CopcWriter(path, skewed), Error);
  EXPECT_EQ(std::distance(fs::directory_iterator(dir.path()), fs::directory_iterator()), 0);
}

TEST(CopcWriterTest, NoFileWithoutClose) {
  TempDir dir;
  {
    CopcWriter w((dir / "x.copc.laz").string(), UtmOptions());
    const std::vector<LasPoint> pts = AerialPoints(100, 5);
    w.WritePoints(pts.data(), pts.size());
  }
  EXPECT_EQ(std::distance(fs::directory_iterator(dir.path()), fs::directory_iterator()), 0);
}

void Patch(const fs::path& path, uint64_t at, const std::vector<uint8_t>& bytes) {
  std::fstream f(path, std::ios::in | std::ios::out | std::ios::binary);
  f.seekp(static_cast<std::streamoff>(at));
  f.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
}

bool HasFinding(const std::vector<std::string>& findings, const std::string& part) {
  return std::any_of(findings.begin(), findings.end(),
                     [&](const std::string& f) { return f.find(part) != std::string::npos; });
}

TEST(CopcValidateTest, FindsBrokenFiles) {
  TempDir dir;
  const std::vector<LasPoint> pts = AerialPoints(20000, 6);
  const fs::path good = dir / "good.copc.laz";
  WriteCopc(good.string(), pts, UtmOptions(), SmallBuild(100000, 1000));
  ASSERT_TRUE(ValidateCopc(good.string()).empty());
  const CopcContents c = ReadCopc(good.string());
  const uint64_t info_at = 375 + 54;

  const auto broken = [&](const std::string& name) {
    const fs::path p = dir / name;
    fs::copy_file(good, p, fs::copy_options::overwrite_existing);
    return p;
  };
  // The root page's first entry (the root node): one point more than its chunk holds.
  fs::path p = broken("count.copc.laz");
  std::vector<uint8_t> count(4);
  const Entry root = c.walk.nodes.front();
  ASSERT_EQ(root.key, VoxelKey{});
  lf::PutI32(count.data(), root.point_count + 1);
  Patch(p, c.info.root_hier_offset + 28, count);
  std::vector<std::string> f = ValidateCopc(p.string());
  EXPECT_TRUE(HasFinding(f, "COPC: counts: the nodes hold")) << f.size();
  EXPECT_TRUE(HasFinding(f, "the chunk table says"));
  // The first chunk's node (written first, in one hierarchy page with the others) addresses one byte later: no
  // chunk starts there, and one chunk is addressed by no node.
  ASSERT_EQ(c.walk.pages, 1u);
  size_t first = 0;
  for (size_t i = 0; i < c.walk.nodes.size(); ++i) {
    if (c.walk.nodes[i].point_count > 0 && c.walk.nodes[i].offset < c.walk.nodes[first].offset) first = i;
  }
  p = broken("offset.copc.laz");
  std::vector<uint8_t> offset(8);
  lf::PutU64(offset.data(), c.walk.nodes[first].offset + 1);
  Patch(p, c.info.root_hier_offset + copc::kEntrySize * first + 16, offset);
  f = ValidateCopc(p.string());
  EXPECT_TRUE(HasFinding(f, "no chunk of the chunk table starts at"));
  EXPECT_TRUE(HasFinding(f, "COPC: unreachable point data"));
  // A root page size that is not a whole number of entries; a reserved word of the info VLR set.
  p = broken("page.copc.laz");
  std::vector<uint8_t> size(8);
  lf::PutU64(size.data(), c.info.root_hier_size + 1);
  Patch(p, info_at + 48, size);
  EXPECT_TRUE(HasFinding(ValidateCopc(p.string()), "is not a positive multiple of 32"));
  p = broken("reserved.copc.laz");
  Patch(p, info_at + 100, {1});
  EXPECT_TRUE(HasFinding(ValidateCopc(p.string()), "reserved word"));
  // A plain LAZ file named as COPC.
  p = dir / "plain.copc.laz";
  {
    LasWriterOptions o = UtmOptions();
    o.compressed = true;
    LasWriter w(p.string(), o);
    w.WritePoints(pts.data(), 100);
    w.Close();
  }
  EXPECT_TRUE(HasFinding(ValidateCopc(p.string()), "its first VLR is not the COPC info VLR"));
  EXPECT_TRUE(ValidateCopc((dir / "good.copc.laz").string()).empty());
}

// The COPC files of PDAL's and laspy's test data (../shared/research-data/las_compat): the COPC rules find
// nothing, our reader decodes every point (through the chunk table's variable chunks), the hierarchy is walked.
TEST(CopcValidateTest, ThirdPartyCopcFilesPass) {
  const auto shared = testing::SharedDir();
  if (!shared) GTEST_SKIP() << "../shared not found (set SACFUSE_SHARED)";
  size_t files = 0;
  for (const char* name : {"pdal/copc__1.2-with-color.copc.laz", "laspy/simple.copc.laz"}) {
    const fs::path path = *shared / "research-data" / "las_compat" / name;
    if (!fs::exists(path)) continue;
    ++files;
    const std::vector<std::string> findings = ValidateCopc(path.string());
    EXPECT_TRUE(findings.empty()) << name << ": " << findings.front();
    EXPECT_NE(DescribeCopc(path.string()).find("COPC 1.0, 65 nodes"), std::string::npos) << DescribeCopc(path.string());
    LasHeader h;
    EXPECT_EQ(ReadAllLasPoints(path.string(), &h).size(), h.point_count);
  }
  if (files == 0) GTEST_SKIP() << "no COPC files in " << (*shared / "research-data" / "las_compat").string();
}

}  // namespace
}  // namespace sacfuse
