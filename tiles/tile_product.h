#pragma once
// A file a tile makes beside its points: the tile's window of a raster product (the DSM's raw cells, and the true
// orthophoto's), made right after the tile's LAZ is written and before its done marker, so the marker covers it
// (tiles/tile_marker.h: its size and checksum; a tile whose product file is missing or altered is not done and is
// recomputed, rewriting the file). The tile worker knows only this interface; jobs implements it
// (jobs/dsm_product.h) and the run assembles the tiles' files into the block's product after the merge.
#include <string>
#include <vector>

#include "tiles/tile_plan.h"

namespace sacfuse {

class TileProduct {
 public:
  virtual ~TileProduct() = default;
  // The file names after "<id>." the product may write, e.g. "dsm.tif": DIR/tiles/<id>.<suffix>
  // (tiles/tile_marker.h TileProductPath).
  virtual std::vector<std::string> suffixes() const = 0;
  // Writes the tile's files (each atomically: io/atomic_file.h) from the tile's point file `las_path` ("" when the
  // tile has no points); returns the suffixes written (none when the tile has nothing for this product). Called
  // from several worker threads at once; throws on errors (the tile then fails).
  virtual std::vector<std::string> Make(const PlannedTile& tile, const std::string& las_path,
                                        const std::string& tiles_dir) const = 0;
};

}  // namespace sacfuse
