#pragma once
// The tile map of the run report: every tile with views as a square at its place (north up), coloured by status
// (done / failed / pending) or by its wall time, labelled with its id; hovering shows its numbers. For an untiled
// run, one rectangle: the extent of the cloud, labelled "untiled". Pure: tiles in, SVG text out.
#include <cstdint>
#include <string>
#include <vector>

#include "report/report_colours.h"
#include "tiling/footprint.h"

namespace sacfuse {

enum class TileStatus { kDone, kFailed, kPending };

struct ReportTile {
  std::string id;            // "ix_iy"
  int ix = 0, iy = 0;        // grid column (x) and row (y, northwards), parsed from the id
  bool has_core = false;     // core bounds known (from plan.json); else placed by ix, iy
  Box2d core;             // world XY, metres
  TileStatus status = TileStatus::kPending;
  std::string reason;        // failed: the error; pending: why not done
  uint64_t points = 0;       // done: points in its core
  std::string file;          // done: its point file (tiles/<id>.laz or <id>.copc.laz)
  uint64_t views = 0;        // done: views it used
  double seconds = 0.0;      // done: wall time
  double peak_rss_mib = 0.0;             // done: process peak RSS when it finished
  uint64_t memory_estimate_bytes = 0;    // plan's estimate (0 = unknown)
};

enum class TileColouring { kStatus, kTime };

const char* TileStatusName(TileStatus status);  // "done" | "failed" | "pending"
Rgb TileStatusColour(TileStatus status);
// Wall-time ramp from light yellow (t_min) through orange to dark red (t_max).
Rgb TimeRampColour(double t, double t_min, double t_max);

// The tiles drawn into an SVG at most width_px wide and max_height_px high (aspect kept). Pending and failed
// tiles in the time map are grey (failed: red outline).
std::string TileMapSvg(const std::vector<ReportTile>& tiles, TileColouring colouring, double width_px,
                       double max_height_px);

// An untiled run: one rectangle of the extent's aspect, "untiled" and its size in metres.
std::string UntiledExtentSvg(const Box2d& extent, double width_px, double max_height_px);

}  // namespace sacfuse
