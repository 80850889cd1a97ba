#pragma once
// What a view's inputs are, so that caches and done markers made from them are reused only while the inputs are
// the same (issue 14: "inputs are part of the state"). A view's identity is its depth map file, its image file
// (each: size, modification time in ns, and a cheap content fingerprint, Fnv1a64FileEdges over the first and last
// 64 KiB and the size), its camera (a hash of the intrinsics and the pose as read) and its stereo partners (the
// views its depth map was matched with, as the input names them, e.g. COLMAP's stereo/patch-match.cfg). A file counts as changed
// when any of the three differs, so an edit inside a large file that keeps its size is still caught by its mtime.
// The files come from the DepthBlock (DepthMapPath, ImagePath): one implementation for every input format.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/view.h"
#include "io/depth_block.h"

namespace sacfuse {

constexpr size_t kIdentityEdgeBytes = 64 * 1024;

struct FileIdentity {
  bool exists = false;  // false: no such file (or the format has none: an input without images)
  uint64_t size = 0;
  int64_t mtime_ns = 0;
  uint64_t content_hash = 0;  // Fnv1a64FileEdges(path, size, kIdentityEdgeBytes)
};

struct ViewIdentity {
  FileIdentity depth, image;
  uint64_t camera_hash = 0;    // CameraHash(view)
  uint64_t partners_hash = 0;  // PartnersHash(view); 0 when the input names no partners
};

// Which parts of a view's inputs a derived file depends on.
enum ViewInputParts : unsigned {
  kDepthInput = 1u,
  kImageInput = 2u,
  kCameraInput = 4u,
  kPartnersInput = 8u,
  kAllViewInputs = 15u,
};

// `path` empty or missing: exists = false. Throws InputError when it exists but cannot be read.
FileIdentity IdentifyFile(const std::string& path);
// FNV-1a 64 of the intrinsics (size, fx, fy, cx, cy) and pose (rotation, translation), as their bytes.
uint64_t CameraHash(const View& view);
// FNV-1a 64 of the view's matching partners (block indices, in order); 0 for none.
uint64_t PartnersHash(const View& view);
ViewIdentity IdentifyView(const DepthBlock& input, const View& view);

// Identities of every view of a block (by view index), with the bytes read and time taken for the log.
struct BlockIdentity {
  std::vector<ViewIdentity> views;
  uint64_t bytes_hashed = 0;
  double seconds = 0.0;
};
BlockIdentity IdentifyBlock(const DepthBlock& input);
// One digest of every view's identity (hex), e.g. to key a plan to the inputs it was made from.
std::string IdentitiesDigest(const std::vector<ViewIdentity>& identities);

// "" when `before` and `now` agree in `parts`; otherwise why not, e.g.
// "depth map changed (size 1228800 -> 1228800, content hash differs)", "image changed (modified time differs;
// size and sampled content equal)", "camera changed (pose or intrinsics)", "stereo partners changed"; several
// separated by "; ".
std::string DescribeViewChange(const ViewIdentity& before, const ViewIdentity& now, unsigned parts = kAllViewInputs);

// Inputs pinned for the length of a run: the views' files (depth map, image) identified now must equal `pinned`
// (identified when the run started, by view index), else InputError naming the first changed file: "<file>:
// depth map changed (size ..., content hash differs) during this run (view 12 (a.jpg)): the fused cloud was not
// written ...". Called before a run writes its cloud.
void CheckInputsUnchanged(const DepthBlock& input, const std::vector<ViewIdentity>& pinned);

// "view 12 (IMG_0012.jpg)".
std::string ViewLabel(const View& view);

// A compact JSON object (one line) and back; nullopt for text that is not one.
std::string ViewIdentityJson(const ViewIdentity& identity);
std::optional<ViewIdentity> ParseViewIdentityJson(const std::string& text);
std::string FileIdentityJson(const FileIdentity& identity);
std::optional<FileIdentity> ParseFileIdentityJson(const std::string& text);
bool operator==(const FileIdentity& a, const FileIdentity& b);

}  // namespace sacfuse
