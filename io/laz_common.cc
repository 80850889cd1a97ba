#include "io/laz_common.h"

namespace sacfuse::laz {
namespace {

// Context tables of the LASzip format (values as published; rows n, columns r). Proper pairs 1 <= r <= n get
// their own classes, the rest (r or n zero, r > n) are spread over the remaining ones.
constexpr uint8_t kReturnContext3[8][8] = {
    {15, 14, 13, 12, 11, 10, 9, 8},  {14, 0, 1, 3, 6, 10, 10, 9},    {13, 1, 2, 4, 7, 11, 11, 10},
    {12, 3, 4, 5, 8, 12, 12, 11},    {11, 6, 7, 8, 9, 13, 13, 12},   {10, 10, 11, 12, 13, 14, 14, 13},
    {9, 10, 11, 12, 13, 14, 15, 14}, {8, 9, 10, 11, 12, 13, 14, 15},
};

constexpr uint8_t kReturnContext4[16][16] = {
    {0, 1, 2, 3, 4, 5, 3, 4, 4, 5, 5, 5, 5, 5, 5, 5}, {1, 0, 1, 3, 3, 3, 3, 3, 3, 3, 3, 3, 3, 3, 3, 3},
    {2, 1, 2, 4, 4, 4, 4, 4, 4, 4, 4, 3, 3, 3, 3, 3}, {3, 3, 4, 5, 4, 4, 4, 4, 4, 4, 4, 4, 4, 4, 4, 4},
    {4, 3, 4, 4, 5, 4, 4, 4, 4, 4, 4, 4, 4, 4, 4, 4}, {5, 3, 4, 4, 4, 5, 4, 4, 4, 4, 4, 4, 4, 4, 4, 4},
    {3, 3, 4, 4, 4, 4, 5, 4, 4, 4, 4, 4, 4, 4, 4, 4}, {4, 3, 4, 4, 4, 4, 4, 5, 4, 4, 4, 4, 4, 4, 4, 4},
    {4, 3, 4, 4, 4, 4, 4, 4, 5, 4, 4, 4, 4, 4, 4, 4}, {5, 3, 4, 4, 4, 4, 4, 4, 4, 5, 4, 4, 4, 4, 4, 4},
    {5, 3, 4, 4, 4, 4, 4, 4, 4, 4, 5, 4, 4, 4, 4, 4}, {5, 3, 3, 4, 4, 4, 4, 4, 4, 4, 4, 5, 5, 4, 4, 4},
    {5, 3, 3, 4, 4, 4, 4, 4, 4, 4, 4, 5, 5, 5, 4, 4}, {5, 3, 3, 4, 4, 4, 4, 4, 4, 4, 4, 4, 5, 5, 5, 4},
    {5, 3, 3, 4, 4, 4, 4, 4, 4, 4, 4, 4, 4, 5, 5, 5}, {5, 3, 3, 4, 4, 4, 4, 4, 4, 4, 4, 4, 4, 4, 5, 5},
};

}  // namespace

uint32_t ReturnContext3(uint32_t n, uint32_t r) { return kReturnContext3[n & 7][r & 7]; }
uint32_t ReturnContext4(uint32_t n, uint32_t r) { return kReturnContext4[n & 15][r & 15]; }

void Median5::Add(int32_t v) {
  std::array<int32_t, 5>& s = values_;  // kept sorted
  if (replace_high_) {
    // Drop the largest value, insert v.
    if (v < s[2]) {
      s[4] = s[3];
      s[3] = s[2];
      if (v < s[0]) {
        s[2] = s[1];
        s[1] = s[0];
        s[0] = v;
      } else if (v < s[1]) {
        s[2] = s[1];
        s[1] = v;
      } else {
        s[2] = v;
      }
    } else {
      if (v < s[3]) {
        s[4] = s[3];
        s[3] = v;
      } else {
        s[4] = v;
      }
      replace_high_ = false;
    }
  } else {
    // Drop the smallest value, insert v.
    if (s[2] < v) {
      s[0] = s[1];
      s[1] = s[2];
      if (s[4] < v) {
        s[2] = s[3];
        s[3] = s[4];
        s[4] = v;
      } else if (s[3] < v) {
        s[2] = s[3];
        s[3] = v;
      } else {
        s[2] = v;
      }
    } else {
      if (s[1] < v) {
        s[0] = s[1];
        s[1] = v;
      } else {
        s[0] = v;
      }
      replace_high_ = true;
    }
  }
}

}  // namespace sacfuse::laz
