#include "io/point_cloud_writer.h"

#include "core/error.h"
#include "io/las_reader.h"

namespace sacfuse {
namespace {

class LasFile final : public PointCloudWriter {
 public:
  LasFile(const std::string& path, const LasWriterOptions& options) : writer_(path, options) {}
  void Write(const FusedPoint* points, size_t count) override { writer_.Write(points, count); }
  void WritePoints(const LasPoint* points, size_t count) override { writer_.WritePoints(points, count); }
  std::optional<LazAppendPart> PrepareLazAppend(LasReader& reader) const override {
    return writer_.PrepareLazAppend(reader);
  }
  void AppendLaz(LasReader& reader, const LazAppendPart& part) override { writer_.AppendLaz(reader, part); }
  void Close() override { writer_.Close(); }
  uint64_t num_points() const override { return writer_.num_points(); }

 private:
  LasWriter writer_;
};

class CopcFile final : public PointCloudWriter {
 public:
  CopcFile(const std::string& path, const LasWriterOptions& las, const CopcOptions& copc) : writer_(path, las, copc) {}
  void Write(const FusedPoint* points, size_t count) override { writer_.Write(points, count); }
  void WritePoints(const LasPoint* points, size_t count) override { writer_.WritePoints(points, count); }
  // COPC chunks are octree nodes: the points are rebuilt.
  std::optional<LazAppendPart> PrepareLazAppend(LasReader&) const override { return std::nullopt; }
  void AppendLaz(LasReader& reader, const LazAppendPart&) override {
    throw Error(reader.path() + ": a COPC file is not appended as LAZ chunks");
  }
  void Close() override { writer_.Close(); }
  uint64_t num_points() const override { return writer_.num_points(); }

 private:
  CopcWriter writer_;
};

}  // namespace

std::unique_ptr<PointCloudWriter> OpenPointCloudWriter(const std::string& path, const CloudFileOptions& options) {
  if (options.copc) return std::make_unique<CopcFile>(path, options.las, *options.copc);
  return std::make_unique<LasFile>(path, options.las);
}

}  // namespace sacfuse
