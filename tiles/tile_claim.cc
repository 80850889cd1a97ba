#include "tiles/tile_claim.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "io/atomic_file.h"

namespace sacfuse {
namespace fs = std::filesystem;
namespace {

constexpr const char* kClaimSuffix = ".claim";
constexpr int kTakeOverAttempts = 3;

std::atomic<uint64_t> g_counter{0};

int64_t NowUnixS() {
  return std::chrono::duration_cast<std::chrono::seconds>(std::chrono::system_clock::now().time_since_epoch())
      .count();
}

std::optional<TileClaimInfo> ParseClaim(const std::string& text) {
  try {
    const nlohmann::json j = nlohmann::json::parse(text);
    TileClaimInfo c;
    c.host = j.at("host").get<std::string>();
    c.pid = j.at("pid").get<int64_t>();
    c.start_unix_s = j.at("start_unix_s").get<int64_t>();
    c.token = j.at("token").get<std::string>();
    return c;
  } catch (const std::exception&) {
    return std::nullopt;
  }
}

// Seconds since the file was last modified (0 when it cannot be stat'ed).
double FileAgeS(const std::string& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) return 0.0;
  return static_cast<double>(NowUnixS() - st.st_mtime);
}

// An unreadable claim (a file that is not claim JSON) counts as live for at most this long after its last
// modification. Claims appear fully written (CreateExclusive), so one that cannot be parsed is left by a file
// system without hard links (the fallback below, killed between create and write) or is damaged: either way no
// worker is writing it after a minute, and waiting tiling.claim_timeout_s (6 h) for it would stall a resumed run.
constexpr double kUnreadableClaimGraceS = 60.0;

// Live claim content at `path` (parsed or not)? Missing file: false.
bool ContentIsLive(const std::string& path, const std::string& text, double timeout_s) {
  if (const auto c = ParseClaim(text)) return !ClaimIsStale(*c, timeout_s);
  return FileAgeS(path) <= std::min(timeout_s, kUnreadableClaimGraceS);
}

// Writes `contents` to a new file at `path` (fsynced) with O_CREAT|O_EXCL; false when it exists.
bool CreateAndWriteExclusive(const std::string& path, const std::string& contents) {
  const int fd = ::open(path.c_str(), O_CREAT | O_EXCL | O_WRONLY | O_CLOEXEC, 0644);
  if (fd < 0) {
    if (errno == EEXIST) return false;
    throw Error(path + ": cannot create claim: " + std::strerror(errno));
  }
  const bool ok = ::write(fd, contents.data(), contents.size()) == static_cast<ssize_t>(contents.size()) &&
                  ::fsync(fd) == 0;
  ::close(fd);
  if (!ok) {
    ::unlink(path.c_str());
    throw Error(path + ": cannot write claim");
  }
  return true;
}

// Creates the claim file exclusively and whole; false when it exists. The contents go to a temporary sibling
// (io/atomic_file.h names it, so a killed worker's leftover is removed like any other) that is hard-linked onto
// the claim path: link() fails with EEXIST atomically, also on NFS, so a claim is never seen empty or half
// written. A worker killed between the create and the write of an O_EXCL claim left an empty claim that held
// its tile for claim_timeout_s (a resumed run waited on it). File systems without hard links fall back to
// O_EXCL and write.
bool CreateExclusive(const std::string& path, const std::string& contents) {
  int link_errno = ENOENT;
  // ENOENT: a worker starting in the same folder saw no live claim and removed our temporary file; try again.
  for (int i = 0; i < kTakeOverAttempts && link_errno == ENOENT; ++i) {
    const std::string temp = TemporaryPathFor(path);
    if (!CreateAndWriteExclusive(temp, contents)) throw Error(temp + ": temporary claim exists");
    link_errno = ::link(temp.c_str(), path.c_str()) == 0 ? 0 : errno;
    // NFS may report an error for a link it made (a retransmitted request): the temporary file's link count
    // says whether the claim is ours (open(2)'s note on O_EXCL over NFS).
    struct stat st {};
    if (link_errno != 0 && ::stat(temp.c_str(), &st) == 0 && st.st_nlink == 2) link_errno = 0;
    ::unlink(temp.c_str());
  }
  if (link_errno == 0) return true;
  if (link_errno == EEXIST) return false;
  if (link_errno == EPERM || link_errno == EOPNOTSUPP || link_errno == ENOSYS) {
    return CreateAndWriteExclusive(path, contents);
  }
  throw Error(path + ": cannot create claim: " + std::strerror(link_errno));
}

}  // namespace

std::string TileClaimPath(const std::string& tiles_dir, const std::string& id) {
  return (fs::path(tiles_dir) / (id + kClaimSuffix)).string();
}

std::optional<TileClaimInfo> ReadTileClaim(const std::string& tiles_dir, const std::string& id) {
  const std::string path = TileClaimPath(tiles_dir, id);
  if (!fs::exists(path)) return std::nullopt;
  return ParseClaim(ReadSmallFile(path));
}

