#pragma once
// Never leave a partial output where a complete one is expected: write to a temporary name in the same folder,
// fsync, rename over the final path, fsync the folder.
#include <cstdio>
#include <string>
#include <vector>

namespace sacfuse {

// Temporary sibling name for `path` (unique per process and call): "<path>.tmp-<pid>-<n>".
std::string TemporaryPathFor(const std::string& path);
// Whether a file name has the form TemporaryPathFor gives.
bool IsTemporaryFileName(const std::string& file_name);
// Deletes the files in `dir` (and its sub-folders when `recursive`) named as TemporaryPathFor names them, left by
// a killed process (callers make sure no live process of the job writes there), and folders so named with
// everything in them (work folders, io/copc_writer.h); returns their paths.
std::vector<std::string> RemoveTemporaryFiles(const std::string& dir, bool recursive = false);
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

}  // namespace sacfuse
