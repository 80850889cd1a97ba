#pragma once
// Per-tile state of a tiled run, on disk under DIR/tiles/ (the state is the files themselves):
//   <id>.laz        the tile's core points, LAZ (absent for a tile whose core got no points). Compressed: at
//                   Dortmund scale the tile files were a third of a run's disk (issue 13). Tiles of versions that
//                   wrote <id>.las are not done for this one (recomputed; ClearTileState removes the old file).
//   <id>.copc.laz   instead of <id>.laz when the run that computed the tile wrote COPC (output.format copc), so
//                   that the tile index DIR/tiles.vpc streams in viewers; the done marker names the tile's file,
//                   so a later run with another output.format keeps done tiles as they are.
//   <id>.<suffix>   the tile's product files (tiles/tile_product.h: e.g. <id>.dsm.tif, its window of the DSM)
//   <id>.done.json  written atomically AFTER the point file and the product files are renamed into place: file,
//                   count, size, bounds, checksum, and each product file's size and checksum
//   <id>.failed.json  why the tile's last attempt threw
// A tile is done only when its marker parses, names the current result-settings hash, its inputs (below) are the
// current ones, its points per view add up to its count (the merge takes them from here, it does not decode the
// tile), and its LAS file exists with the recorded size, a readable header with the recorded count, and
// the recorded FNV-1a 64 checksum, and every product file it records exists with the recorded size and checksum.
// The marker records the tile's inputs: its core and halo and, for every view whose window it reads, the window
// and the view's identity (io/view_identity.h: depth map, image, camera). A tile is recomputed exactly when one
// of those differs from the current plan and inputs.
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/pixel_window.h"
#include "core/view.h"
#include "io/view_identity.h"
#include "tiles/tile_plan.h"

namespace sacfuse {

struct TileInputView {
  uint32_t view = 0;
  std::string name;
  PixelWindow window;
  ViewIdentity identity;
};

struct TileInputs {
  std::array<double, 4> core = {0, 0, 0, 0}, halo = {0, 0, 0, 0};  // min x, min y, max x, max y
  std::vector<TileInputView> views;                                // in the tile's view order
};

// The inputs of a planned tile: `views` and `identities` by view index (the block's).
TileInputs TileInputsOf(const PlannedTile& tile, const std::vector<View>& views,
                        const std::vector<ViewIdentity>& identities);

// A product file of a tile (tiles/tile_product.h), as its done marker records it.
struct TileProductFile {
  std::string suffix;       // DIR/tiles/<id>.<suffix>
  uint64_t file_size = 0;
  std::string checksum;     // FNV-1a 64, hex
};

struct TileDoneMarker {
  std::string id;
  std::string config_hash;  // ResultSettingsHash of the run that wrote it
  uint64_t points = 0;      // 0: no point file
  std::string file;         // the point file's name in DIR/tiles: <id>.laz or <id>.copc.laz ("" when points == 0)
  uint64_t file_size = 0;   // its bytes
  std::string checksum;     // FNV-1a 64 of every byte of the file, hex ("" when points == 0)
  std::array<double, 3> min = {0, 0, 0}, max = {0, 0, 0};  // header bounds
  uint64_t views = 0;                                      // views the tile used
  // Points of <id>.laz per source view: (the block's view index, points), views with points only, ascending.
  std::vector<std::pair<uint32_t, uint64_t>> points_per_view;
  double seconds = 0.0;                                    // wall time of the tile
  double peak_rss_mib = 0.0;                               // process peak RSS when the tile finished
  int64_t finished_unix_ns = 0;                            // wall clock when the marker was written
  std::optional<TileInputs> inputs;                        // absent in markers of older versions
  std::vector<TileProductFile> products;                   // the tile's product files (none: no products)
};

struct TileCheck {
  bool done = false;
  std::string reason;  // why not done ("no marker", "LAS size 12 != 345", ...); "" when done
  // Not done because its inputs changed: each changed view of the tile as "view 12 (a.jpg): depth map changed
  // (...)", or how the tile's geometry or windows changed.
  std::vector<std::string> input_changes;
};

// Name of a tile's point file in DIR/tiles: <id>.laz (LAZ), or <id>.copc.laz (COPC).
std::string TileCloudFileName(const std::string& id, bool copc);
// The point file a done marker names (markers of versions before COPC tiles name none: <id>.laz).
std::string TileCloudPath(const std::string& tiles_dir, const TileDoneMarker& marker);
std::string TileDonePath(const std::string& tiles_dir, const std::string& id);
std::string TileFailedPath(const std::string& tiles_dir, const std::string& id);
// DIR/tiles/<id>.<suffix>: a product file of the tile.
std::string TileProductPath(const std::string& tiles_dir, const std::string& id, const std::string& suffix);
// The record of a written product file (size and checksum).
TileProductFile DescribeTileProduct(const std::string& tiles_dir, const std::string& id, const std::string& suffix);

// Fills file, size, count, bounds and checksum from a finished tile point file named `file` in tiles_dir, or
// the empty-tile fields when `file` is "".
TileDoneMarker DescribeTileFile(const std::string& tiles_dir, const std::string& id, const std::string& file);
void WriteTileDoneMarker(const std::string& tiles_dir, const TileDoneMarker& marker);
std::optional<TileDoneMarker> ReadTileDoneMarker(const std::string& tiles_dir, const std::string& id);

// Full check as described above. With full_checksum = false the checksum is not recomputed (size, header and
// count still are): what `sacfuse status` uses to stay cheap. `inputs` null: the inputs are not compared (status,
// which opens no input).
TileCheck VerifyTileDone(const std::string& tiles_dir, const std::string& id, const std::string& config_hash,
                         bool full_checksum = true, const TileInputs* inputs = nullptr);

void WriteTileFailedMarker(const std::string& tiles_dir, const std::string& id, const std::string& reason);
std::optional<std::string> ReadTileFailedReason(const std::string& tiles_dir, const std::string& id);
// Removes a tile's done/failed markers, point file, LAZ or COPC, and the product files named by `product_suffixes`
// (before it is recomputed), and an <id>.las of an older version.
void ClearTileState(const std::string& tiles_dir, const std::string& id,
                    const std::vector<std::string>& product_suffixes = {});


}  // namespace sacfuse
