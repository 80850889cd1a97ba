#include "io/las_writer.h"

#include <cmath>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <random>

#include <gtest/gtest.h>

#include "core/error.h"
#include "io/las_reader.h"
#include "tests/support/test_support.h"

namespace sacfuse {
namespace {

namespace fs = std::filesystem;
using testing::TempDir;

std::vector<uint8_t> ReadBytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::vector<uint8_t>(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}
uint16_t U16(const std::vector<uint8_t>& b, size_t at) { return static_cast<uint16_t>(b[at] | (b[at + 1] << 8)); }
uint32_t U32(const std::vector<uint8_t>& b, size_t at) {
  uint32_t v = 0;
  for (int i = 3; i >= 0; --i) v = (v << 8) | b[at + i];
  return v;
}
uint64_t U64(const std::vector<uint8_t>& b, size_t at) {
  uint64_t v = 0;
  for (int i = 7; i >= 0; --i) v = (v << 8) | b[at + i];
  return v;
}
double F64(const std::vector<uint8_t>& b, size_t at) {
  const uint64_t bits = U64(b, at);
  double v;
  std::memcpy(&v, &bits, sizeof(v));
  return v;
}

// UTM-sized fused points around (390123.4567, 5705123.4567, 52.3).
std::vector<FusedPoint> MakeFusedPoints(size_t n, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> d(-80.0, 80.0);
  std::uniform_int_distribution<int> byte(0, 255);
  std::uniform_int_distribution<uint32_t> view(0, 1999);
  std::vector<FusedPoint> points(n);
  for (size_t i = 0; i < n; ++i) {
    points[i].point_in_world = {390123.4567 + d(rng), 5705123.4567 + d(rng), 52.3 + d(rng) / 8};
    points[i].rgb = {static_cast<uint8_t>(byte(rng)), static_cast<uint8_t>(byte(rng)), static_cast<uint8_t>(byte(rng))};
    points[i].view_index = view(rng);
  }
  return points;
}

size_t CountEntries(const fs::path& dir) {
  return static_cast<size_t>(std::distance(fs::directory_iterator(dir), fs::directory_iterator()));
}

// Checks everything a fused-point round trip must preserve.
void ExpectFusedRoundTrip(const std::vector<FusedPoint>& in, const std::string& path, double scale) {
  LasHeader header;
  const std::vector<LasPoint> out = ReadAllLasPoints(path, &header);
  ASSERT_EQ(out.size(), in.size());
  EXPECT_EQ(header.point_count, in.size());
  EXPECT_EQ(header.points_by_return[0], in.size());
  for (int r = 1; r < 15; ++r) EXPECT_EQ(header.points_by_return[r], 0u);
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(1e300), hi = Eigen::Vector3d::Constant(-1e300);
  for (size_t i = 0; i < in.size(); ++i) {
    for (int a = 0; a < 3; ++a) {
      ASSERT_LE(std::abs(out[i].xyz[a] - in[i].point_in_world[a]), scale / 2 + 1e-9) << "point " << i << " axis " << a;
      lo[a] = std::min(lo[a], out[i].xyz[a]);
      hi[a] = std::max(hi[a], out[i].xyz[a]);
      ASSERT_EQ(out[i].rgb[a], in[i].rgb[a] * 256) << i;
    }
    ASSERT_EQ(out[i].point_source_id, in[i].view_index + 1) << i;
    ASSERT_EQ(out[i].return_number, 1);
    ASSERT_EQ(out[i].number_of_returns, 1);
    ASSERT_EQ(out[i].classification, 0);
    ASSERT_EQ(out[i].gps_time, 0.0);
    ASSERT_FALSE(out[i].scan_direction);
    ASSERT_FALSE(out[i].edge_of_flight_line);
    ASSERT_EQ(out[i].scanner_channel, 0);
  }
  // Bounds are the dequantised stored integer extremes, i.e. exactly the extremes of the coordinates read.
  for (int a = 0; a < 3; ++a) {
    EXPECT_EQ(header.min[a], lo[a]) << a;
    EXPECT_EQ(header.max[a], hi[a]) << a;
    EXPECT_EQ(header.scale[a], scale);
    // Automatic offset: first point snapped down to 1000 m, hence a multiple of the scale.
    EXPECT_EQ(header.offset[a], std::floor(in[0].point_in_world[a] / 1000.0) * 1000.0) << a;
    const double steps = header.offset[a] / scale;
    EXPECT_NEAR(steps, std::round(steps), 1e-6) << a;
  }
  EXPECT_EQ(header.file_source_id, 0);
  std::time_t now = std::time(nullptr);
  std::tm utc{};
  gmtime_r(&now, &utc);
  EXPECT_EQ(header.creation_year, utc.tm_year + 1900);
  EXPECT_GE(header.creation_day, 1);
  EXPECT_LE(header.creation_day, 366);
}

TEST(LasWriterTest, RoundTripLas14Pdrf7WithRawHeaderBytes) {
  TempDir dir;
  const std::string path = (dir / "cloud.las").string();
  const std::vector<FusedPoint> points = MakeFusedPoints(5000, 1);
  const std::string wkt = "PROJCS[\"WGS 84 / UTM zone 32N\"]";
  LasVlr wkt_vlr;
  wkt_vlr.user_id = "LASF_Projection";
  wkt_vlr.record_id = 2112;
  wkt_vlr.description = "OGC WKT";
  wkt_vlr.data.assign(wkt.begin(), wkt.end());
  wkt_vlr.data.push_back(0);
  LasWriterOptions options;
  options.vlrs = {wkt_vlr};
  options.global_encoding_extra_bits = 0x10;
  {
    LasWriter writer(path, options);
    for (size_t i = 0; i < points.size(); i += 777) writer.Write(&points[i], std::min<size_t>(777, points.size() - i));
    EXPECT_EQ(writer.num_points(), points.size());
    writer.Close();
  }
  ExpectFusedRoundTrip(points, path, 0.001);

  LasHeader header;
  ReadAllLasPoints(path, &header);
  EXPECT_EQ(header.version_major, 1);
  EXPECT_EQ(header.version_minor, 4);
  EXPECT_EQ(header.point_format, 7);
  EXPECT_EQ(header.Wkt(), wkt);
  EXPECT_EQ(header.system_identifier, "sacfuse");

  const std::vector<uint8_t> b = ReadBytes(path);
  ASSERT_GE(b.size(), 375u);
  EXPECT_EQ(std::string(b.begin(), b.begin() + 4), "LASF");
  EXPECT_EQ(U16(b, 4), 0);      // file source ID
  EXPECT_EQ(U16(b, 6), 0x10);   // global encoding: WKT
  for (int i = 8; i < 24; ++i) EXPECT_EQ(b[i], 0) << "GUID byte " << i;
  EXPECT_EQ(b[24], 1);
  EXPECT_EQ(b[25], 4);
  for (int i = 26 + 7; i < 58; ++i) EXPECT_EQ(b[i], 0) << "system ID padding " << i;
  EXPECT_EQ(U16(b, 94), 375);   // header size
  const uint32_t point_offset = U32(b, 96);
  EXPECT_EQ(point_offset, 375u + 54u + wkt_vlr.data.size());
  EXPECT_EQ(U32(b, 100), 1u);   // VLR count
  EXPECT_EQ(b[104], 7);         // PDRF
  EXPECT_EQ(U16(b, 105), 36);   // record length
  EXPECT_EQ(U32(b, 107), 0u);   // legacy count is 0 for PDRF >= 6
  for (int r = 0; r < 5; ++r) EXPECT_EQ(U32(b, 111 + 4 * r), 0u);
  EXPECT_EQ(U64(b, 227), 0u);   // waveform start
  EXPECT_EQ(U64(b, 235), 0u);   // no EVLRs
  EXPECT_EQ(U32(b, 243), 0u);
  EXPECT_EQ(U64(b, 247), points.size());
  EXPECT_EQ(U64(b, 255), points.size());
  for (int r = 1; r < 15; ++r) EXPECT_EQ(U64(b, 255 + 8 * r), 0u);
  for (int a = 0; a < 3; ++a) {
    EXPECT_EQ(F64(b, 131 + 8 * a), 0.001);
    EXPECT_EQ(F64(b, 179 + 16 * a), header.max[a]);  // max comes first
    EXPECT_EQ(F64(b, 187 + 16 * a), header.min[a]);
    EXPECT_GT(F64(b, 179 + 16 * a), F64(b, 187 + 16 * a));
  }
  EXPECT_EQ(std::string(b.begin() + 377, b.begin() + 377 + 15), "LASF_Projection");
  EXPECT_EQ(b.size(), point_offset + 36 * points.size());
}

TEST(LasWriterTest, RoundTripLas12Pdrf3WithRawHeaderBytes) {
  TempDir dir;
  const std::string path = (dir / "cloud12.las").string();
  const std::vector<FusedPoint> points = MakeFusedPoints(3000, 2);
  LasWriterOptions options;
  options.version_minor = 2;
  options.scale_m = 0.0025;
  LasWriter writer(path, options);
  writer.Write(points.data(), points.size());
  writer.Close();
  ExpectFusedRoundTrip(points, path, 0.0025);

  const std::vector<uint8_t> b = ReadBytes(path);
  EXPECT_EQ(b[25], 2);
  EXPECT_EQ(U16(b, 6), 0);      // global encoding
  EXPECT_EQ(U16(b, 94), 227);
  EXPECT_EQ(U32(b, 96), 227u);
  EXPECT_EQ(b[104], 3);
  EXPECT_EQ(U16(b, 105), 34);
  EXPECT_EQ(U32(b, 107), points.size());  // the 32-bit count is the count before 1.4
  EXPECT_EQ(U32(b, 111), points.size());
  EXPECT_EQ(F64(b, 131), 0.0025);
  EXPECT_EQ(b.size(), 227 + 34 * points.size());
}

TEST(LasWriterTest, StreamsManyPointsInManyChunks) {
  TempDir dir;
  const std::string path = (dir / "big.las").string();
  const size_t total = 250000;  // > 3 internal 64k buffers
  std::vector<FusedPoint> all = MakeFusedPoints(total, 3);
  LasWriter writer(path, {});
  std::mt19937 rng(4);
  std::uniform_int_distribution<size_t> chunk(1, 5000);
  for (size_t i = 0; i < total;) {
    const size_t n = std::min(chunk(rng), total - i);
    writer.Write(&all[i], n);
    i += n;
  }
  writer.Close();
  EXPECT_EQ(fs::file_size(path), 375u + 36u * total);
  ExpectFusedRoundTrip(all, path, 0.001);
}

TEST(LasWriterTest, DestroyedWithoutCloseLeavesNothing) {
  TempDir dir;
  const std::string path = (dir / "abandoned.las").string();
  {
    LasWriter writer(path, {});
    const auto points = MakeFusedPoints(70000, 5);
    writer.Write(points.data(), points.size());
    EXPECT_EQ(CountEntries(dir.path()), 1u);  // the temporary file
    EXPECT_FALSE(fs::exists(path));
  }
  EXPECT_FALSE(fs::exists(path));
  EXPECT_EQ(CountEntries(dir.path()), 0u);
}

TEST(LasWriterTest, ExistingFileIsReplacedOnlyByClose) {
  TempDir dir;
  const std::string path = (dir / "tile.las").string();
  const auto first = MakeFusedPoints(10, 6);
  {
    LasWriter writer(path, {});
    writer.Write(first.data(), first.size());
    writer.Close();
  }
  const std::vector<uint8_t> original = ReadBytes(path);
  const auto second = MakeFusedPoints(20, 7);
  {
    LasWriter abandoned(path, {});
    abandoned.Write(second.data(), second.size());
  }
  EXPECT_EQ(ReadBytes(path), original);
  LasWriter writer(path, {});
  writer.Write(second.data(), second.size());
  EXPECT_EQ(ReadBytes(path), original);
  writer.Close();
  writer.Close();  // a second Close is a no-op
  ExpectFusedRoundTrip(second, path, 0.001);
  EXPECT_EQ(CountEntries(dir.path()), 1u);
}

TEST(LasWriterTest, FailedCommitLeavesNothingAtThePath) {
  TempDir dir;
  const fs::path path = dir / "occupied";
  fs::create_directory(path);  // rename onto a directory fails
  LasWriter writer(path.string(), {});
  const auto points = MakeFusedPoints(10, 8);
  writer.Write(points.data(), points.size());
  EXPECT_THROW(writer.Close(), Error);
  EXPECT_TRUE(fs::is_directory(path));
  EXPECT_EQ(CountEntries(dir.path()), 1u);  // no temporary file left behind
}

TEST(LasWriterTest, MissingFolderThrows) {
  TempDir dir;
  EXPECT_THROW(LasWriter((dir / "no" / "such" / "x.las").string(), {}), Error);
}

TEST(LasWriterTest, PointSourceIdOverflowThrows) {
  TempDir dir;
  const std::string path = (dir / "views.las").string();
  LasWriter writer(path, {});
  FusedPoint p;
  p.point_in_world = {390000.0, 5700000.0, 10.0};
  p.view_index = 65534;  // point source ID 65535: the largest
  writer.Write(&p, 1);
  p.view_index = 65535;
  try {
    writer.Write(&p, 1);
    FAIL() << "no exception";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
  writer.Close();
  const auto out = ReadAllLasPoints(path);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0].point_source_id, 65535);
}

TEST(LasWriterTest, QuantisationOverflowThrowsAndKeepsTheChunkOut) {
  TempDir dir;
  const std::string path = (dir / "overflow.las").string();
  LasWriterOptions options;
  options.offset = Eigen::Vector3d::Zero();  // PDAL's default: a UTM northing does not fit at 1 mm
  {
    LasWriter writer(path, options);
    FusedPoint p;
    p.point_in_world = {390123.4567, 5705123.4567, 50.0};
    try {
      writer.Write(&p, 1);
      FAIL() << "no exception";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("int32"), std::string::npos) << e.what();
    }
    EXPECT_EQ(writer.num_points(), 0u);
  }
  // Automatic offset: a point 3000 km from the first one overflows; the rejected chunk is not written.
  LasWriter writer(path, {});
  std::vector<FusedPoint> chunk(3);
  chunk[0].point_in_world = {390123.4567, 5705123.4567, 50.0};
  chunk[1].point_in_world = {390124.0, 5705124.0, 51.0};
  writer.Write(chunk.data(), 2);
  chunk[2].point_in_world = {390123.0, 5705123.0 + 3.0e6, 50.0};
  EXPECT_THROW(writer.Write(chunk.data(), 3), Error);
  EXPECT_EQ(writer.num_points(), 2u);
  writer.Close();
  EXPECT_EQ(ReadAllLasPoints(path).size(), 2u);
}

