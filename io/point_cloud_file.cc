#include "io/point_cloud_file.h"

#include <fstream>
#include <optional>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "core/error.h"
#include "io/las_reader.h"
#include "io/ply_reader.h"
#include "io/raster_crs.h"

namespace sacfuse {

struct PointCloudFile::Impl {
  std::string path;
  Eigen::Vector3d shift = Eigen::Vector3d::Zero();
  std::unique_ptr<LasReader> las;
  std::unique_ptr<PlyVertexReader> ply;
  std::optional<Box2d> bounds;
  std::vector<LasPoint> las_buffer;
  std::vector<PlyVertex> ply_buffer;
};

PointCloudFile::PointCloudFile(const std::string& path, const Eigen::Vector3d& shift)
    : impl_(std::make_unique<Impl>()) {
  impl_->path = path;
  impl_->shift = shift;
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, "cannot open the point cloud");
  char magic[4] = {0, 0, 0, 0};
  in.read(magic, 4);
  const std::string m(magic, 4);
  if (m == "LASF") {
    impl_->las = std::make_unique<LasReader>(path);
  } else if (m.rfind("ply", 0) == 0) {
    impl_->ply = std::make_unique<PlyVertexReader>(path);
  } else {
    throw InputError(path, "not a LAS, LAZ or PLY point cloud (no \"LASF\" or \"ply\" signature)");
  }
}

PointCloudFile::~PointCloudFile() = default;

const std::string& PointCloudFile::path() const { return impl_->path; }
bool PointCloudFile::is_las() const { return impl_->las != nullptr; }

uint64_t PointCloudFile::point_count() const {
  return impl_->las ? impl_->las->header().point_count : impl_->ply->vertex_count();
}

double PointCloudFile::quantum_m() const {
  return impl_->las ? impl_->las->header().scale.head<2>().maxCoeff() : 0.0;
}

std::string PointCloudFile::crs_wkt() const { return impl_->las ? RasterCrsWktOfLas(impl_->las->header()) : ""; }

Box2d PointCloudFile::bounds_xy() {
  if (impl_->bounds) return *impl_->bounds;
  Box2d b;
  if (impl_->las) {
    const LasHeader& h = impl_->las->header();
    if (h.point_count > 0) {
      b.Extend(Eigen::Vector2d(h.min.x(), h.min.y()) + impl_->shift.head<2>());
      b.Extend(Eigen::Vector2d(h.max.x(), h.max.y()) + impl_->shift.head<2>());
    }
  } else {
    Rewind();
    CloudChunk chunk;
    while (Read(&chunk, 1 << 16) > 0) {
      for (const Eigen::Vector3d& p : chunk.xyz) b.Extend(Eigen::Vector2d(p.x(), p.y()));
    }
    Rewind();
  }
  impl_->bounds = b;
  return b;
}

size_t PointCloudFile::Read(CloudChunk* chunk, size_t max_points) {
  if (impl_->las) {
    const size_t n = impl_->las->Read(&impl_->las_buffer, max_points);
    chunk->xyz.resize(n);
    chunk->classification.resize(n);
    chunk->source_id.resize(n);
    chunk->rgb.resize(n);
    // On the job's threads, as the records were decoded (one thread copying them would be a serial share).
    tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 4096), [&](const tbb::blocked_range<size_t>& range) {
      for (size_t i = range.begin(); i < range.end(); ++i) {
        const LasPoint& p = impl_->las_buffer[i];
        chunk->xyz[i] = p.xyz + impl_->shift;
        chunk->classification[i] = p.classification;
        chunk->source_id[i] = p.point_source_id;
        chunk->rgb[i] = {static_cast<uint8_t>(p.rgb[0] >> 8), static_cast<uint8_t>(p.rgb[1] >> 8),
                         static_cast<uint8_t>(p.rgb[2] >> 8)};
      }
    });
    return n;
  }
  const size_t n = impl_->ply->Read(&impl_->ply_buffer, max_points);
  chunk->xyz.resize(n);
  chunk->classification.assign(n, 0);
  chunk->source_id.assign(n, 0);
  chunk->rgb.resize(n);
  for (size_t i = 0; i < n; ++i) {
    chunk->xyz[i] = impl_->ply_buffer[i].xyz + impl_->shift;
    chunk->rgb[i] = impl_->ply_buffer[i].rgb;
  }
  return n;
}

void PointCloudFile::Rewind() {
  if (impl_->las) {
    impl_->las->Rewind();
  } else {
    impl_->ply = std::make_unique<PlyVertexReader>(impl_->path);
  }
}

}  // namespace sacfuse
