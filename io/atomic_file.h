#pragma once
// Never leave a partial output where a complete one is expected: write to a temporary name in the same folder,
// fsync, rename over the final path, fsync the folder.
#include <cstdint>
#include <cstdio>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace sacfuse {

// Temporary sibling name for `path` (unique per process and call): "<path>.tmp-<host>-<pid>-<n>", naming its
// writer so that a cleanup can prove the writer gone (io/process_identity.h) before removing it. The host is
// gethostname() with characters other than letters, digits, '.', '-' and '_' replaced by '_'.
std::string TemporaryPathFor(const std::string& path);

// Who wrote a temporary file: host ("" for "<path>.tmp-<pid>-<n>", the names of versions before the host was
// recorded) and pid.
struct TemporaryFileOwner {
  std::string host;
  int64_t pid = 0;
};
// The owner named by a file name of the TemporaryPathFor form (either version); nullopt for other names.
std::optional<TemporaryFileOwner> TemporaryFileOwnerOf(const std::string& file_name);
// Whether a file name has the form TemporaryPathFor gives (either version).
bool IsTemporaryFileName(const std::string& file_name);
// Whether the writer of a temporary file is provably gone: it names this host and its pid is not alive here.
bool TemporaryFileOwnerIsGone(const TemporaryFileOwner& owner);
// Whether a temporary file names this host as its writer's.
bool TemporaryFileOwnerIsOnThisHost(const TemporaryFileOwner& owner);
// Deletes the files in `dir` (and its sub-folders when `recursive`) named as TemporaryPathFor names them, and
// folders so named with everything in them (work folders, io/copc_writer.h), whose owner `removable` accepts
// (default: provably gone, above; callers that know no other process of the job is alive pass a wider rule);
// returns their paths.
std::vector<std::string> RemoveTemporaryFiles(
    const std::string& dir, bool recursive = false,
    const std::function<bool(const TemporaryFileOwner&)>& removable = TemporaryFileOwnerIsGone);
// fsync a written file by path; throws Error on failure.
void FsyncPath(const std::string& path);
// Rename `temp_path` onto `final_path` after fsyncing it, then fsync the parent folder.
void CommitTemporaryFile(const std::string& temp_path, const std::string& final_path);
// Closes `file` (written to temp_path), and on success (write_ok and a clean close) commits it to final_path;
// otherwise removes the temporary file and throws Error ("write failed").
void CloseAndCommitTemporaryFile(FILE* file, bool write_ok, const std::string& temp_path,
                                 const std::string& final_path);
// Whole-file convenience: contents -> temp -> fsync -> rename. Creates parent folders.
void WriteFileAtomically(const std::string& path, const std::string& contents);
// The whole contents of a small state file (markers, claims, manifests, lock files); "" when it is missing or
// cannot be read (callers treat that as "no state").
std::string ReadSmallFile(const std::string& path);

}  // namespace sacfuse
