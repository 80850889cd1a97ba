#pragma once
// The input of a fusion job, whatever format it came in: the oriented views of a block and, per view, its depth
// raster (read whole or by window), its image, and what else the format knows (scene heights, dense-matching
// consistency). Jobs see only this interface; each input format (COLMAP workspace, OpenMVS .dmap files, depth
// rasters with a camera file) implements it.
#include <memory>
#include <string>
#include <vector>

#include "core/consistency_graph.h"
#include "core/pixel_window.h"
#include "core/raster.h"
#include "core/view.h"

namespace sacfuse {

// Width and height of a view's depth raster, pixels (the depth raster may be smaller than the image: the view's
// intrinsics are at image resolution and are scaled by the readers of depth pixels).
struct DepthRasterSize {
  int width = 0, height = 0;
};

class DepthBlock {
 public:
  virtual ~DepthBlock() = default;

  // What names this input in messages (a folder or file).
  virtual const std::string& source() const = 0;
  // Views numbered 0..n-1; views()[i].index == i.
  virtual const std::vector<View>& views() const = 0;

  // The file holding a view's depth (for messages and cache keys).
  virtual std::string DepthMapPath(const View& view) const = 0;
  // The file holding a view's image, or "" when the input has none. With DepthMapPath and the view's camera, what
  // a view's identity is made of (io/view_identity.h): caches and tile markers are valid only while it is unchanged.
  virtual std::string ImagePath(const View& view) const = 0;
  // Size of a view's depth raster, read from its header only. Throws InputError naming the file and view.
  virtual DepthRasterSize DepthSize(const View& view) const = 0;
  // A view's whole depth raster (z in the camera frame, metres; <= 0 or non-finite = invalid).
  virtual DepthMap ReadDepthMap(const View& view) const = 0;
  // Rows and columns of `window` only (must fit in the raster); reads no more of the file than it needs to.
  virtual DepthMap ReadDepthWindow(const View& view, const PixelWindow& window) const = 0;
  // The rows `rows` (each in [0, height)) at full width: row i of the result is rows[i] of the map (co-registration
  // reads every k-th row). Checked like ReadDepthMap. This default reads the whole map; a format that can read
  // rows alone (COLMAP's arrays) reads only those.
  virtual DepthMap ReadDepthRows(const View& view, const std::vector<int>& rows) const;
  // The view's image (RGB, full resolution), or an empty raster when the input has no images (points then get
  // no colour).
  virtual RgbImage ReadImage(const View& view) const = 0;

  // Heights (world z, metres) of scene points the input knows besides the depth maps (e.g. sparse tie points),
  // used to bound the block's height range when planning tiles; empty when the format has none.
  virtual std::vector<double> SceneHeights() const { return {}; }
  // Where SceneHeights come from, for the log and plan.json ("sparse points", "depth-map sample", ...).
  virtual std::string SceneHeightsSource() const { return "sparse points"; }

  // Dense-matching consistency graphs (which views agree with each pixel), when the input has them.
  virtual bool HasConsistencyGraph(const View& /*view*/) const { return false; }
  virtual ConsistencyGraph ReadConsistencyGraph(const View& view) const;
};

// Heights (world z, metres) of a sample of the views' valid depth pixels: in each view 16 rows evenly spaced, 64
// columns of each, read by window (DepthSize, ReadDepthWindow). The scene heights of inputs that have no other
// (OpenMVS, a COLMAP model without sparse points), for the block's height range (tiles/tile_plan.h).
std::vector<double> SampleDepthMapHeights(const DepthBlock& input);

// For the readers of whole depth maps: warns (io/input_warnings.h) naming the view and `path` when `depth` has no
// valid pixel (the view then adds no points); returns `depth`.
DepthMap WarnIfNoValidDepth(DepthMap depth, const View& view, const std::string& path);

}  // namespace sacfuse