TEST(LasWriterTest, RoundsHalfAwayFromZero) {
  TempDir dir;
  const std::string path = (dir / "round.las").string();
  LasWriterOptions options;
  options.scale_m = 0.5;
  options.offset = Eigen::Vector3d(1000.0, 2000.0, 0.0);
  LasWriter writer(path, options);
  std::vector<FusedPoint> p(2);
  p[0].point_in_world = {1000.25, 1999.75, 0.25};  // exactly half a step: llround goes away from zero
  p[1].point_in_world = {1000.75, 2000.0, -0.25};
  writer.Write(p.data(), p.size());
  writer.Close();
  const auto out = ReadAllLasPoints(path);
  EXPECT_EQ(out[0].xyz, Eigen::Vector3d(1000.5, 1999.5, 0.5));
  EXPECT_EQ(out[1].xyz, Eigen::Vector3d(1001.0, 2000.0, -0.5));
}

TEST(LasWriterTest, RejectsBadOptions) {
  TempDir dir;
  const std::string path = (dir / "bad.las").string();
  auto make = [&](const LasWriterOptions& o) { LasWriter w(path, o); };
  LasWriterOptions o;
  o.version_minor = 3;
  EXPECT_THROW(make(o), Error);
  o = {};
  o.scale_m = 0.003;
  EXPECT_THROW(make(o), Error);
  o.scale_m = 0.0;
  EXPECT_THROW(make(o), Error);
  o = {};
  o.version_minor = 2;
  o.global_encoding_extra_bits = 0x10;  // WKT bit is 1.4-only
  EXPECT_THROW(make(o), Error);
  o = {};
  o.global_encoding_extra_bits = 0x2;  // waveform bit without waveform data
  EXPECT_THROW(make(o), Error);
  o = {};
  o.version_minor = 2;
  o.point_format = 7;
  EXPECT_THROW(make(o), Error);
  o = {};
  o.point_format = 4;
  EXPECT_THROW(make(o), Error);
  o = {};
  o.system_identifier = std::string(33, 'x');
  EXPECT_THROW(make(o), Error);
  o = {};
  o.vlrs.resize(1);
  o.vlrs[0].data.resize(70000);
  EXPECT_THROW(make(o), Error);
  for (double good : {0.001, 0.0025, 0.005, 0.01, 0.25, 1.0}) {
    o = {};
    o.scale_m = good;
    EXPECT_NO_THROW(make(o)) << good;
  }
  EXPECT_EQ(CountEntries(dir.path()), 0u);
}

