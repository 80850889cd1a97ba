#pragma once
// A COLMAP dense workspace as image_undistorter + patch_match_stereo leave it:
//   images/<name>, sparse/{cameras,images,points3D}.{bin|txt},
//   stereo/depth_maps/<name>.{geometric|photometric}.bin, stereo/normal_maps/<name>.<type>.bin,
//   stereo/fusion.cfg (one image name per line; when present, only those images are used, in that order),
//   stereo/patch-match.cfg (optional: each view's matching partners when it names them; io/colmap_patch_match_config.h).
// <name> may contain sub-folders.
#include <mutex>
#include <string>
#include <vector>

#include "core/consistency_graph.h"
#include "core/raster.h"
#include "core/view.h"
#include "io/colmap_model.h"
#include "io/depth_block.h"

namespace sacfuse {

enum class ColmapDepthType { kGeometric, kPhotometric };

class ColmapWorkspace : public DepthBlock {
 public:
  // Reads the sparse model and fusion.cfg. Views are numbered 0..n-1 in fusion.cfg order (else images order).
  // Cameras must be PINHOLE or SIMPLE_PINHOLE, or another model whose distortion parameters are all zero.
  // An image without a depth map of `depth_type` is left out with a warning naming the file, as COLMAP's
  // stereo_fusion does (the dense matcher failed on it, or fusion.cfg lists images it did not match); when none has
  // one, InputError says which depth maps the workspace has instead and what to set or run.
  ColmapWorkspace(const std::string& dir, ColmapDepthType depth_type);

  const std::string& dir() const { return dir_; }
  const std::string& source() const override { return dir_; }
  const std::vector<View>& views() const override { return views_; }
  const ColmapModel& model() const { return model_; }

  std::string ImagePath(const View& view) const override;
  std::string DepthMapPath(const View& view) const override;
  std::string NormalMapPath(const View& view) const;

  // Throws InputError naming the file (and the view) on missing, corrupt or mis-sized data.
  DepthRasterSize DepthSize(const View& view) const override;
  DepthMap ReadDepthMap(const View& view) const override;
  DepthMap ReadDepthWindow(const View& view, const PixelWindow& window) const override;
  DepthMap ReadDepthRows(const View& view, const std::vector<int>& rows) const override;
  NormalMap ReadNormalMap(const View& view) const;
  RgbImage ReadImage(const View& view) const override;
  // z of the sparse model's points; a model without points (an empty points3D file) gives a sample of the depth
  // maps instead (SampleDepthMapHeights), with a warning naming the file (io/input_warnings.h).
  std::vector<double> SceneHeights() const override;
  std::string SceneHeightsSource() const override;

  // Dense-matching consistency (stereo/consistency_graphs/<name>.<type>.bin), when the input has it. COLMAP's
  // image indices (images order of the sparse model) are mapped to view indices; images not used are dropped.
  std::string ConsistencyGraphPath(const View& view) const;
  bool HasConsistencyGraph(const View& view) const override;
  ConsistencyGraph ReadConsistencyGraph(const View& view) const override;

 private:
  // The model indices of `order` whose depth map exists (see the constructor).
  std::vector<size_t> WithDepthMaps(const std::vector<size_t>& order) const;
  // Sets the views' matching_partners from stereo/patch-match.cfg when it names sources; a malformed file is a
  // warning naming its line (the partners stay unknown).
  void ReadMatchingPartners();

  std::string dir_;
  ColmapDepthType depth_type_;
  ColmapModel model_;
  std::vector<View> views_;
  std::vector<uint32_t> model_index_to_view_;  // images order of the sparse model -> view index (or UINT32_MAX)
  mutable std::once_flag heights_once_;         // a model without points: the depth sample, taken once
  mutable std::vector<double> sampled_heights_;
};

// Writes stereo/fusion.cfg and stereo/patch-match.cfg for the given image names. `sources` (empty, or one list per
// image): the images each was matched with, named in patch-match.cfg; an image without (or all, when `sources` is
// empty) gets COLMAP's "__auto__, 20". Throws Error on a name that cannot be written (empty, a line break, a comma).
void WriteColmapStereoConfigs(const std::string& workspace_dir, const std::vector<std::string>& image_names,
                              const std::vector<std::vector<std::string>>& sources = {});

}  // namespace sacfuse
