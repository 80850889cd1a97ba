#include "io/proj_handles.h"

#include <mutex>

#include "core/error.h"
#include "io/crs.h"

namespace sacfuse {
namespace {

std::mutex& ExtraPathsMutex() {
  static std::mutex m;
  return m;
}

std::vector<std::string>& ExtraPaths() {
  static std::vector<std::string> paths;
  return paths;
}

// PROJ's own search path (PROJ_DATA or its build-time default, plus the user's data folder), ':'-separated.
std::vector<std::string> DefaultSearchPaths() {
  std::vector<std::string> out;
  const std::string all = proj_info().searchpath != nullptr ? proj_info().searchpath : "";
  size_t start = 0;
  while (start <= all.size()) {
    const size_t end = all.find(':', start);
    const std::string part = all.substr(start, end == std::string::npos ? std::string::npos : end - start);
    if (!part.empty()) out.push_back(part);
    if (end == std::string::npos) break;
    start = end + 1;
  }
  return out;
}

}  // namespace

void SetExtraProjSearchPaths(const std::vector<std::string>& dirs) {
  std::lock_guard<std::mutex> lock(ExtraPathsMutex());
  ExtraPaths() = dirs;
}

ProjContext::ProjContext() {
  ctx_ = proj_context_create();
  if (ctx_ == nullptr) throw Error("PROJ: cannot create a context");
  proj_log_func(ctx_, this, &ProjContext::Log);
  proj_log_level(ctx_, PJ_LOG_ERROR);
  proj_context_set_enable_network(ctx_, 0);
  {
    std::lock_guard<std::mutex> lock(ExtraPathsMutex());  // also serialises proj_info(), a process-wide static
    paths_ = ExtraPaths();
    for (std::string& p : DefaultSearchPaths()) paths_.push_back(std::move(p));
  }
  std::vector<const char*> c_paths;
  for (const std::string& p : paths_) c_paths.push_back(p.c_str());
  proj_context_set_search_paths(ctx_, static_cast<int>(c_paths.size()), c_paths.data());
}

ProjContext::~ProjContext() { proj_context_destroy(ctx_); }

void ProjContext::Log(void* self, int /*level*/, const char* message) {
  ProjContext* c = static_cast<ProjContext*>(self);
  if (message == nullptr || *message == '\0') return;
  if (!c->messages_.empty()) c->messages_ += "; ";
  c->messages_ += message;
}

std::string ProjContext::TakeMessages() {
  std::string out;
  out.swap(messages_);
  return out;
}

std::string JoinedSearchPaths(const ProjContext& ctx) {
  std::string out;
  for (const std::string& p : ctx.search_paths()) out += (out.empty() ? "" : ", ") + p;
  return out;
}

}  // namespace sacfuse
