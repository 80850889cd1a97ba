#pragma once
// FNV-1a 64-bit checksums of strings and of whole files (streamed in chunks), for done markers and config
// fingerprints. Not cryptographic: it detects truncation, corruption and accidental edits.
#include <cstdint>
#include <string>

namespace sacfuse {

uint64_t Fnv1a64(const std::string& bytes);
// Checksum of every byte of a file, read in 1 MiB chunks. Throws InputError when it cannot be read.
uint64_t Fnv1a64File(const std::string& path);
// 16 lowercase hex digits.
std::string HexDigest(uint64_t value);

}  // namespace sacfuse
