#include "report/report_writer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>

#include <spdlog/spdlog.h>
#include <tbb/task_arena.h>
#include <tbb/task_group.h>

#include "config/output_layout.h"
#include "core/error.h"
#include "io/atomic_file.h"
#include "io/gdal_raster.h"
#include "io/las_reader.h"
#include "report/report_cross_section.h"
#include "report/report_data.h"
#include "report/report_html.h"
#include "report/report_input_counts.h"
#include "report/report_map_figure.h"
#include "report/report_png.h"
#include "io/resource_usage.h"
#include "tiles/tile_marker.h"

namespace sacfuse {
namespace fs = std::filesystem;
namespace {

constexpr size_t kLasChunk = 1 << 16;
constexpr const char* kFiguresJson = "figures.json";

// Streams fused.las into a top grid sized from its header, one band of the grid's rows per thread.
TopGrid ScanTopGrid(const ReportCloud& cloud, const ReportOptions& o) {
  TopGrid grid = MakeTopGrid(cloud.min[0], cloud.min[1], cloud.max[0], cloud.max[1], cloud.points, o.max_map_cells,
                             o.min_cell_m);
  LasReader reader(cloud.path);
  std::vector<LasPoint> chunk;
  TopGridFiller filler(&grid, static_cast<size_t>(tbb::this_task_arena::max_concurrency()));
  while (reader.Read(&chunk, kLasChunk) > 0) filler.Add(chunk);
  return grid;
}

MapFigure WriteMap(const TopGrid& grid, const std::vector<Rgb>& colours, uint64_t points, const ReportOptions& o,
                   const std::string& report_dir) {
  SourceMapStyle style;
  style.pixels_per_cell = PixelsPerCellFor(grid, o.map_target_px);
  const RgbImage image = RenderSourceMap(grid, colours, style);
  MapFigure m;
  m.present = true;
  m.file = "map.png";
  WritePng((fs::path(report_dir) / m.file).string(), image);
  m.width_px = image.width;
  m.height_px = image.height;
  m.x_min = grid.x_min;
  m.y_max = grid.y_max;
  m.metres_per_px = grid.cell_m / style.pixels_per_cell;
  m.cell_m = grid.cell_m;
  m.points_scanned = points;
  m.cells_total = grid.num_cells();
  for (const uint32_t c : grid.count) m.cells_filled += c > 0 ? 1 : 0;
  return m;
}

// A raster product's thumbnail `file` in the report folder, from the first of `paths` that exists (the single COG
// or the VRT), read at most map_target_px cells on its longer side (GDAL's overviews) and drawn by `render`
// (the raster, the size read, the metres per sample read); absent when the run wrote neither. A raster that cannot
// be read adds the warning "no <what> picture: ..." to `warnings`.
using ThumbnailRenderer = std::function<RgbImage(const RasterFile& raster, int max_side, double* metres_per_px)>;
MapFigure WriteRasterFigure(const std::vector<std::string>& paths, const std::string& file, const std::string& what,
                            const ReportOptions& o, const std::string& report_dir, const ThumbnailRenderer& render,
                            std::vector<std::string>* warnings) {
  MapFigure m;
  std::error_code ec;
  std::string path;
  for (const std::string& p : paths) {
    if (path.empty() && fs::is_regular_file(p, ec)) path = p;
  }
  if (path.empty()) return m;
  try {
    const RasterFile raster(path);
    double metres_per_px = 0.0;
    const RgbImage image = render(raster, o.map_target_px, &metres_per_px);
    m.present = true;
    m.file = file;
    WritePng((fs::path(report_dir) / m.file).string(), image);
    m.width_px = image.width;
    m.height_px = image.height;
    m.x_min = raster.window().west();
    m.y_max = raster.window().north();
    m.metres_per_px = metres_per_px;
    m.cell_m = raster.window().cell_m;
    m.cells_total = raster.window().size();
  } catch (const std::exception& e) {
    warnings->push_back("no " + what + " picture: " + std::string(e.what()));
    m = MapFigure{};
  }
  return m;
}

// The DSM's hill-shade thumbnail (dsm.png) from DIR/dsm.tif or DIR/dsm.vrt.
RgbImage RenderDsmThumbnail(const RasterFile& dsm, int max_side, double* metres_per_px) {
  int cols = 0, rows = 0;
  const std::vector<float> z = dsm.ReadOverview(max_side, &cols, &rows);
  *metres_per_px = dsm.window().cell_m * static_cast<double>(dsm.window().cols) / cols;
  return RenderDsmHillShade(z, cols, rows, *metres_per_px, SourceMapStyle{});
}

// The true orthophoto's thumbnail (ortho.png) from DIR/ortho.tif or DIR/ortho.vrt (overviews averaged), its
// transparent cells light grey.
RgbImage RenderOrthoThumbnail(const RasterFile& ortho, int max_side, double* metres_per_px) {
  if (ortho.bands() != 4) throw Error(ortho.path() + ": not an RGBA raster");
  int cols = 0, rows = 0;
  std::vector<std::vector<float>> bands;
  for (int b = 1; b <= 4; ++b) bands.push_back(ortho.ReadOverview(max_side, &cols, &rows, b));
  RgbImage image(cols, rows, 3, 0);
  constexpr float kBackground = 235.0f;
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < cols; ++c) {
      const size_t i = static_cast<size_t>(r) * cols + c;
      const float a = std::isfinite(bands[3][i]) ? bands[3][i] / 255.0f : 0.0f;
      for (int k = 0; k < 3; ++k) {
        const float v = std::isfinite(bands[k][i]) ? bands[k][i] : 0.0f;
        image.at(r, c, k) = static_cast<uint8_t>(std::lround(std::clamp(a * v + (1 - a) * kBackground, 0.0f, 255.0f)));
      }
    }
  }
  *metres_per_px = ortho.window().cell_m * static_cast<double>(ortho.window().cols) / cols;
  return image;
}

