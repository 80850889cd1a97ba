#include "io/las_copy.h"

#include <vector>

#include "io/las_reader.h"
#include "io/las_writer.h"

namespace sacfuse {

uint64_t CopyLasFile(const std::string& in_path, const std::string& out_path, bool compressed) {
  LasReader reader(in_path);
  const LasHeader& header = reader.header();
  LasWriterOptions options;
  options.version_minor = header.version_minor >= 3 ? 4 : 2;
  options.point_format = header.point_format;
  options.scale_xyz = header.scale;
  options.offset = header.offset;
  options.compressed = compressed;
  options.system_identifier = header.system_identifier;
  options.generating_software = header.generating_software;
  // GPS time type (bit 0), and the WKT bit (4) where LAS 1.4 allows it.
  options.global_encoding_extra_bits =
      static_cast<uint16_t>(header.global_encoding & (options.version_minor == 4 ? 0x11 : 0x1));
  for (const LasVlr& vlr : header.vlrs) {
    if (vlr.user_id == "LASF_Spec" && vlr.record_id == 4) continue;  // extra bytes are not written back
    if (vlr.extended && options.version_minor < 4) continue;
    options.vlrs.push_back(vlr);
  }
  LasWriter writer(out_path, options);
  std::vector<LasPoint> chunk;
  uint64_t copied = 0;
  while (const size_t n = reader.Read(&chunk, 65536)) {
    writer.WritePoints(chunk.data(), n);
    copied += n;
  }
  writer.Close();
  return copied;
}

}  // namespace sacfuse
