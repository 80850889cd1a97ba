#pragma once
// A view's superpixel label raster in memory at 2 bytes per pixel (issue 13: as int32 the labels were a quarter of
// an untiled run's heap, as much as the depth maps). Labels are numbered block by block (core/superpixels.h), so
// the labels of a band of 64 rows span at most the clusters of one or two block rows: each pixel stores the u16
// offset of its label from the smallest label of its band. A raster where some band spans more than 65,535 labels
// (tiny regions on very wide views, or labels that are not block-numbered) keeps int32 labels. The same banding is
// the superpixel cache file's layout (io/superpixel_io.h), which writes and reads it as it is.
#include <cstddef>
#include <cstdint>
#include <vector>

namespace sacfuse {

class SuperpixelLabels {
 public:
  static constexpr int kBandRows = 64;            // rows per band
  static constexpr int64_t kMaxBandSpan = 65535;  // largest label - band base a u16 holds

  SuperpixelLabels() = default;
  // Row-major labels of a width x height raster. Throws Error when labels.size() != width * height. Negative
  // labels are kept (int32 storage), for the validators downstream to name.
  SuperpixelLabels(int width, int height, const std::vector<int32_t>& labels);

  int width() const { return width_; }
  int height() const { return height_; }
  size_t size() const { return static_cast<size_t>(width_) * static_cast<size_t>(height_); }
  bool empty() const { return size() == 0; }

  int32_t at(int row, int col) const {
    const size_t i = static_cast<size_t>(row) * static_cast<size_t>(width_) + static_cast<size_t>(col);
    if (!banded_) return wide_[i];
    return static_cast<int32_t>(band_base_[static_cast<size_t>(row / kBandRows)] + offsets_[i]);
  }
  // Row `row` into out[0, width).
  void CopyRow(int row, int32_t* out) const;
  // Row-major int32 copy (tests, writers of other formats).
  std::vector<int32_t> ToVector() const;

  // The storage, for the cache file (io/superpixel_io.h): banded() true = band_base() (one per band) and the u16
  // offsets of row `row` at offsets_row(row); false = int32 labels at wide_row(row).
  bool banded() const { return banded_; }
  const std::vector<uint32_t>& band_base() const { return band_base_; }
  const uint16_t* offsets_row(int row) const { return offsets_.data() + static_cast<size_t>(row) * width_; }
  const int32_t* wide_row(int row) const { return wide_.data() + static_cast<size_t>(row) * width_; }
  size_t bytes() const { return offsets_.size() * 2 + wide_.size() * 4 + band_base_.size() * 4; }

  // Same raster, same labels (the storage of given labels is unique).
  bool operator==(const SuperpixelLabels& o) const {
    return width_ == o.width_ && height_ == o.height_ && banded_ == o.banded_ && band_base_ == o.band_base_ &&
           offsets_ == o.offsets_ && wide_ == o.wide_;
  }
  bool operator!=(const SuperpixelLabels& o) const { return !(*this == o); }

 private:
  int width_ = 0, height_ = 0;
  bool banded_ = true;
  std::vector<uint32_t> band_base_;  // banded: smallest label of each band
  std::vector<uint16_t> offsets_;    // banded: label - band base, row-major
  std::vector<int32_t> wide_;        // not banded: the labels, row-major
};

}  // namespace sacfuse
