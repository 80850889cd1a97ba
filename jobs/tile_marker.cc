#include "jobs/tile_marker.h"

#include <chrono>
#include <filesystem>
#include <fstream>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "io/atomic_file.h"
#include "io/file_checksum.h"
#include "io/las_reader.h"

namespace sacfuse {
namespace fs = std::filesystem;
namespace {

std::optional<nlohmann::json> ReadJsonFile(const std::string& path) {
  std::ifstream in(path);
  if (!in) return std::nullopt;
  try {
    return nlohmann::json::parse(in);
  } catch (const std::exception&) {
    return std::nullopt;
  }
}

std::string Path(const std::string& tiles_dir, const std::string& name) {
  return (fs::path(tiles_dir) / name).string();
}

}  // namespace

std::string TileLasPath(const std::string& tiles_dir, const std::string& id) { return Path(tiles_dir, id + ".las"); }
std::string TileDonePath(const std::string& tiles_dir, const std::string& id) {
  return Path(tiles_dir, id + ".done.json");
}
std::string TileFailedPath(const std::string& tiles_dir, const std::string& id) {
  return Path(tiles_dir, id + ".failed.json");
}

TileDoneMarker DescribeTileLas(const std::string& tiles_dir, const std::string& id, bool has_las) {
  TileDoneMarker m;
  m.id = id;
  if (!has_las) return m;
  const std::string las = TileLasPath(tiles_dir, id);
  m.file_size = fs::file_size(las);
  const LasHeader header = LasReader(las).header();
  m.points = header.point_count;
  for (int a = 0; a < 3; ++a) {
    m.min[a] = header.min[a];
    m.max[a] = header.max[a];
  }
  m.checksum = HexDigest(Fnv1a64File(las));
  return m;
}

void WriteTileDoneMarker(const std::string& tiles_dir, const TileDoneMarker& m) {
  const int64_t now =
      std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::system_clock::now().time_since_epoch()).count();
  const nlohmann::json j = {{"id", m.id},
                            {"config_hash", m.config_hash},
                            {"points", m.points},
                            {"file_size", m.file_size},
                            {"checksum_fnv1a64", m.checksum},
                            {"min", m.min},
                            {"max", m.max},
                            {"views", m.views},
                            {"seconds", m.seconds},
                            {"peak_rss_mib", m.peak_rss_mib},
                            {"finished_unix_ns", m.finished_unix_ns ? m.finished_unix_ns : now}};
  WriteFileAtomically(TileDonePath(tiles_dir, m.id), j.dump(2) + "\n");
}

std::optional<TileDoneMarker> ReadTileDoneMarker(const std::string& tiles_dir, const std::string& id) {
  const auto j = ReadJsonFile(TileDonePath(tiles_dir, id));
  if (!j) return std::nullopt;
  try {
    TileDoneMarker m;
    m.id = j->at("id").get<std::string>();
    m.config_hash = j->at("config_hash").get<std::string>();
    m.points = j->at("points").get<uint64_t>();
    m.file_size = j->at("file_size").get<uint64_t>();
    m.checksum = j->at("checksum_fnv1a64").get<std::string>();
    m.min = j->at("min").get<std::array<double, 3>>();
    m.max = j->at("max").get<std::array<double, 3>>();
    m.views = j->at("views").get<uint64_t>();
    m.seconds = j->at("seconds").get<double>();
    m.peak_rss_mib = j->at("peak_rss_mib").get<double>();
    m.finished_unix_ns = j->at("finished_unix_ns").get<int64_t>();
    if (m.id != id) return std::nullopt;
    return m;
  } catch (const std::exception&) {
    return std::nullopt;
  }
}

TileCheck VerifyTileDone(const std::string& tiles_dir, const std::string& id, const std::string& config_hash,
                         bool full_checksum) {
  const auto fail = [](std::string reason) { return TileCheck{false, std::move(reason)}; };
  if (!fs::exists(TileDonePath(tiles_dir, id))) return fail("no done marker");
  const auto m = ReadTileDoneMarker(tiles_dir, id);
  if (!m) return fail("done marker unreadable");
  if (m->config_hash != config_hash) return fail("computed with another config");
  const std::string las = TileLasPath(tiles_dir, id);
  std::error_code ec;
  if (m->points == 0) {
    if (fs::exists(las, ec)) return fail("marker says empty but " + id + ".las exists");
    return {true, ""};
  }
  const auto size = fs::file_size(las, ec);
  if (ec) return fail(id + ".las missing");
  if (size != m->file_size) {
    return fail(id + ".las size " + std::to_string(size) + " != " + std::to_string(m->file_size));
  }
  try {
    const uint64_t count = LasReader(las).header().point_count;
    if (count != m->points)
      return fail(id + ".las count " + std::to_string(count) + " != " + std::to_string(m->points));
    if (full_checksum && HexDigest(Fnv1a64File(las)) != m->checksum) return fail(id + ".las checksum mismatch");
  } catch (const Error& e) {
    return fail(e.what());
  }
  return {true, ""};
}

void WriteTileFailedMarker(const std::string& tiles_dir, const std::string& id, const std::string& reason) {
  const nlohmann::json j = {{"id", id}, {"reason", reason}};
  WriteFileAtomically(TileFailedPath(tiles_dir, id), j.dump(2) + "\n");
}

std::optional<std::string> ReadTileFailedReason(const std::string& tiles_dir, const std::string& id) {
  const auto j = ReadJsonFile(TileFailedPath(tiles_dir, id));
  if (!j) return std::nullopt;
  return j->value("reason", std::string("(no reason recorded)"));
}

void ClearTileState(const std::string& tiles_dir, const std::string& id) {
  std::error_code ec;
  // The marker goes first: a kill between the removals leaves no marker pointing at a missing file.
  fs::remove(TileDonePath(tiles_dir, id), ec);
  fs::remove(TileFailedPath(tiles_dir, id), ec);
  fs::remove(TileLasPath(tiles_dir, id), ec);
}

size_t RemoveTemporaryFiles(const std::string& dir, bool recursive) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) return 0;
  std::vector<fs::path> temporary;
  const auto visit = [&](const fs::directory_entry& entry) {
    if (entry.is_regular_file(ec) && entry.path().filename().string().find(".tmp-") != std::string::npos) {
      temporary.push_back(entry.path());
    }
  };
  if (recursive) {
    for (const auto& entry : fs::recursive_directory_iterator(dir, ec)) visit(entry);
  } else {
    for (const auto& entry : fs::directory_iterator(dir, ec)) visit(entry);
  }
  size_t removed = 0;
  for (const auto& path : temporary) removed += fs::remove(path, ec) ? 1 : 0;
  return removed;
}

}  // namespace sacfuse
