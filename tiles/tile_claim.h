#pragma once
// Atomic per-tile claims, so that several processes or machines sharing DIR can work through one tile list
// without computing a tile twice. A claim is the file DIR/tiles/<id>.claim, holding JSON {host, pid,
// start_unix_s, token}. It appears whole: written to a temporary sibling, then hard-linked into place (link()
// fails with EEXIST atomically, on local file systems and NFS; O_CREAT|O_EXCL and write where links are refused).
//   live   the file exists and is not stale (an unreadable claim counts as live for one minute after its last
//          modification, then as stale);
//   stale  its pid no longer exists on this host (kill(pid, 0) fails with ESRCH; pids of other hosts cannot be
//          checked), or it is older than tiling.claim_timeout_s (default 6 h).
// A stale claim is taken over: renamed to a unique "<id>.claim.stale-<host>-<pid>-<n>" (atomic), removed, and
// the claim created again; if the renamed file turns out to be a fresh claim another worker created
// in the meantime, it is linked back in place. A claim is released by its owner only (matched by token).
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>

#include "io/process_identity.h"  // ThisHostName, ProcessIsGone

namespace sacfuse {

struct TileClaimInfo {
  std::string host;
  int64_t pid = 0;
  int64_t start_unix_s = 0;
  std::string token;  // unique per claim: host, pid, time, counter
};

struct ClaimAttempt {
  bool claimed = false;
  bool took_over = false;  // a stale claim was removed first
  std::string holder;      // when not claimed: who holds it ("host pid 123 since 2026-01-01 12:00:00 UTC")
  std::string token;       // when claimed: pass to ReleaseTileClaim
};

std::string TileClaimPath(const std::string& tiles_dir, const std::string& id);

// The claim of a tile, nullopt when there is none or it cannot be parsed.
std::optional<TileClaimInfo> ReadTileClaim(const std::string& tiles_dir, const std::string& id);
bool ClaimIsStale(const TileClaimInfo& claim, double timeout_s);
std::string DescribeClaim(const TileClaimInfo& claim);
// True when the tile has a live claim (see above).
bool TileClaimIsLive(const std::string& tiles_dir, const std::string& id, double timeout_s);
// True when any tile in `tiles_dir` has a live claim.
bool AnyLiveTileClaim(const std::string& tiles_dir, double timeout_s);

// Removes every stale claim in `tiles_dir` (left by killed workers, e.g. after their tile was done) through
// TryClaimTile + ReleaseTileClaim, so a live claim is never removed; returns how many.
size_t RemoveStaleTileClaims(const std::string& tiles_dir, double timeout_s);

// Claims a tile for this process (taking over a stale claim). Throws Error on I/O errors other than EEXIST.
ClaimAttempt TryClaimTile(const std::string& tiles_dir, const std::string& id, double timeout_s);
// Removes the claim if it still holds `token` (never another worker's claim).
void ReleaseTileClaim(const std::string& tiles_dir, const std::string& id, const std::string& token);

// Holds a claim until destroyed.
class TileClaimGuard {
 public:
  TileClaimGuard(std::string tiles_dir, std::string id, std::string token)
      : tiles_dir_(std::move(tiles_dir)), id_(std::move(id)), token_(std::move(token)) {}
  ~TileClaimGuard() { ReleaseTileClaim(tiles_dir_, id_, token_); }
  TileClaimGuard(const TileClaimGuard&) = delete;
  TileClaimGuard& operator=(const TileClaimGuard&) = delete;

 private:
  std::string tiles_dir_, id_, token_;
};

}  // namespace sacfuse
