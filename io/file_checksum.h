#pragma once
// FNV-1a 64-bit checksums of strings and of whole files (streamed in chunks), for done markers and config
// fingerprints. Not cryptographic: it detects truncation, corruption and accidental edits.
#include <cstdint>
#include <string>

namespace sacfuse {

uint64_t Fnv1a64(const std::string& bytes);
// Checksum of every byte of a file, read in 1 MiB chunks. Throws InputError when it cannot be read.
uint64_t Fnv1a64File(const std::string& path);
// Cheap content fingerprint of a file of `size` bytes: FNV-1a 64 over the size (8 bytes, little-endian), the first
// `edge_bytes` and the last `edge_bytes` (the whole file when it is at most 2 x edge_bytes). Reads at most
// 2 x edge_bytes. Throws InputError when it cannot be read.
uint64_t Fnv1a64FileEdges(const std::string& path, uint64_t size, size_t edge_bytes);
// 16 lowercase hex digits.
std::string HexDigest(uint64_t value);

}  // namespace sacfuse