TEST(LasWriterTest, WritePointsKeepsFieldsAndRejectsWhatTheFormatCannotHold) {
  TempDir dir;
  LasPoint p;
  p.xyz = {500000.123, 4000000.456, 12.5};
  p.classification = 40;  // fine in PDRF 7, too large for PDRF 3
  p.return_number = 2;
  p.number_of_returns = 3;
  p.flags = 0x5;
  p.intensity = 4321;
  p.scan_angle_deg = -12.006f;
  p.user_data = 9;
  p.point_source_id = 77;
  p.gps_time = 123456.789;
  p.rgb = {1, 2, 65535};
  p.scanner_channel = 2;
  p.edge_of_flight_line = true;
  const std::string path14 = (dir / "fields14.las").string();
  {
    LasWriter writer(path14, {});
    writer.WritePoints(&p, 1);
    writer.Close();
  }
  LasHeader header;
  const auto out = ReadAllLasPoints(path14, &header);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0].classification, 40);
  EXPECT_EQ(out[0].return_number, 2);
  EXPECT_EQ(out[0].number_of_returns, 3);
  EXPECT_EQ(out[0].flags, 0x5);
  EXPECT_EQ(out[0].intensity, 4321);
  EXPECT_NEAR(out[0].scan_angle_deg, -12.006f, 1e-4);
  EXPECT_EQ(out[0].user_data, 9);
  EXPECT_EQ(out[0].point_source_id, 77);
  EXPECT_EQ(out[0].gps_time, 123456.789);
  EXPECT_EQ(out[0].rgb, p.rgb);
  EXPECT_EQ(out[0].scanner_channel, 2);
  EXPECT_TRUE(out[0].edge_of_flight_line);
  EXPECT_EQ(header.points_by_return[1], 1u);  // return number 2
  EXPECT_EQ(header.points_by_return[0], 0u);

  LasWriterOptions o12;
  o12.version_minor = 2;
  LasWriter writer12((dir / "fields12.las").string(), o12);
  EXPECT_THROW(writer12.WritePoints(&p, 1), Error);  // classification 40 > 31
  p.classification = 6;
  EXPECT_THROW(writer12.WritePoints(&p, 1), Error);  // scanner channel needs PDRF 6+
  p.scanner_channel = 0;
  p.flags = 0x8;
  EXPECT_THROW(writer12.WritePoints(&p, 1), Error);  // overlap bit needs PDRF 6+
  p.flags = 0x1;
  writer12.WritePoints(&p, 1);
  EXPECT_EQ(writer12.num_points(), 1u);

  LasWriterOptions o0;
  o0.version_minor = 2;
  o0.point_format = 0;
  LasWriter writer0((dir / "fields0.las").string(), o0);
  EXPECT_THROW(writer0.WritePoints(&p, 1), Error);  // GPS time and RGB need other formats
}

