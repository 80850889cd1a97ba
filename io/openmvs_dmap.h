#pragma once
// OpenMVS depth-map files (`depth%04u.dmap`, written by DensifyPointCloud and OpenMVS's importers through
// MVS::ExportDepthDataRaw). Native little-endian layout:
//
//   offset  type         field
//   0       u16          magic, the bytes "DR"
//   2       u8           content flags: 1 depth (required), 2 normals, 4 confidence, 8 views
//   3       u8           padding
//   4       u32 x 2      image width, height (the resolution K refers to)
//   12      u32 x 2      depth width, height (<= the image's)
//   20      f32 x 2      depth min, max of the view
//   28      u16 n + n chars           image path, relative to the folder of the .dmap file
//   ..      u32 m + m x u32           view IDs: the reference view, then its neighbours (1 <= m <= 255)
//   ..      f64 K[9], R[9], C[3]      row-major; x_image = K R (X - C), K at the image resolution above,
//                                     OpenMVS pixel convention: integer coordinates = pixel CENTRES
//   ..      f32 depth[H][W]           z in the camera frame; 0 = invalid
//   ..      f32 normal[H][W][3]       if flag 2 (pixel-interleaved, camera frame)
//   ..      f32 confidence[H][W]      if flag 4
//   ..      u8  views[H][W][4]        if flag 8
//
// The readers check the file length against the header exactly before allocating anything, and throw
// InputError naming the file and what is wrong.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "core/pixel_window.h"
#include "core/raster.h"

namespace sacfuse {

// Content flags of the header (HeaderDepthDataRaw::HAS_*).
enum DmapFlags : uint8_t { kDmapDepth = 1, kDmapNormals = 2, kDmapConfidence = 4, kDmapViews = 8 };

// The camera stored in a .dmap, exactly as OpenMVS writes it (see the layout above).
struct DmapCamera {
  std::array<double, 9> K{};  // row-major intrinsics at the header's image resolution, pixel-centre convention
  std::array<double, 9> R{};  // row-major rotation, camera from world
  std::array<double, 3> C{};  // camera centre in world coordinates
};

// Everything before the depth data, and where each map starts.
struct DmapHeader {
  uint8_t flags = 0;
  uint32_t image_width = 0, image_height = 0;  // pixels
  uint32_t depth_width = 0, depth_height = 0;  // pixels
  float depth_min = 0.0f, depth_max = 0.0f;    // metres
  std::string image_path;                      // as stored: relative to the .dmap's folder
  std::vector<uint32_t> view_ids;              // reference view first
  DmapCamera camera;
  uint64_t depth_offset = 0;       // bytes from the file start to depth[0][0]
  uint64_t normals_offset = 0;     // 0 when the file has no normal map
  uint64_t confidence_offset = 0;  // 0 when absent
  uint64_t views_offset = 0;       // 0 when absent
  uint64_t file_size = 0;          // bytes (equal to the size the header implies)

  bool has(DmapFlags flag) const { return (flags & flag) != 0; }
};

// Header, image path, view IDs and camera; checks the magic, the flags, the sizes and the file length.
DmapHeader ReadDmapHeader(const std::string& path);

// The whole depth map (z, metres; 0 = invalid).
DepthMap ReadDmapDepth(const std::string& path);
// The pixels of `window` (one seek and read per row). Throws InputError for a bad file and Error for a window
// outside the depth map.
DepthMap ReadDmapDepthWindow(const std::string& path, const PixelWindow& window);
// As above with a header already read from `path` (saves re-reading it for many small windows).
DepthMap ReadDmapDepthWindow(const std::string& path, const DmapHeader& header, const PixelWindow& window);

// The optional maps; each throws InputError naming the file when the flags say the file has no such map.
NormalMap ReadDmapNormals(const std::string& path);            // 3 channels, camera frame
Raster<float> ReadDmapConfidence(const std::string& path);     // 1 channel
Raster<uint8_t> ReadDmapViews(const std::string& path);        // 4 channels: indices into view_ids after the first

// What WriteDmap writes. The depth raster sets the depth size; optional maps are written when non-empty and must
// have the depth raster's size (normals 3 channels, confidence 1, views 4).
struct DmapContents {
  uint32_t image_width = 0, image_height = 0;  // >= the depth size
  float depth_min = 0.0f, depth_max = 0.0f;
  std::string image_path;                      // relative to the .dmap's folder; at most 65535 bytes
  std::vector<uint32_t> view_ids;              // 1..255 ids, reference first
  DmapCamera camera;
  DepthMap depth;
  NormalMap normals;
  Raster<float> confidence;
  Raster<uint8_t> views;
};

// Writes atomically (temporary name, fsync, rename); creates the parent folder. Throws Error for contents that
// break the rules above or a failed write.
void WriteDmap(const std::string& path, const DmapContents& contents);

}  // namespace sacfuse
