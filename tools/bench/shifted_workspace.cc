#include "tools/bench/shifted_workspace.h"

#include <filesystem>

#include "core/error.h"
#include "io/colmap_model.h"
#include "tools/bench/model_shift.h"

namespace sacfuse {
namespace {

namespace fs = std::filesystem;

// DEST/name -> target, replacing an older link; refuses to touch anything that is not a link.
void LinkInto(const fs::path& dest, const std::string& name, const fs::path& target) {
  const fs::path link = dest / name;
  if (fs::is_symlink(fs::symlink_status(link))) {
    fs::remove(link);
  } else if (fs::exists(fs::symlink_status(link))) {
    throw Error(link.string() + " exists and is not a symbolic link; choose an empty output folder");
  }
  fs::create_directory_symlink(target, link);
}

}  // namespace

ShiftedWorkspace PrepareShiftedWorkspace(const std::string& source_workspace, const std::string& dest_dir) {
  const fs::path source = fs::absolute(source_workspace).lexically_normal();
  const fs::path dest = fs::absolute(dest_dir).lexically_normal();
  for (const char* part : {"sparse", "images", "stereo/depth_maps", "stereo/normal_maps"}) {
    if (!fs::is_directory(source / part)) {
      throw InputError((source / part).string(),
                       std::string("missing; COLMAP's stereo_fusion needs ") + part + "/ in the workspace" +
                           (std::string(part) == "stereo/normal_maps" ? " (simulate without --no-normal-maps)" : ""));
    }
  }
  if (!fs::is_regular_file(source / "stereo" / "fusion.cfg")) {
    throw InputError((source / "stereo" / "fusion.cfg").string(), "missing; COLMAP's stereo_fusion reads the views "
                                                                  "to fuse from it");
  }
  if (source == dest) throw Error("the shifted workspace must not be the source workspace " + source.string());

  ColmapModel model = ReadColmapModel((source / "sparse").string());
  ShiftedWorkspace result;
  result.path = dest.string();
  result.offset = ChooseModelOffset(model);
  result.images = model.images.size();
  result.points3D = model.points3D.size();
  ShiftColmapModel(&model, result.offset);

  fs::create_directories(dest);
  const fs::path sparse = dest / "sparse";
  if (fs::is_symlink(fs::symlink_status(sparse))) fs::remove(sparse);
  fs::create_directories(sparse);
  for (const char* stale : {"cameras.txt", "images.txt", "points3D.txt"}) fs::remove(sparse / stale);
  WriteColmapModelBinary(model, sparse.string());
  LinkInto(dest, "images", source / "images");
  LinkInto(dest, "stereo", source / "stereo");
  return result;
}

}  // namespace sacfuse
