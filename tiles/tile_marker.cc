#include "tiles/tile_marker.h"

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "io/atomic_file.h"
#include "io/file_checksum.h"
#include "io/las_reader.h"
#include "io/json_text.h"

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

nlohmann::json BoxJson(const std::array<double, 4>& b) { return {b[0], b[1], b[2], b[3]}; }

std::array<double, 4> BoxOf(const Box2d& b) { return {b.min.x(), b.min.y(), b.max.x(), b.max.y()}; }

nlohmann::json InputsJson(const TileInputs& inputs) {
  nlohmann::json views = nlohmann::json::array();
  for (const TileInputView& v : inputs.views) {
    const PixelWindow& w = v.window;
    views.push_back({{"view", v.view},
                     {"name", v.name},
                     {"window", {w.row_begin, w.row_end, w.col_begin, w.col_end}},
                     {"identity", nlohmann::json::parse(ViewIdentityJson(v.identity))}});
  }
  return {{"core", BoxJson(inputs.core)}, {"halo", BoxJson(inputs.halo)}, {"views", views}};
}

TileInputs InputsFromJson(const nlohmann::json& j) {
  TileInputs inputs;
  inputs.core = j.at("core").get<std::array<double, 4>>();
  inputs.halo = j.at("halo").get<std::array<double, 4>>();
  for (const auto& v : j.at("views")) {
    TileInputView view;
    view.view = v.at("view").get<uint32_t>();
    view.name = v.at("name").get<std::string>();
    const auto w = v.at("window").get<std::array<int, 4>>();
    view.window = PixelWindow{w[0], w[1], w[2], w[3]};
    const auto identity = ParseViewIdentityJson(v.at("identity").dump());
    if (!identity) throw Error("unreadable view identity");
    view.identity = *identity;
    inputs.views.push_back(view);
  }
  return inputs;
}

bool SameWindow(const PixelWindow& a, const PixelWindow& b) {
  return a.row_begin == b.row_begin && a.row_end == b.row_end && a.col_begin == b.col_begin &&
         a.col_end == b.col_end;
}

// How the recorded inputs differ from the current ones (empty: they agree).
std::vector<std::string> InputChanges(const TileInputs& recorded, const TileInputs& now) {
  std::vector<std::string> changes;
  if (recorded.core != now.core || recorded.halo != now.halo) changes.push_back("its core or halo moved (re-planned)");
  const auto label = [](const TileInputView& v) { return "view " + std::to_string(v.view) + " (" + v.name + ")"; };
  for (const TileInputView& v : now.views) {
    const auto it = std::find_if(recorded.views.begin(), recorded.views.end(),
                                 [&](const TileInputView& r) { return r.view == v.view; });
    if (it == recorded.views.end()) {
      changes.push_back(label(v) + ": now read by the tile (re-planned)");
      continue;
    }
    const std::string change = DescribeViewChange(it->identity, v.identity);
    if (!change.empty()) changes.push_back(label(v) + ": " + change);
    if (!SameWindow(it->window, v.window) || it->name != v.name) {
      changes.push_back(label(v) + ": its window changed (re-planned)");
    }
  }
  for (const TileInputView& r : recorded.views) {
    const bool still = std::any_of(now.views.begin(), now.views.end(),
                                   [&](const TileInputView& v) { return v.view == r.view; });
    if (!still) changes.push_back(label(r) + ": no longer read by the tile (re-planned)");
  }
  return changes;
}

}  // namespace

TileInputs TileInputsOf(const PlannedTile& tile, const std::vector<View>& views,
                        const std::vector<ViewIdentity>& identities) {
  TileInputs inputs;
  inputs.core = BoxOf(tile.core);
  inputs.halo = BoxOf(tile.halo);
  for (const TileViewWindow& tw : tile.views) {
    // The name as the marker carries it (io/json_text.h), so a name with bytes that are not UTF-8 compares equal.
    inputs.views.push_back({tw.view, ValidUtf8(views.at(tw.view).name), tw.window, identities.at(tw.view)});
  }
  return inputs;
}

