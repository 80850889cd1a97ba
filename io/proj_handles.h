#pragma once
// Owning handles around PROJ's C API, for the CRS code in io/crs*.cc only (nothing else includes proj.h).
// A ProjContext never writes to stderr (PROJ's messages are collected and end up in our errors), never uses the
// network (grids are never downloaded at run time) and searches the folders of SetExtraProjSearchPaths before
// PROJ's own search path (PROJ_DATA, ~/.local/share/proj, the proj-data package's /usr/share/proj).
// A context and the objects made in it are used by one thread at a time (callers serialise with a mutex).
#include <memory>
#include <string>
#include <vector>

#include <proj.h>

namespace sacfuse {

struct PjDeleter {
  void operator()(PJ* p) const { proj_destroy(p); }
};
using PjPtr = std::unique_ptr<PJ, PjDeleter>;

class ProjContext {
 public:
  ProjContext();
  ~ProjContext();
  ProjContext(const ProjContext&) = delete;
  ProjContext& operator=(const ProjContext&) = delete;

  PJ_CONTEXT* get() const { return ctx_; }
  // PROJ's messages since the last call, joined by "; " ("" when none), and forgets them.
  std::string TakeMessages();
  // The folders this context searches for grids and its database, in order.
  const std::vector<std::string>& search_paths() const { return paths_; }

 private:
  static void Log(void* self, int level, const char* message);
  PJ_CONTEXT* ctx_ = nullptr;
  std::vector<std::string> paths_;
  std::string messages_;
};

// The folders of ProjContext::search_paths(), ", "-joined, for messages.
std::string JoinedSearchPaths(const ProjContext& ctx);

}  // namespace sacfuse
