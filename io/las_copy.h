#pragma once
// Point-for-point copy of a LAS or LAZ file into LAS (or LAZ): same point format, scale, offset and VLRs, so
// every stored coordinate integer is unchanged. For tools that read only uncompressed LAS (aerial-bench's numpy
// reader) given a LAZ-only source. LAS 1.0-1.2 sources are written as LAS 1.2, 1.3-1.4 as LAS 1.4 (the versions
// LasWriter writes); extra bytes per record are dropped (with their LASF_Spec/4 description), as are waveform
// formats, which LasWriter refuses. Streams in chunks; the output appears whole or not at all (LasWriter).
#include <cstdint>
#include <string>

namespace sacfuse {

// Returns the number of points copied. Throws InputError naming `in_path` when it cannot be read, Error when
// `out_path` cannot be written.
uint64_t CopyLasFile(const std::string& in_path, const std::string& out_path, bool compressed);

}  // namespace sacfuse
