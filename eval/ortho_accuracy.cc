#include "eval/ortho_accuracy.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <opencv2/imgproc.hpp>

#include "core/error.h"
#include "io/gdal_raster.h"
#include "io/point_cloud_file.h"

namespace sacfuse {
namespace {

cv::Mat Grey(const RgbaGrid& g) {
  cv::Mat out(static_cast<int>(g.window.rows), static_cast<int>(g.window.cols), CV_8U);
  for (size_t i = 0; i < g.window.size(); ++i) {
    const uint8_t* p = &g.rgba[4 * i];
    out.data[i] = static_cast<uint8_t>(std::lround(0.299 * p[0] + 0.587 * p[1] + 0.114 * p[2]));
  }
  return out;
}

double Quantile(std::vector<double> v, double q) {
  if (v.empty()) return 0.0;
  const size_t k = std::min(v.size() - 1, static_cast<size_t>(std::floor(q * (v.size() - 1) + 0.5)));
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
  return v[k];
}

}  // namespace

RgbaGrid ReadRgbaGrid(const std::string& path, const CellWindow& window) {
  const RasterFile file(path);
  if (file.bands() != 3 && file.bands() != 4) throw InputError(path, "not an RGB or RGBA raster");
  RgbaGrid g;
  g.window = window;
  g.rgba.assign(4 * window.size(), 0);
  std::vector<std::vector<float>> bands;
  for (int b = 1; b <= file.bands(); ++b) bands.push_back(file.ReadFloat(window, b));
  for (size_t i = 0; i < window.size(); ++i) {
    bool inside = true;
    for (int b = 0; b < 3; ++b) {
      inside = inside && std::isfinite(bands[b][i]);
      g.rgba[4 * i + b] = std::isfinite(bands[b][i]) ? static_cast<uint8_t>(bands[b][i]) : 0;
    }
    const float a = file.bands() == 4 ? bands[3][i] : 255.0f;
    g.rgba[4 * i + 3] = inside && std::isfinite(a) ? static_cast<uint8_t>(a) : 0;
  }
  return g;
}

RgbaGrid PointColourOrtho(const std::string& cloud_path, const CellWindow& window) {
  std::vector<std::array<double, 3>> sum(window.size(), {0, 0, 0});
  std::vector<uint32_t> count(window.size(), 0);
  PointCloudFile cloud(cloud_path);
  CloudChunk chunk;
  while (cloud.Read(&chunk, kCloudReadChunkPoints) > 0) {
    for (size_t k = 0; k < chunk.xyz.size(); ++k) {
      const int64_t col = CellIndexOf(chunk.xyz[k].x(), window.cell_m);
      const int64_t row = CellIndexOf(chunk.xyz[k].y(), window.cell_m);
      if (!window.Contains(col, row)) continue;
      const size_t i = window.Index(col, row);
      for (int c = 0; c < 3; ++c) sum[i][c] += chunk.rgb[k][c];
      ++count[i];
    }
  }
  RgbaGrid g;
  g.window = window;
  g.rgba.assign(4 * window.size(), 0);
  for (size_t i = 0; i < window.size(); ++i) {
    if (count[i] == 0) continue;
    for (int c = 0; c < 3; ++c) g.rgba[4 * i + c] = static_cast<uint8_t>(std::lround(sum[i][c] / count[i]));
    g.rgba[4 * i + 3] = 255;
  }
  return g;
}

OrthoScores ScoreOrtho(const std::string& name, const RgbaGrid& ortho, const RgbaGrid& reference) {
  if (ortho.window != reference.window) throw Error("ScoreOrtho: the ortho and the reference differ in extent");
  OrthoScores s;
  s.name = name;
  s.cell_m = ortho.window.cell_m;
  const int rows = static_cast<int>(ortho.window.rows), cols = static_cast<int>(ortho.window.cols);
  cv::Mat both(rows, cols, CV_8U, cv::Scalar(0));
  double squared = 0.0;
  for (size_t i = 0; i < ortho.window.size(); ++i) {
    if (reference.rgba[4 * i + 3] == 0) continue;
    ++s.cells;
    if (ortho.rgba[4 * i + 3] == 0) continue;
    ++s.common;
    both.data[i] = 255;
    for (int c = 0; c < 3; ++c) {
      const double d = static_cast<double>(ortho.rgba[4 * i + c]) - reference.rgba[4 * i + c];
      squared += d * d;
    }
  }
  s.coverage = s.cells > 0 ? static_cast<double>(s.common) / static_cast<double>(s.cells) : 0.0;
  if (s.common == 0) return s;
  const double mse = squared / (3.0 * static_cast<double>(s.common));
  s.psnr_db = mse > 0 ? 10.0 * std::log10(255.0 * 255.0 / mse) : 99.0;

  // SSIM on grey values, over the cells whose 11 x 11 window both cover.
  cv::Mat a, b;
  Grey(ortho).convertTo(a, CV_64F);
  Grey(reference).convertTo(b, CV_64F);
  const cv::Size win(11, 11);
  const double sigma = 1.5, c1 = std::pow(0.01 * 255, 2), c2 = std::pow(0.03 * 255, 2);
  cv::Mat mu_a, mu_b, aa, bb, ab;
  cv::GaussianBlur(a, mu_a, win, sigma);
  cv::GaussianBlur(b, mu_b, win, sigma);
  cv::GaussianBlur(a.mul(a), aa, win, sigma);
  cv::GaussianBlur(b.mul(b), bb, win, sigma);
  cv::GaussianBlur(a.mul(b), ab, win, sigma);
  cv::Mat inside;
  cv::erode(both, inside, cv::getStructuringElement(cv::MORPH_RECT, win));
  double ssim_sum = 0.0;
  uint64_t ssim_cells = 0;
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < cols; ++c) {
      if (!inside.at<uint8_t>(r, c)) continue;
      const double ma = mu_a.at<double>(r, c), mb = mu_b.at<double>(r, c);
      const double va = aa.at<double>(r, c) - ma * ma, vb = bb.at<double>(r, c) - mb * mb;
      const double cov = ab.at<double>(r, c) - ma * mb;
      ssim_sum += ((2 * ma * mb + c1) * (2 * cov + c2)) / ((ma * ma + mb * mb + c1) * (va + vb + c2));
      ++ssim_cells;
    }
  }
  s.ssim = ssim_cells > 0 ? ssim_sum / static_cast<double>(ssim_cells) : 0.0;

  // Edge displacement: reference edges to the nearest ortho edge.
  cv::Mat edges_ref, edges_ortho, not_edge, distance, core;
  cv::Canny(Grey(reference), edges_ref, 50, 150, 3, true);
  cv::Canny(Grey(ortho), edges_ortho, 50, 150, 3, true);
  cv::erode(both, core, cv::getStructuringElement(cv::MORPH_RECT, cv::Size(7, 7)));
  edges_ortho.setTo(0, both == 0);
  cv::threshold(edges_ortho, not_edge, 0, 255, cv::THRESH_BINARY_INV);
  cv::distanceTransform(not_edge, distance, cv::DIST_L2, cv::DIST_MASK_PRECISE);
  std::vector<double> d;
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < cols; ++c) {
      if (edges_ref.at<uint8_t>(r, c) && core.at<uint8_t>(r, c)) d.push_back(distance.at<float>(r, c));
    }
  }
  s.edge_cells = d.size();
  s.edge_median_cells = Quantile(d, 0.5);
  s.edge_p90_cells = Quantile(d, 0.9);
  double total = 0.0;
  for (const double x : d) total += x;
  s.edge_mean_cells = d.empty() ? 0.0 : total / static_cast<double>(d.size());
  return s;
}

std::string FormatOrthoScores(const std::vector<OrthoScores>& scores) {
  std::string out = "Orthophoto against the reference ortho (cells the reference covers):\n";
  char line[512];
  std::snprintf(line, sizeof(line), "  %-14s %10s %10s %9s %7s %24s %24s %24s\n", "ortho", "cells", "coverage",
                "PSNR dB", "SSIM", "edge shift median", "edge shift p90", "edge shift mean");
  out += line;
  for (const OrthoScores& s : scores) {
    std::snprintf(line, sizeof(line),
                  "  %-14s %10llu %9.2f%% %9.2f %7.3f %8.2f cells %6.3f m %8.2f cells %6.3f m %8.2f cells %6.3f m\n",
                  s.name.c_str(), static_cast<unsigned long long>(s.cells), 100.0 * s.coverage, s.psnr_db, s.ssim,
                  s.edge_median_cells, s.edge_median_cells * s.cell_m, s.edge_p90_cells, s.edge_p90_cells * s.cell_m,
                  s.edge_mean_cells, s.edge_mean_cells * s.cell_m);
    out += line;
  }
  return out;
}

}  // namespace sacfuse