// The files holding the fused points of the strip: for a tiled run whose tiles are all done and placed, the tile
// files whose core meets the strip (far less than fused.las); else fused.las.
std::vector<std::string> AfterFiles(const ReportData& d, const Box2d& strip_box, std::string* source) {
  if (d.tiled && !d.tiles.empty()) {
    std::vector<std::string> files;
    bool usable = true;
    for (const ReportTile& t : d.tiles) {
      usable = usable && t.status == TileStatus::kDone && t.has_core;
      if (usable && t.points > 0 && t.core.Intersects(strip_box)) files.push_back(t.file);
    }
    if (usable) {
      *source = std::to_string(files.size()) + " tile files";
      return files;
    }
  }
  *source = d.cloud.name;
  return {d.cloud.path};
}

std::string ReadTextFile(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream os;
  os << in.rdbuf();
  return os.str();
}

// A run_report.json written before the per-view "before" counts existed (all 0) for a SAC run.
bool NeedsBeforeCounts(const ReportData& d) {
  return d.run.present && d.run.method == "sac" && !d.run.views.empty() &&
         std::all_of(d.run.views.begin(), d.run.views.end(), [](const ViewCounts& v) { return v.before == 0; });
}

// Such a report's counts from the superpixel cache (cluster tables only; never the depth maps).
void FillBeforeCountsFromCache(const DepthBlock& input, const JobConfig& config, ReportData* d) {
  if (input.views().size() != d->run.views.size()) return;
  size_t not_cached = 0;
  const std::vector<uint64_t> counts =
      ValidDepthPixelsPerView(input, SuperpixelCacheDir(config), &not_cached, /*count_rasters=*/false);
  for (size_t i = 0; i < counts.size(); ++i) d->run.views[i].before = counts[i];
  d->warnings.push_back("run_report.json has no per-view 'before' counts (written by an older sacfuse); they were "
                        "taken from the superpixel cache" +
                        (not_cached > 0 ? " (" + std::to_string(not_cached) + " views without one show 0)" : std::string()));
}

// What the cross-section needs from the run (reference, fused points, input, sizes); may add a warning to *d.
CrossSectionInputs CrossSectionFor(ReportData& d, const JobConfig& config, const ReportOptions& o,
                                   const TopGrid& grid, const DepthBlock* input, const std::vector<Rgb>& colours) {
  CrossSectionInputs in;
  in.grid = &grid;
  in.input = input;
  in.colours = colours;
  in.max_points = o.max_profile_points;
  in.max_width_px = o.profile_max_width_px;
  in.min_width_px = o.profile_min_width_px;
  in.min_height_px = o.profile_min_height_px;
  in.max_height_px = o.profile_max_height_px;
  const double area = (d.cloud.max[0] - d.cloud.min[0]) * (d.cloud.max[1] - d.cloud.min[1]);
  in.fallback_gsd_m = std::max(0.01, std::sqrt(std::max(area, 1e-6) / static_cast<double>(d.cloud.points)));
  std::error_code ec;
  if (!config.evaluation.reference.empty()) {
    if (fs::exists(config.evaluation.reference, ec)) {
      in.reference_las = config.evaluation.reference;
    } else {
      d.warnings.push_back("reference " + config.evaluation.reference + " not found: not in the cross-section");
    }
  }
  in.after_files = [&d](const Box2d& box, std::string* source) {
    return AfterFiles(d, box, source);
  };
  return in;
}

void WritePage(const ReportData& data, const ReportFigures& figures, const std::string& report_dir) {
  WriteFileAtomically((fs::path(report_dir) / "index.html").string(), RenderReportPage(data, figures));
}

}  // namespace

std::string ReportDir(const JobConfig& config, const ReportOptions& options) {
  return options.report_dir.empty() ? ReportDir(config) : options.report_dir;
}