std::string TileCloudFileName(const std::string& id, bool copc) { return id + (copc ? ".copc.laz" : ".laz"); }
std::string TileCloudPath(const std::string& tiles_dir, const TileDoneMarker& marker) {
  return Path(tiles_dir, marker.file.empty() ? TileCloudFileName(marker.id, false) : marker.file);
}
std::string TileDonePath(const std::string& tiles_dir, const std::string& id) {
  return Path(tiles_dir, id + ".done.json");
}
std::string TileFailedPath(const std::string& tiles_dir, const std::string& id) {
  return Path(tiles_dir, id + ".failed.json");
}
std::string TileProductPath(const std::string& tiles_dir, const std::string& id, const std::string& suffix) {
  return Path(tiles_dir, id + "." + suffix);
}

TileProductFile DescribeTileProduct(const std::string& tiles_dir, const std::string& id, const std::string& suffix) {
  const std::string path = TileProductPath(tiles_dir, id, suffix);
  return {suffix, fs::file_size(path), HexDigest(Fnv1a64File(path))};
}

TileDoneMarker DescribeTileFile(const std::string& tiles_dir, const std::string& id, const std::string& file) {
  TileDoneMarker m;
  m.id = id;
  if (file.empty()) return m;
  m.file = file;
  const std::string las = Path(tiles_dir, file);
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
  nlohmann::json j = {{"id", m.id},
                            {"config_hash", m.config_hash},
                            {"points", m.points},
                            {"file", m.file},
                            {"file_size", m.file_size},
                            {"checksum_fnv1a64", m.checksum},
                            {"min", m.min},
                            {"max", m.max},
                            {"views", m.views},
                            {"points_per_view", m.points_per_view},
                            {"seconds", m.seconds},
                            {"peak_rss_mib", m.peak_rss_mib},
                            {"finished_unix_ns", m.finished_unix_ns ? m.finished_unix_ns : now}};
  if (m.inputs) j["inputs"] = InputsJson(*m.inputs);
  if (!m.products.empty()) {
    nlohmann::json products = nlohmann::json::array();
    for (const TileProductFile& p : m.products) {
      products.push_back({{"suffix", p.suffix}, {"file_size", p.file_size}, {"checksum_fnv1a64", p.checksum}});
    }
    j["products"] = products;
  }
  WriteFileAtomically(TileDonePath(tiles_dir, m.id), JsonText(j, 2) + "\n");
}

std::optional<TileDoneMarker> ReadTileDoneMarker(const std::string& tiles_dir, const std::string& id) {
  const auto j = ReadJsonFile(TileDonePath(tiles_dir, id));
  if (!j) return std::nullopt;
  try {
    TileDoneMarker m;
    m.id = j->at("id").get<std::string>();
    m.config_hash = j->at("config_hash").get<std::string>();
    m.points = j->at("points").get<uint64_t>();
    m.file = j->value("file", std::string());
    m.file_size = j->at("file_size").get<uint64_t>();
    m.checksum = j->at("checksum_fnv1a64").get<std::string>();
    m.min = j->at("min").get<std::array<double, 3>>();
    m.max = j->at("max").get<std::array<double, 3>>();
    m.views = j->at("views").get<uint64_t>();
    m.seconds = j->at("seconds").get<double>();
    m.peak_rss_mib = j->at("peak_rss_mib").get<double>();
    m.finished_unix_ns = j->at("finished_unix_ns").get<int64_t>();
    if (j->contains("inputs")) m.inputs = InputsFromJson(j->at("inputs"));
    for (const auto& p : j->value("products", nlohmann::json::array())) {
      m.products.push_back({p.at("suffix").get<std::string>(), p.at("file_size").get<uint64_t>(),
                            p.at("checksum_fnv1a64").get<std::string>()});
    }
    if (j->contains("points_per_view")) {
      m.points_per_view = j->at("points_per_view").get<std::vector<std::pair<uint32_t, uint64_t>>>();
    }
    if (m.id != id) return std::nullopt;
    return m;
  } catch (const std::exception&) {
    return std::nullopt;
  }
}

