#include "jobs/thread_limit.h"

#include <algorithm>

namespace sacfuse {

ThreadLimit::ThreadLimit(int threads)
    : control_(std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                     static_cast<size_t>(std::max(1, threads)))) {}

ThreadLimit::~ThreadLimit() = default;

}  // namespace sacfuse