ReportFigures WriteHtmlReport(const JobConfig& config, const ReportOptions& o) {
  const auto start = std::chrono::steady_clock::now();
  const std::string report_dir = ReportDir(config, o);
  fs::create_directories(report_dir);
  RemoveTemporaryFiles(report_dir);  // left by a report killed while writing
  ReportData data = GatherReportData(config);
  std::unique_ptr<DepthBlock> input;
  if (o.before_profile || NeedsBeforeCounts(data)) {
    try {
      if (!o.open_input) throw Error("no way to open it was given");
      input = o.open_input();
    } catch (const std::exception& e) {
      data.warnings.push_back(std::string("input not readable (no 'before' cross-section): ") + e.what());
    }
  }
  if (input && NeedsBeforeCounts(data)) FillBeforeCountsFromCache(*input, config, &data);
  const std::vector<Rgb> colours = ReportViewColours(data);
  ReportFigures figures;
  // The pictures that need nothing of each other are drawn and encoded side by side: the DSM and orthophoto
  // thumbnails from the start, the map once the top grid is scanned, beside the cross-section. Their warnings
  // join the page's in a fixed order.
  std::vector<std::string> dsm_warnings, ortho_warnings;
  tbb::task_group pictures;
  pictures.run([&] {
    figures.dsm = WriteRasterFigure({DsmPath(config), DsmVrtPath(config)}, "dsm.png", "DSM", o, report_dir,
                                    RenderDsmThumbnail, &dsm_warnings);
  });
  pictures.run([&] {
    figures.ortho = WriteRasterFigure({OrthoPath(config), OrthoVrtPath(config)}, "ortho.png", "orthophoto", o,
                                      report_dir, RenderOrthoThumbnail, &ortho_warnings);
  });
  if (data.cloud.exists && data.cloud.points > 0) {
    const auto map_start = std::chrono::steady_clock::now();
    TopGrid grid;
    bool scanned = false;
    try {
      grid = ScanTopGrid(data.cloud, o);
      scanned = true;
    } catch (const Error& e) {  // e.g. a cloud cut short after its header: no map, the rest of the report stays
      data.warnings.push_back(std::string("no map: ") + e.what());
      figures.profile.reason = "the fused cloud could not be read";
    }
    const auto profile_start = std::chrono::steady_clock::now();
    figures.map_seconds = std::chrono::duration<double>(profile_start - map_start).count();
    if (!o.before_profile) input.reset();
    if (scanned) {
      std::string map_error;
      tbb::task_group map_picture;
      map_picture.run([&] {
        const auto start_map = std::chrono::steady_clock::now();
        try {
          figures.map = WriteMap(grid, colours, data.cloud.points, o, report_dir);
        } catch (const Error& e) {
          map_error = e.what();
        }
        figures.map_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start_map).count();
      });
      const size_t map_warning_at = data.warnings.size();
      try {
        figures.profile = MakeCrossSection(CrossSectionFor(data, config, o, grid, input.get(), colours), report_dir);
      } catch (const Error& e) {
        figures.profile = ProfileFigure{};
        figures.profile.reason = e.what();
      }
      map_picture.wait();
      if (!map_error.empty()) {
        data.warnings.insert(data.warnings.begin() + static_cast<std::ptrdiff_t>(map_warning_at), "no map: " + map_error);
      }
      if (!figures.profile.before_reason.empty()) {
        data.warnings.push_back("no 'before' cross-section: " + figures.profile.before_reason);
      }
    }
    figures.profile_seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - profile_start).count();
  } else {
    figures.profile.reason = data.cloud.exists ? data.cloud.name + " has no points" : "no " + data.cloud.name;
  }
  pictures.wait();
  data.warnings.insert(data.warnings.end(), dsm_warnings.begin(), dsm_warnings.end());
  data.warnings.insert(data.warnings.end(), ortho_warnings.begin(), ortho_warnings.end());
  figures.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  figures.peak_rss_mib = PeakRssMiB();
  WriteFileAtomically((fs::path(report_dir) / kFiguresJson).string(), ReportFiguresToJson(figures));
  WritePage(data, figures, report_dir);
  return figures;
}

void RewriteHtmlReportPage(const JobConfig& config, const ReportOptions& o) {
  const std::string report_dir = ReportDir(config, o);
  const fs::path figures_path = fs::path(report_dir) / kFiguresJson;
  std::error_code ec;
  if (!fs::exists(figures_path, ec)) {
    WriteHtmlReport(config, o);
    return;
  }
  ReportFigures figures;
  try {
    figures = ReportFiguresFromJson(ReadTextFile(figures_path));
  } catch (const std::exception& e) {
    spdlog::warn("{} unreadable ({}); rewriting the whole report", figures_path.string(), e.what());
    WriteHtmlReport(config, o);
    return;
  }
  WritePage(GatherReportData(config), figures, report_dir);
}

void WriteHtmlReportOrWarn(const JobConfig& config, const ReportOptions& o) {
  try {
    const ReportFigures f = WriteHtmlReport(config, o);
    spdlog::info("report: {} ({:.1f} s)", (fs::path(ReportDir(config, o)) / "index.html").string(), f.seconds);
  } catch (const std::exception& e) {
    spdlog::warn("the HTML report was not written: {}", e.what());
  }
}

}  // namespace sacfuse
