#pragma once
// A view's superpixel label raster in memory at about 0.6 bytes per pixel (issue 13: as int32 the labels were a
// quarter of an untiled run's heap, as much as the depth maps; as u16 offsets still half as much). Superpixels are
// ~16 pixels across, so a block of 16 x 16 pixels meets a handful of them: each block keeps a palette of its
// distinct labels (in the order they first appear, row-major) and each pixel a 4-bit index into it. A raster where
// some block meets more than 16 labels (tiny regions) keeps u16 offsets from the smallest label of each band of 64
// rows, and one whose band spans more than 65,535 labels (or holds negative labels) keeps int32 labels.
// The superpixel cache file (io/superpixel_io.h) stores the banded u16 layout when the labels fit it (banded()),
// else int32; both are written from CopyRow.
#include <cstddef>
#include <cstdint>
#include <vector>

namespace sacfuse {

// How a freshly computed label raster is held: packed (the constructor: palettes, ~0.6 bytes per pixel) or as
// given (SuperpixelLabels::Unpacked, for a map that is written to its cache file and dropped).
enum class LabelPacking { kPacked, kUnpacked };

class SuperpixelLabels {
 public:
  static constexpr int kBandRows = 64;            // rows per band (the file layout; the u16 storage)
  static constexpr int64_t kMaxBandSpan = 65535;  // largest label - band base a u16 holds
  static constexpr int kBlockPx = 16;             // palette blocks of kBlockPx x kBlockPx pixels
  static constexpr int kMaxPaletteLabels = 16;    // 4-bit indices

  SuperpixelLabels() = default;
  // Row-major labels of a width x height raster. Throws Error when labels.size() != width * height. Negative
  // labels are kept (int32 storage), for the validators downstream to name.
  SuperpixelLabels(int width, int height, const std::vector<int32_t>& labels);
  // The same labels kept as given (int32, 4 bytes per pixel, nothing packed): for a map that is only written to
  // the cache file and dropped (the tiled runs' superpixel pass), where packing the palettes and unpacking them
  // again row by row for the file was ~9 % of the pass (issue 13). banded() and band_base() are as above, so the
  // file is the same; operator== then differs from the packed labels' (it compares storage).
  static SuperpixelLabels Unpacked(int width, int height, std::vector<int32_t> labels);

  int width() const { return width_; }
  int height() const { return height_; }
  size_t size() const { return static_cast<size_t>(width_) * static_cast<size_t>(height_); }
  bool empty() const { return size() == 0; }

  int32_t at(int row, int col) const {
    const size_t i = static_cast<size_t>(row) * static_cast<size_t>(width_) + static_cast<size_t>(col);
    switch (storage_) {
      case Storage::kPalette: {
        const size_t block =
            static_cast<size_t>(row / kBlockPx) * blocks_per_row_ + static_cast<size_t>(col / kBlockPx);
        return palette_[palette_begin_[block] + static_cast<uint32_t>(PaletteIndex(i))];
      }
      case Storage::kBanded:
        return static_cast<int32_t>(band_base_[static_cast<size_t>(row / kBandRows)] + offsets_[i]);
      case Storage::kWide:
        break;
    }
    return wide_[i];
  }
  // Row `row` into out[0, width).
  void CopyRow(int row, int32_t* out) const;
  // Row-major int32 copy (tests, writers of other formats).
  std::vector<int32_t> ToVector() const;

  // Whether the labels fit the banded u16 layout of the cache file (io/superpixel_io.h): none negative, and the
  // labels of each band of kBandRows rows within kMaxBandSpan of band_base() (its smallest label).
  bool banded() const { return banded_; }
  const std::vector<uint32_t>& band_base() const { return band_base_; }
  // Bytes held.
  size_t bytes() const {
    return indices_.size() + palette_begin_.size() * 4 + palette_.size() * 4 + offsets_.size() * 2 +
           wide_.size() * 4 + band_base_.size() * 4;
  }
  // Whether the labels are held as per-block palettes (false: u16 offsets or int32, see the header).
  bool paletted() const { return storage_ == Storage::kPalette; }

  // Same raster, same labels (the storage of given labels is unique).
  bool operator==(const SuperpixelLabels& o) const {
    return width_ == o.width_ && height_ == o.height_ && storage_ == o.storage_ && banded_ == o.banded_ &&
           band_base_ == o.band_base_ && indices_ == o.indices_ && palette_begin_ == o.palette_begin_ &&
           palette_ == o.palette_ && offsets_ == o.offsets_ && wide_ == o.wide_;
  }
  bool operator!=(const SuperpixelLabels& o) const { return !(*this == o); }

 private:
  enum class Storage : uint8_t { kPalette, kBanded, kWide };
  // Checks the size and sets banded_ and band_base_ (throws Error when labels.size() != width * height).
  void FindBands(const std::vector<int32_t>& labels);
  // Palette storage: pixel i's 4-bit index into its block's palette.
  int PaletteIndex(size_t i) const { return (indices_[i / 2] >> ((i % 2) * 4)) & 0xF; }
  // Tries the palette storage; false (nothing kept) when a block meets more than kMaxPaletteLabels labels.
  bool BuildPalettes(const std::vector<int32_t>& labels);

  int width_ = 0, height_ = 0;
  Storage storage_ = Storage::kPalette;
  bool banded_ = true;
  std::vector<uint32_t> band_base_;      // banded(): smallest label of each band
  size_t blocks_per_row_ = 0;            // palette: blocks across the raster
  std::vector<uint8_t> indices_;         // palette: 4-bit index per pixel, row-major, the even pixel in the low bits
  std::vector<uint32_t> palette_begin_;  // palette: first entry of each block's palette in palette_
  std::vector<int32_t> palette_;         // palette: the blocks' labels
  std::vector<uint16_t> offsets_;        // banded storage: label - band base, row-major
  std::vector<int32_t> wide_;            // int32 storage: the labels, row-major
};

}  // namespace sacfuse