bool ClaimIsStale(const TileClaimInfo& claim, double timeout_s) {
  if (static_cast<double>(NowUnixS() - claim.start_unix_s) > timeout_s) return true;
  return ProcessIsGone(claim.host, claim.pid);
}

std::string DescribeClaim(const TileClaimInfo& claim) {
  return claim.host + " pid " + std::to_string(claim.pid) + " since " + UtcText(claim.start_unix_s * 1000000000);
}

bool TileClaimIsLive(const std::string& tiles_dir, const std::string& id, double timeout_s) {
  const std::string path = TileClaimPath(tiles_dir, id);
  if (!fs::exists(path)) return false;
  return ContentIsLive(path, ReadSmallFile(path), timeout_s);
}

bool AnyLiveTileClaim(const std::string& tiles_dir, double timeout_s) {
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(tiles_dir, ec)) {
    const std::string name = e.path().filename().string();
    if (name.size() <= std::strlen(kClaimSuffix) ||
        name.compare(name.size() - std::strlen(kClaimSuffix), std::string::npos, kClaimSuffix) != 0)
      continue;
    if (ContentIsLive(e.path().string(), ReadSmallFile(e.path().string()), timeout_s)) return true;
  }
  return false;
}

ClaimAttempt TryClaimTile(const std::string& tiles_dir, const std::string& id, double timeout_s) {
  const std::string path = TileClaimPath(tiles_dir, id);
  TileClaimInfo me;
  me.host = ThisHostName();
  me.pid = ::getpid();
  me.start_unix_s = NowUnixS();
  me.token = me.host + "-" + std::to_string(me.pid) + "-" +
             std::to_string(std::chrono::steady_clock::now().time_since_epoch().count()) + "-" +
             std::to_string(g_counter++);
  const std::string contents = nlohmann::json{{"host", me.host},
                                              {"pid", me.pid},
                                              {"start_unix_s", me.start_unix_s},
                                              {"token", me.token}}.dump() + "\n";
  ClaimAttempt attempt;
  for (int i = 0; i < kTakeOverAttempts; ++i) {
    if (CreateExclusive(path, contents)) {
      attempt.claimed = true;
      attempt.token = me.token;
      return attempt;
    }
    const std::string seen = ReadSmallFile(path);
    if (ContentIsLive(path, seen, timeout_s)) {
      const auto holder = ParseClaim(seen);
      attempt.holder = holder ? DescribeClaim(*holder) : "another worker (claim being written)";
      return attempt;
    }
    // Stale: move it out of the way under a unique name, then check that what moved is what was judged stale.
    const std::string moved = path + ".stale-" + me.host + "-" + std::to_string(me.pid) + "-" +
                              std::to_string(g_counter++);
    if (::rename(path.c_str(), moved.c_str()) != 0) {
      if (errno == ENOENT) continue;  // another worker moved or released it first
      throw Error(path + ": cannot move stale claim: " + std::strerror(errno));
    }
    if (ReadSmallFile(moved) != seen) {
      if (::link(moved.c_str(), path.c_str()) != 0 && errno != EEXIST) {
        ::unlink(moved.c_str());
        throw Error(path + ": cannot restore a claim moved by mistake: " + std::strerror(errno));
      }
      ::unlink(moved.c_str());
      continue;  // the restored claim is live: the next round reports its holder
    }
    ::unlink(moved.c_str());
    attempt.took_over = true;
  }
  const auto holder = ReadTileClaim(tiles_dir, id);
  attempt.holder = holder ? DescribeClaim(*holder) : "another worker";
  return attempt;
}

size_t RemoveStaleTileClaims(const std::string& tiles_dir, double timeout_s) {
  std::vector<std::string> stale;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(tiles_dir, ec)) {
    const std::string name = e.path().filename().string();
    const size_t n = std::strlen(kClaimSuffix);
    if (name.size() <= n || name.compare(name.size() - n, n, kClaimSuffix) != 0) continue;
    if (!ContentIsLive(e.path().string(), ReadSmallFile(e.path().string()), timeout_s))
      stale.push_back(name.substr(0, name.size() - n));
  }
  size_t removed = 0;
  for (const std::string& id : stale) {
    const ClaimAttempt a = TryClaimTile(tiles_dir, id, timeout_s);
    if (!a.claimed) continue;
    ReleaseTileClaim(tiles_dir, id, a.token);
    removed += a.took_over ? 1 : 0;
  }
  return removed;
}

void ReleaseTileClaim(const std::string& tiles_dir, const std::string& id, const std::string& token) {
  const auto claim = ReadTileClaim(tiles_dir, id);
  if (claim && claim->token == token) ::unlink(TileClaimPath(tiles_dir, id).c_str());
}

}  // namespace sacfuse