TEST(LasWriterTest, ZeroPointFileIsValid) {
  TempDir dir;
  const std::string path = (dir / "empty.las").string();
  LasWriter writer(path, {});
  writer.Close();
  LasHeader header;
  EXPECT_TRUE(ReadAllLasPoints(path, &header).empty());
  EXPECT_EQ(header.point_count, 0u);
  EXPECT_EQ(header.min, Eigen::Vector3d::Zero());
  EXPECT_EQ(header.max, Eigen::Vector3d::Zero());
  EXPECT_EQ(fs::file_size(path), 375u);
}

TEST(LasWriterTest, ExtendedVlrsFollowThePoints) {
  TempDir dir;
  const std::string path = (dir / "evlr.las").string();
  LasWriterOptions options;
  LasVlr evlr;
  evlr.user_id = "sacfuse";
  evlr.record_id = 7;
  evlr.extended = true;
  evlr.data.assign(100000, 0xAB);  // too large for a VLR
  options.vlrs = {evlr};
  const auto points = MakeFusedPoints(100, 9);
  LasWriter writer(path, options);
  writer.Write(points.data(), points.size());
  writer.Close();
  LasHeader header;
  EXPECT_EQ(ReadAllLasPoints(path, &header).size(), 100u);
  ASSERT_EQ(header.vlrs.size(), 1u);
  EXPECT_TRUE(header.vlrs[0].extended);
  EXPECT_EQ(header.vlrs[0].data, evlr.data);
  const auto b = ReadBytes(path);
  EXPECT_EQ(U64(b, 235), 375u + 36u * 100u);
  EXPECT_EQ(U32(b, 243), 1u);
}

}  // namespace
}  // namespace sacfuse
