#pragma once
// resources.threads for one job: caps TBB's parallelism (superpixels, SAC stages) for the lifetime of the object.
#include <memory>

#include <tbb/global_control.h>

namespace sacfuse {

class ThreadLimit {
 public:
  explicit ThreadLimit(int threads);  // >= 1
  ~ThreadLimit();
  ThreadLimit(const ThreadLimit&) = delete;
  ThreadLimit& operator=(const ThreadLimit&) = delete;

 private:
  std::unique_ptr<tbb::global_control> control_;
};

}  // namespace sacfuse
