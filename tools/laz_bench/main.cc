// sacfuse_laz_bench: compression ratio and write/read speed of LAZ against LAS, through LasWriter and LasReader.
// Not a test: prints a Markdown table (docs/benchmarks.md).
//
//   sacfuse_laz_bench [--las FILE] [--points N] [--dir DIR]
//
// --las FILE: the points of an existing LAS/LAZ file (e.g. a fused.las of `sacfuse run`), written back with its
// point format; otherwise N (default 3,000,000) synthetic fused points (a 2.5D city surface sampled like a
// depth-map fusion: 2 cm noise, smooth colours, one view per 40 m block) written as LAS 1.4 format 7 / LAS 1.2
// format 3. Each file is written and read back (all points) three times; the best time is reported.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "io/las_reader.h"
#include "io/las_writer.h"

namespace {

using sacfuse::LasPoint;
namespace fs = std::filesystem;

std::vector<sacfuse::FusedPoint> SyntheticFused(size_t n) {
  std::mt19937 rng(42);
  std::normal_distribution<double> noise(0.0, 0.02);
  std::vector<sacfuse::FusedPoint> pts(n);
  const size_t side = static_cast<size_t>(std::sqrt(static_cast<double>(n))) + 1;
  const double step = 0.1;  // 10 cm ground sampling
  for (size_t i = 0; i < n; ++i) {
    // Row-major over 40 m tiles (fused tiles come out block by block).
    const double x = static_cast<double>(i % side) * step;
    const double y = static_cast<double>(i / side) * step;
    const double building = (std::fmod(x, 40.0) > 12 && std::fmod(y, 40.0) > 10) ? 8.0 + std::fmod(x * 0.3, 6.0) : 0.0;
    sacfuse::FusedPoint& p = pts[i];
    p.point_in_world = {390000.0 + x, 5705000.0 + y, 70.0 + 0.01 * x + building + noise(rng)};
    const double shade = 0.5 + 0.5 * std::sin(x * 0.05) * std::cos(y * 0.07);
    for (int c = 0; c < 3; ++c) {
      p.rgb[c] = static_cast<uint8_t>(std::clamp(60.0 + 150.0 * shade + 20.0 * c + 8.0 * noise(rng) * 50, 0.0, 255.0));
    }
    p.view_index = static_cast<uint32_t>(std::floor(x / 40.0) + 100 * std::floor(y / 40.0));
  }
  return pts;
}

double Seconds(std::chrono::steady_clock::time_point since) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count();
}

}  // namespace

int main(int argc, char** argv) {
  std::string las_in;
  size_t n = 3000000;
  fs::path dir = fs::temp_directory_path() / "sacfuse_laz_bench";
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string a = argv[i];
    if (a == "--las") las_in = argv[i + 1];
    if (a == "--points") n = std::strtoull(argv[i + 1], nullptr, 10);
    if (a == "--dir") dir = argv[i + 1];
  }
  fs::create_directories(dir);
  std::vector<sacfuse::FusedPoint> fused;
  std::vector<LasPoint> points;
  sacfuse::LasHeader in_header;
  if (!las_in.empty()) {
    points = sacfuse::ReadAllLasPoints(las_in, &in_header);
    n = points.size();
  } else {
    fused = SyntheticFused(n);
  }
  std::printf("| cloud | format | file | MB | ratio | write s | write Mpt/s | read s | read Mpt/s |\n");
  std::printf("|---|---|---|---:|---:|---:|---:|---:|---:|\n");
  const std::vector<int> minors = las_in.empty() ? std::vector<int>{4, 2} : std::vector<int>{in_header.version_minor >= 4 ? 4 : 2};
  for (int minor : minors) {
    double las_bytes = 0;
    for (bool compressed : {false, true}) {
      const fs::path path = dir / (std::string("bench_1") + std::to_string(minor) + (compressed ? ".laz" : ".las"));
      double best_write = 1e30, best_read = 1e30;
      for (int run = 0; run < 3; ++run) {
        sacfuse::LasWriterOptions o;
        o.version_minor = minor;
        o.compressed = compressed;
        if (!las_in.empty()) {
          o.point_format = in_header.point_format;
          o.scale_xyz = in_header.scale;
          o.offset = in_header.offset;
        }
        auto t0 = std::chrono::steady_clock::now();
        {
          sacfuse::LasWriter w(path.string(), o);
          if (las_in.empty()) {
            w.Write(fused.data(), fused.size());
          } else {
            w.WritePoints(points.data(), points.size());
          }
          w.Close();
        }
        best_write = std::min(best_write, Seconds(t0));
        t0 = std::chrono::steady_clock::now();
        sacfuse::LasReader reader(path.string());
        std::vector<LasPoint> chunk;
        size_t total = 0;
        double checksum = 0;
        while (size_t k = reader.Read(&chunk, 65536)) {
          total += k;
          checksum += chunk[0].xyz.z();
        }
        best_read = std::min(best_read, Seconds(t0));
        if (total != n || !(checksum == checksum)) return 1;
      }
      const double bytes = static_cast<double>(fs::file_size(path));
      if (!compressed) las_bytes = bytes;
      const int pdrf = las_in.empty() ? (minor == 4 ? 7 : 3) : in_header.point_format;
      std::printf("| %s (%zu pts) | LAS 1.%d PDRF %d | %s | %.1f | %.2f | %.2f | %.2f | %.2f | %.2f |\n",
                  las_in.empty() ? "synthetic fused" : fs::path(las_in).filename().c_str(), n, minor, pdrf,
                  compressed ? "LAZ" : "LAS", bytes / 1e6, las_bytes / bytes, best_write, n / best_write / 1e6,
                  best_read, n / best_read / 1e6);
      fs::remove(path);
    }
  }
  return 0;
}
