#include "io/view_identity.h"

#include <sys/stat.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <exception>

#include <nlohmann/json.hpp>
#include <tbb/parallel_for.h>

#include "core/error.h"
#include "io/file_checksum.h"
#include "io/input_file.h"

namespace sacfuse {
namespace {

template <typename T>
void AppendBytes(std::string* bytes, const T& value) {
  bytes->append(reinterpret_cast<const char*>(&value), sizeof(value));
}

nlohmann::json FileJson(const FileIdentity& f) {
  if (!f.exists) return {{"exists", false}};
  return {{"size", f.size}, {"mtime_ns", f.mtime_ns}, {"hash", HexDigest(f.content_hash)}};
}

FileIdentity FileFromJson(const nlohmann::json& j) {
  FileIdentity f;
  if (j.contains("exists") && !j.at("exists").get<bool>()) return f;
  f.exists = true;
  f.size = j.at("size").get<uint64_t>();
  f.mtime_ns = j.at("mtime_ns").get<int64_t>();
  f.content_hash = std::stoull(j.at("hash").get<std::string>(), nullptr, 16);
  return f;
}

std::string DescribeFileChange(const char* what, const FileIdentity& before, const FileIdentity& now) {
  if (before == now) return "";
  if (!before.exists) return std::string(what) + " appeared";
  if (!now.exists) return std::string(what) + " is gone";
  std::string detail = "size " + std::to_string(before.size) + " -> " + std::to_string(now.size);
  if (before.content_hash != now.content_hash) {
    detail += ", content hash differs";
  } else if (before.size == now.size) {
    detail += ", modified time differs; sampled content equal";
  }
  return std::string(what) + " changed (" + detail + ")";
}

}  // namespace

bool operator==(const FileIdentity& a, const FileIdentity& b) {
  if (a.exists != b.exists) return false;
  return !a.exists || (a.size == b.size && a.mtime_ns == b.mtime_ns && a.content_hash == b.content_hash);
}

FileIdentity IdentifyFile(const std::string& path) {
  FileIdentity f;
  if (path.empty()) return f;
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) {
    if (errno == ENOENT) return f;
    ThrowInputOsError(path, "input file", errno);
  }
  CheckInputFile(path, "input file");
  f.exists = true;
  f.size = static_cast<uint64_t>(st.st_size);
  f.mtime_ns = static_cast<int64_t>(st.st_mtim.tv_sec) * 1000000000 + st.st_mtim.tv_nsec;
  f.content_hash = Fnv1a64FileEdges(path, f.size, kIdentityEdgeBytes);
  return f;
}

uint64_t CameraHash(const View& view) {
  std::string bytes;
  const PinholeCamera& c = view.camera;
  AppendBytes(&bytes, c.width);
  AppendBytes(&bytes, c.height);
  for (const double v : {c.fx, c.fy, c.cx, c.cy}) AppendBytes(&bytes, v);
  const Eigen::Quaterniond& q = view.cam_from_world.rotation;
  for (const double v : {q.w(), q.x(), q.y(), q.z()}) AppendBytes(&bytes, v);
  const Eigen::Vector3d& t = view.cam_from_world.translation;
  for (int i = 0; i < 3; ++i) AppendBytes(&bytes, t[i]);
  return Fnv1a64(bytes);
}

uint64_t PartnersHash(const View& view) {
  if (view.matching_partners.empty()) return 0;
  std::string bytes;
  for (const uint32_t partner : view.matching_partners) AppendBytes(&bytes, partner);
  return Fnv1a64(bytes);
}

ViewIdentity IdentifyView(const DepthBlock& input, const View& view) {
  ViewIdentity id;
  id.depth = IdentifyFile(input.DepthMapPath(view));
  id.image = IdentifyFile(input.ImagePath(view));
  id.camera_hash = CameraHash(view);
  id.partners_hash = PartnersHash(view);
  return id;
}

