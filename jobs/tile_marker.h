#pragma once
// Per-tile state of a tiled run, on disk under DIR/tiles/ (the state is the files themselves):
//   <id>.las        the tile's core points (absent for a tile whose core got no points)
//   <id>.done.json  written atomically AFTER <id>.las is renamed into place: count, size, bounds, checksum
//   <id>.failed.json  why the tile's last attempt threw
// A tile is done only when its marker parses, names the current result-settings hash, and its LAS file exists
// with the recorded size, a readable header with the recorded count, and the recorded FNV-1a 64 checksum.
#include <array>
#include <cstdint>
#include <optional>
#include <string>

namespace sacfuse {

struct TileDoneMarker {
  std::string id;
  std::string config_hash;  // ResultSettingsHash of the run that wrote it
  uint64_t points = 0;      // 0: no LAS file
  uint64_t file_size = 0;   // bytes of <id>.las
  std::string checksum;     // FNV-1a 64 of every byte of <id>.las, hex ("" when points == 0)
  std::array<double, 3> min = {0, 0, 0}, max = {0, 0, 0};  // header bounds
  uint64_t views = 0;                                      // views the tile used
  double seconds = 0.0;                                    // wall time of the tile
  double peak_rss_mib = 0.0;                               // process peak RSS when the tile finished
  int64_t finished_unix_ns = 0;                            // wall clock when the marker was written
};

struct TileCheck {
  bool done = false;
  std::string reason;  // why not done ("no marker", "LAS size 12 != 345", ...); "" when done
};

std::string TileLasPath(const std::string& tiles_dir, const std::string& id);
std::string TileDonePath(const std::string& tiles_dir, const std::string& id);
std::string TileFailedPath(const std::string& tiles_dir, const std::string& id);

// Fills size, count, bounds and checksum from a finished tile LAS (points > 0), or the empty-tile fields.
TileDoneMarker DescribeTileLas(const std::string& tiles_dir, const std::string& id, bool has_las);
void WriteTileDoneMarker(const std::string& tiles_dir, const TileDoneMarker& marker);
std::optional<TileDoneMarker> ReadTileDoneMarker(const std::string& tiles_dir, const std::string& id);

// Full check as described above. With full_checksum = false the checksum is not recomputed (size, header and
// count still are): what `sacfuse status` uses to stay cheap.
TileCheck VerifyTileDone(const std::string& tiles_dir, const std::string& id, const std::string& config_hash,
                         bool full_checksum = true);

void WriteTileFailedMarker(const std::string& tiles_dir, const std::string& id, const std::string& reason);
std::optional<std::string> ReadTileFailedReason(const std::string& tiles_dir, const std::string& id);
// Removes a tile's done/failed markers and LAS (before it is recomputed).
void ClearTileState(const std::string& tiles_dir, const std::string& id);

// Deletes every "*.tmp-*" file in `dir` (and its sub-folders when `recursive`), left by a killed run;
// returns how many.
size_t RemoveTemporaryFiles(const std::string& dir, bool recursive = false);

}  // namespace sacfuse
