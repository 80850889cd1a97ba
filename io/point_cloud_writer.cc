#include "io/point_cloud_writer.h"

namespace sacfuse {
namespace {

class LasFile final : public PointCloudWriter {
 public:
  LasFile(const std::string& path, const LasWriterOptions& options) : writer_(path, options) {}
  void Write(const FusedPoint* points, size_t count) override { writer_.Write(points, count); }
  void WritePoints(const LasPoint* points, size_t count) override { writer_.WritePoints(points, count); }
  bool AppendLaz(LasReader& reader) override { return writer_.AppendLaz(reader); }
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
  bool AppendLaz(LasReader&) override { return false; }  // COPC chunks are octree nodes: points are rebuilt
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