TileCheck VerifyTileDone(const std::string& tiles_dir, const std::string& id, const std::string& config_hash,
                         bool full_checksum, const TileInputs* inputs) {
  const auto fail = [](std::string reason) { return TileCheck{false, std::move(reason), {}}; };
  if (!fs::exists(TileDonePath(tiles_dir, id))) return fail("no done marker");
  const auto m = ReadTileDoneMarker(tiles_dir, id);
  if (!m) return fail("done marker unreadable");
  if (m->config_hash != config_hash) return fail("computed with another config");
  if (inputs != nullptr) {
    if (!m->inputs) return fail("its done marker records no inputs (written by an older sacfuse)");
    std::vector<std::string> changes = InputChanges(*m->inputs, *inputs);
    if (!changes.empty()) {
      std::string reason = "inputs changed: ";
      for (size_t i = 0; i < changes.size(); ++i) reason += (i ? "; " : "") + changes[i];
      return TileCheck{false, reason, std::move(changes)};
    }
  }
  uint64_t per_view_sum = 0;
  for (const auto& [view, n] : m->points_per_view) per_view_sum += n;
  if (per_view_sum != m->points) {
    return fail("its done marker's points per view add up to " + std::to_string(per_view_sum) + ", not " +
                std::to_string(m->points) + (m->points_per_view.empty() ? " (written by an older sacfuse)" : ""));
  }
  std::error_code ec;
  for (const TileProductFile& p : m->products) {
    const std::string path = TileProductPath(tiles_dir, id, p.suffix);
    const std::string file = fs::path(path).filename().string();
    const auto size = fs::file_size(path, ec);
    if (ec) return fail(file + " missing");
    if (size != p.file_size) return fail(file + " size " + std::to_string(size) + " != " + std::to_string(p.file_size));
    try {
      if (full_checksum && HexDigest(Fnv1a64File(path)) != p.checksum) return fail(file + " checksum mismatch");
    } catch (const Error& e) {
      return fail(e.what());
    }
  }
  const std::string las = TileCloudPath(tiles_dir, *m);
  const std::string name = fs::path(las).filename().string();
  if (m->points == 0) {
    if (fs::exists(las, ec)) return fail("marker says empty but " + name + " exists");
    return {true, "", {}};
  }
  const auto size = fs::file_size(las, ec);
  if (ec) return fail(name + " missing");
  if (size != m->file_size) {
    return fail(name + " size " + std::to_string(size) + " != " + std::to_string(m->file_size));
  }
  try {
    const uint64_t count = LasReader(las).header().point_count;
    if (count != m->points)
      return fail(name + " count " + std::to_string(count) + " != " + std::to_string(m->points));
    if (full_checksum && HexDigest(Fnv1a64File(las)) != m->checksum) return fail(name + " checksum mismatch");
  } catch (const Error& e) {
    return fail(e.what());
  }
  return {true, "", {}};
}

void WriteTileFailedMarker(const std::string& tiles_dir, const std::string& id, const std::string& reason) {
  const nlohmann::json j = {{"id", id}, {"reason", reason}};
  WriteFileAtomically(TileFailedPath(tiles_dir, id), JsonText(j, 2) + "\n");
}

std::optional<std::string> ReadTileFailedReason(const std::string& tiles_dir, const std::string& id) {
  const auto j = ReadJsonFile(TileFailedPath(tiles_dir, id));
  if (!j) return std::nullopt;
  return j->value("reason", std::string("(no reason recorded)"));
}

void ClearTileState(const std::string& tiles_dir, const std::string& id,
                    const std::vector<std::string>& product_suffixes) {
  std::error_code ec;
  // The marker goes first: a kill between the removals leaves no marker pointing at a missing file.
  fs::remove(TileDonePath(tiles_dir, id), ec);
  fs::remove(TileFailedPath(tiles_dir, id), ec);
  fs::remove(Path(tiles_dir, TileCloudFileName(id, false)), ec);
  fs::remove(Path(tiles_dir, TileCloudFileName(id, true)), ec);
  for (const std::string& suffix : product_suffixes) fs::remove(TileProductPath(tiles_dir, id, suffix), ec);
  fs::remove(Path(tiles_dir, id + ".las"), ec);  // written by versions before the tiles were LAZ
}

}  // namespace sacfuse
