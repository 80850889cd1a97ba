#include "core/superpixel_labels.h"

#include <algorithm>
#include <string>
#include <utility>

#include "core/error.h"

namespace sacfuse {

SuperpixelLabels::SuperpixelLabels(int width, int height, const std::vector<int32_t>& labels)
    : width_(width), height_(height) {
  FindBands(labels);
  const size_t row_values = static_cast<size_t>(width);
  if (BuildPalettes(labels)) {
    storage_ = Storage::kPalette;
    return;
  }
  if (!banded_) {
    storage_ = Storage::kWide;
    wide_ = labels;
    return;
  }
  storage_ = Storage::kBanded;
  offsets_.resize(labels.size());
  for (int r = 0; r < height; ++r) {
    const uint32_t base = band_base_[static_cast<size_t>(r / kBandRows)];
    const size_t first = static_cast<size_t>(r) * row_values;
    for (size_t i = first; i < first + row_values; ++i) {
      offsets_[i] = static_cast<uint16_t>(static_cast<uint32_t>(labels[i]) - base);
    }
  }
}

SuperpixelLabels SuperpixelLabels::Unpacked(int width, int height, std::vector<int32_t> labels) {
  SuperpixelLabels out;
  out.width_ = width;
  out.height_ = height;
  out.FindBands(labels);
  out.storage_ = Storage::kWide;
  out.wide_ = std::move(labels);
  return out;
}

void SuperpixelLabels::FindBands(const std::vector<int32_t>& labels) {
  if (width_ < 0 || height_ < 0 || labels.size() != size()) {
    throw Error("SuperpixelLabels: " + std::to_string(labels.size()) + " labels for a " + std::to_string(width_) +
                "x" + std::to_string(height_) + " raster");
  }
  const size_t row_values = static_cast<size_t>(width_);
  const size_t bands = (static_cast<size_t>(height_) + kBandRows - 1) / kBandRows;
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
  if (!banded_) band_base_.clear();
}

bool SuperpixelLabels::BuildPalettes(const std::vector<int32_t>& labels) {
  blocks_per_row_ = (static_cast<size_t>(width_) + kBlockPx - 1) / kBlockPx;
  const size_t block_rows = (static_cast<size_t>(height_) + kBlockPx - 1) / kBlockPx;
  std::vector<uint8_t> indices((size() + 1) / 2, 0);
  std::vector<uint32_t> palette_begin(blocks_per_row_ * block_rows);
  std::vector<int32_t> palette;
  for (size_t br = 0; br < block_rows; ++br) {
    for (size_t bc = 0; bc < blocks_per_row_; ++bc) {
      const uint32_t begin = static_cast<uint32_t>(palette.size());
      palette_begin[br * blocks_per_row_ + bc] = begin;
      const int row_end = std::min(height_, static_cast<int>(br + 1) * kBlockPx);
      const int col_end = std::min(width_, static_cast<int>(bc + 1) * kBlockPx);
      // Most pixels repeat the label before them: that one's index is reused without a search.
      int32_t last_label = 0;
      size_t last_index = kMaxPaletteLabels;  // none yet in this block
      for (int r = static_cast<int>(br) * kBlockPx; r < row_end; ++r) {
        for (int c = static_cast<int>(bc) * kBlockPx; c < col_end; ++c) {
          const size_t i = static_cast<size_t>(r) * static_cast<size_t>(width_) + static_cast<size_t>(c);
          size_t index = last_index;
          if (index == kMaxPaletteLabels || labels[i] != last_label) {
            const auto first = palette.begin() + begin;
            const auto found = std::find(first, palette.end(), labels[i]);
            index = static_cast<size_t>(found - first);
            if (found == palette.end()) {
              if (index == kMaxPaletteLabels) return false;
              palette.push_back(labels[i]);
            }
            last_label = labels[i];
            last_index = index;
          }
          indices[i / 2] = static_cast<uint8_t>(indices[i / 2] | (index << ((i % 2) * 4)));
        }
      }
    }
  }
  indices_ = std::move(indices);
  palette_begin_ = std::move(palette_begin);
  palette.shrink_to_fit();
  palette_ = std::move(palette);
  return true;
}

void SuperpixelLabels::CopyRow(int row, int32_t* out) const {
  switch (storage_) {
    case Storage::kPalette: {  // at(), one block's palette at a time
      const size_t first = static_cast<size_t>(row) * static_cast<size_t>(width_);
      const uint32_t* block_begin = palette_begin_.data() + static_cast<size_t>(row / kBlockPx) * blocks_per_row_;
      for (int c0 = 0; c0 < width_; c0 += kBlockPx) {
        const int32_t* palette = palette_.data() + block_begin[c0 / kBlockPx];
        const int c1 = std::min(width_, c0 + kBlockPx);
        for (int c = c0; c < c1; ++c) out[c] = palette[PaletteIndex(first + static_cast<size_t>(c))];
      }
      return;
    }
    case Storage::kBanded: {
      const uint32_t base = band_base_[static_cast<size_t>(row / kBandRows)];
      const uint16_t* offsets = offsets_.data() + static_cast<size_t>(row) * width_;
      for (int c = 0; c < width_; ++c) out[c] = static_cast<int32_t>(base + offsets[c]);
      return;
    }
    case Storage::kWide:
      std::copy_n(wide_.data() + static_cast<size_t>(row) * width_, width_, out);
      return;
  }
}

std::vector<int32_t> SuperpixelLabels::ToVector() const {
  std::vector<int32_t> out(size());
  for (int r = 0; r < height_; ++r) CopyRow(r, out.data() + static_cast<size_t>(r) * width_);
  return out;
}

}  // namespace sacfuse
