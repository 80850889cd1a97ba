#pragma once
// An OpenMVS dense folder as input: the `depth%04u.dmap` files DensifyPointCloud (or an OpenMVS importer) leaves
// in its working folder, each holding its view's camera (K, R, C), its depth map and the path of its image
// (relative to that folder). Views are the .dmap files in ascending number order; the binary `.mvs` scene
// archive is not read (every .dmap carries its own camera, which is all fusion needs).
//
// Conventions converted here (io/openmvs_dmap.h has the byte layout):
// - OpenMVS puts integer pixel coordinates at pixel CENTRES, sacfuse at the top-left corner of the top-left
//   pixel: cx_sacfuse = K[0][2] + 0.5, cy_sacfuse = K[1][2] + 0.5.
// - K refers to the header's image size (image_width x image_height). A smaller depth map is back-projected
//   through K scaled per axis the way OpenMVS does (Scene::LoadDMAP, Camera::ScaleK: f * s and
//   (c + 0.5) * s - 0.5), which is exactly sacfuse's PinholeCamera::Scaled in the corner convention.
// - x_image = K R (X - C): cam_from_world = {R, -R C}.
#include <string>
#include <vector>

#include "core/camera.h"
#include "core/rigid3.h"
#include "io/depth_block.h"
#include "io/openmvs_dmap.h"

namespace sacfuse {

class OpenMvsBlock : public DepthBlock {
 public:
  // Lists `dir`'s depth%04u.dmap files and reads their headers and cameras. Throws InputError naming the folder
  // (no .dmap files) or the file (corrupt header, camera not a pinhole with zero skew and a rotation R).
  explicit OpenMvsBlock(const std::string& dir);

  const std::string& source() const override { return dir_; }
  // Views numbered 0..n-1 in .dmap number order; a view's name is its .dmap file name (e.g. "depth0007.dmap").
  const std::vector<View>& views() const override { return views_; }

  std::string DepthMapPath(const View& view) const override;
  // The image the .dmap names, resolved against the folder (absolute paths kept; '\' read as '/').
  std::string ImagePath(const View& view) const override;
  DepthRasterSize DepthSize(const View& view) const override;
  DepthMap ReadDepthMap(const View& view) const override;
  DepthMap ReadDepthWindow(const View& view, const PixelWindow& window) const override;
  // The image at its own resolution: the header's image size or a scale of it with the same aspect (OpenMVS's
  // DensifyPointCloud stores the full-resolution image path with the header size of the resized image it
  // matched). Throws InputError naming the image file and the view when it is missing, undecodable or
  // of another aspect.
  RgbImage ReadImage(const View& view) const override;
  // z of depth pixels back-projected on a sparse grid (16 rows x up to 64 columns of every view), so tile planning
  // gets the block's height range without reading every depth map whole.
  std::vector<double> SceneHeights() const override;
  std::string SceneHeightsSource() const override { return "depth-map sample"; }

 private:
  std::string dir_;
  std::vector<View> views_;
  std::vector<std::string> dmap_paths_;
  std::vector<std::string> image_paths_;  // as stored in each .dmap
};

// OpenMVS camera -> sacfuse. `who` names the file and view in error messages (InputError on `path`).
PinholeCamera PinholeFromDmap(const DmapHeader& header, const std::string& path, const std::string& who);
Rigid3d CamFromWorldFromDmap(const DmapCamera& camera, const std::string& path, const std::string& who);
// sacfuse view -> OpenMVS camera (K at the view's image size, pixel-centre convention).
DmapCamera DmapCameraFromView(const View& view);

// Writes `input` as an OpenMVS folder in `out_dir`: per view (in view order) `depth%04u.dmap` with the view index
// as its ID, its camera, the depth map (invalid pixels as 0) and `images/<view name>.png` (the view's image
// re-encoded losslessly; `images/%04u.png` when the name is not a plain relative path). Throws Error when
// `out_dir` already holds .dmap files or a view has no image, InputError when reading the input fails.
void WriteOpenMvsBlock(const DepthBlock& input, const std::string& out_dir);

}  // namespace sacfuse