BlockIdentity IdentifyBlock(const DepthBlock& input) {
  const auto start = std::chrono::steady_clock::now();
  BlockIdentity block;
  const std::vector<View>& views = input.views();
  block.views.resize(views.size());
  // Views in parallel (each reads its files' edges): a serial share of co-registration and of the tiled plan. An
  // unreadable file throws as a serial loop would: the first view's error.
  std::vector<std::exception_ptr> errors(views.size());
  tbb::parallel_for(size_t{0}, views.size(), [&](size_t i) {
    try {
      block.views[i] = IdentifyView(input, views[i]);
    } catch (...) {
      errors[i] = std::current_exception();
    }
  });
  for (const std::exception_ptr& e : errors) {
    if (e) std::rethrow_exception(e);
  }
  for (const ViewIdentity& id : block.views) {
    for (const FileIdentity* f : {&id.depth, &id.image}) {
      if (f->exists) block.bytes_hashed += std::min<uint64_t>(f->size, 2 * kIdentityEdgeBytes);
    }
  }
  block.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return block;
}

std::string IdentitiesDigest(const std::vector<ViewIdentity>& identities) {
  std::string all;
  for (const ViewIdentity& id : identities) all += ViewIdentityJson(id) + "\n";
  return HexDigest(Fnv1a64(all));
}

std::string DescribeViewChange(const ViewIdentity& before, const ViewIdentity& now, unsigned parts) {
  std::string out;
  const auto add = [&out](const std::string& change) {
    if (!change.empty()) out += (out.empty() ? "" : "; ") + change;
  };
  if (parts & kDepthInput) add(DescribeFileChange("depth map", before.depth, now.depth));
  if (parts & kImageInput) add(DescribeFileChange("image", before.image, now.image));
  if ((parts & kCameraInput) && before.camera_hash != now.camera_hash) add("camera changed (pose or intrinsics)");
  if ((parts & kPartnersInput) && before.partners_hash != now.partners_hash) {
    add("stereo partners changed (the views its depth map was matched with)");
  }
  return out;
}

void CheckInputsUnchanged(const DepthBlock& input, const std::vector<ViewIdentity>& pinned) {
  for (const View& view : input.views()) {
    if (view.index >= pinned.size()) continue;
    const ViewIdentity& before = pinned[view.index];
    const std::string depth_path = input.DepthMapPath(view), image_path = input.ImagePath(view);
    const auto check = [&](const char* what, const std::string& path, const FileIdentity& then) {
      const std::string change = DescribeFileChange(what, then, IdentifyFile(path));
      if (change.empty()) return;
      throw InputError(path, change + " during this run (" + ViewLabel(view) + "): the fused cloud was not "
                             "written, as it would mix the file's old and new contents; run again (the next run "
                             "recomputes what the change affects)");
    };
    check("depth map", depth_path, before.depth);
    check("image", image_path, before.image);
  }
}

std::string ViewLabel(const View& view) { return "view " + std::to_string(view.index) + " (" + view.name + ")"; }

std::string ViewIdentityJson(const ViewIdentity& id) {
  nlohmann::json j = {
      {"depth", FileJson(id.depth)}, {"image", FileJson(id.image)}, {"camera", HexDigest(id.camera_hash)}};
  // Only where the input names partners, so that the identities of inputs without them read as before.
  if (id.partners_hash != 0) j["partners"] = HexDigest(id.partners_hash);
  return j.dump();
}

std::optional<ViewIdentity> ParseViewIdentityJson(const std::string& text) {
  try {
    const nlohmann::json j = nlohmann::json::parse(text);
    ViewIdentity id;
    id.depth = FileFromJson(j.at("depth"));
    id.image = FileFromJson(j.at("image"));
    id.camera_hash = std::stoull(j.at("camera").get<std::string>(), nullptr, 16);
    if (j.contains("partners")) id.partners_hash = std::stoull(j.at("partners").get<std::string>(), nullptr, 16);
    return id;
  } catch (const std::exception&) {
    return std::nullopt;
  }
}

std::string FileIdentityJson(const FileIdentity& identity) { return FileJson(identity).dump(); }

std::optional<FileIdentity> ParseFileIdentityJson(const std::string& text) {
  try {
    return FileFromJson(nlohmann::json::parse(text));
  } catch (const std::exception&) {
    return std::nullopt;
  }
}

}  // namespace sacfuse
