#pragma once
// The one gate every reader of a user file passes before reading it (depth maps, dense arrays, images, COLMAP
// models, camera files, LAS, configs): the path must name a regular file the process may read. A FIFO, a
// directory, a device or a socket in place of a file is refused with a message instead of a read that hangs
// forever (a FIFO blocks until someone writes) or fails later as "corrupt"; an OS error keeps its strerror text
// (e.g. "Permission denied"), so nobody is told a file is corrupt or missing when it is unreadable.
#include <fstream>
#include <string>

namespace sacfuse {

// Throws InputError naming `path` unless it is a regular file (symbolic links followed) that can be opened for
// reading; `what` names the kind of file in the message ("depth map", "image file", ...):
//   missing:          "missing <what>: it does not exist (cannot open it)"
//   not a file:       "cannot read <what>: it is a FIFO (named pipe), not a regular file"  (or a directory, ...)
//   other OS errors:  "cannot open <what>: <strerror>"  (e.g. Permission denied)
// Never blocks (the file is stat'ed first and opened non-blocking).
void CheckInputFile(const std::string& path, const std::string& what);

// Throws the InputError of a failed OS call on an input file, as above: `err` is the errno value (ENOENT gives
// the "missing" message).
[[noreturn]] void ThrowInputOsError(const std::string& path, const std::string& what, int err);

// CheckInputFile, then the file opened as a binary stream (an open that still fails throws with its strerror).
std::ifstream OpenInputStream(const std::string& path, const std::string& what);

}  // namespace sacfuse
