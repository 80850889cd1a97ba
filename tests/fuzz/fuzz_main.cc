// The libFuzzer entry point of one fuzz target; CMake compiles it once per target with SACFUSE_FUZZ_TARGET set
// to the target's name (tests/fuzz/fuzz_readers.h lists them).
#include <cstddef>
#include <cstdint>

#include "tests/fuzz/fuzz_readers.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  sacfuse::fuzz::RunTarget(SACFUSE_FUZZ_TARGET, data, size);
  return 0;
}
