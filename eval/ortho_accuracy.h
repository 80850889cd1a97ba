#pragma once
// True-orthophoto accuracy (`sacfuse eval --ortho ORTHO --ortho-reference REF`; docs/dsm-and-ortho.md): an RGBA
// orthophoto against a reference orthophoto on the same cell lattice (on the simulator, `sacfuse simulate
// --truth-ortho-cell M` renders the true scene from straight above with the images' view-independent shading),
// beside an ortho made from the fused points' colours (the mean colour of each cell's points: what a tool without
// the images would deliver; made here only for the comparison).
//   Cells scored: those the reference covers (alpha > 0) inside the common extent.
//   coverage      share of the scored cells the ortho covers (alpha > 0)
//   PSNR (dB)     over the cells both cover, of the 8-bit RGB values (MSE over the three channels)
//   SSIM          Wang et al. (2004) on the grey values (Gaussian window, sigma 1.5 cells, C1 = (0.01 255)^2,
//                 C2 = (0.03 255)^2), averaged over the cells both cover whose 11 x 11 window both cover
//   edge displacement  Canny edges (thresholds 50/150 on the grey values, 3 x 3 Sobel) of the reference, inside the
//                 cells both cover (eroded by 3 cells), each at its distance to the nearest edge of the ortho: median,
//                 90th percentile and mean, in cells and metres (building outlines that lean or smear move edges)
#include <cstdint>
#include <string>
#include <vector>

#include "core/cell_window.h"

namespace sacfuse {

// An RGBA raster on the lattice, north-up, 4 interleaved bytes per cell.
struct RgbaGrid {
  CellWindow window;
  std::vector<uint8_t> rgba;
};

struct OrthoScores {
  std::string name;
  uint64_t cells = 0;          // scored (the reference covers them)
  uint64_t common = 0;         // of those, covered by the ortho too
  double coverage = 0.0;
  double psnr_db = 0.0;
  double ssim = 0.0;
  uint64_t edge_cells = 0;     // reference edge cells measured
  double edge_median_cells = 0.0, edge_p90_cells = 0.0, edge_mean_cells = 0.0;
  double cell_m = 0.0;
};

// Reads an RGBA raster (or RGB, then covered wherever it has cells) over
// `window` (its cells outside the file transparent). Throws InputError naming the file.
RgbaGrid ReadRgbaGrid(const std::string& path, const CellWindow& window);
// The mean colour of each cell's points of a LAS/LAZ/PLY cloud (cells without points transparent).
RgbaGrid PointColourOrtho(const std::string& cloud_path, const CellWindow& window);

// `ortho` and `reference` must share their window.
OrthoScores ScoreOrtho(const std::string& name, const RgbaGrid& ortho, const RgbaGrid& reference);

// One line per score set, with a header.
std::string FormatOrthoScores(const std::vector<OrthoScores>& scores);

}  // namespace sacfuse
