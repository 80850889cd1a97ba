#include "core/superpixel_labels.h"

#include <algorithm>
#include <string>

#include "core/error.h"

namespace sacfuse {

SuperpixelLabels::SuperpixelLabels(int width, int height, const std::vector<int32_t>& labels)
    : width_(width), height_(height) {
  if (width < 0 || height < 0 || labels.size() != size()) {
    throw Error("SuperpixelLabels: " + std::to_string(labels.size()) + " labels for a " + std::to_string(width) +
                "x" + std::to_string(height) + " raster");
  }
  const size_t row_values = static_cast<size_t>(width);
  const size_t bands = (static_cast<size_t>(height) + kBandRows - 1) / kBandRows;
  band_base_.assign(bands, 0);
  for (size_t b = 0; b < bands && banded_; ++b) {
    const auto begin = labels.begin() + static_cast<std::ptrdiff_t>(b * kBandRows * row_values);
    const size_t end_index = std::min(labels.size(), (b + 1) * kBandRows * row_values);
    const auto end = labels.begin() + static_cast<std::ptrdiff_t>(end_index);
    if (begin == end) continue;
    const auto [lo, hi] = std::minmax_element(begin, end);
    if (*lo < 0 || static_cast<int64_t>(*hi) - *lo > kMaxBandSpan) {
      banded_ = false;
    } else {
      band_base_[b] = static_cast<uint32_t>(*lo);
    }
  }
  if (!banded_) {
    band_base_.clear();
    wide_ = labels;
    return;
  }
  offsets_.resize(labels.size());
  for (int r = 0; r < height; ++r) {
    const uint32_t base = band_base_[static_cast<size_t>(r / kBandRows)];
    const size_t first = static_cast<size_t>(r) * row_values;
    for (size_t i = first; i < first + row_values; ++i) {
      offsets_[i] = static_cast<uint16_t>(static_cast<uint32_t>(labels[i]) - base);
    }
  }
}

void SuperpixelLabels::CopyRow(int row, int32_t* out) const {
  if (!banded_) {
    std::copy_n(wide_row(row), width_, out);
    return;
  }
  const uint32_t base = band_base_[static_cast<size_t>(row / kBandRows)];
  const uint16_t* offsets = offsets_row(row);
  for (int c = 0; c < width_; ++c) out[c] = static_cast<int32_t>(base + offsets[c]);
}

std::vector<int32_t> SuperpixelLabels::ToVector() const {
  std::vector<int32_t> out(size());
  for (int r = 0; r < height_; ++r) CopyRow(r, out.data() + static_cast<size_t>(r) * width_);
  return out;
}

}  // namespace sacfuse
