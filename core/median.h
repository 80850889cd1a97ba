#pragma once
// The one median helper of core: the element at size / 2 after a partial sort (the upper median of an even count;
// no averaging, so the result is one of the values).
#include <algorithm>
#include <vector>

namespace sacfuse {

// Reorders `values`; 0 when empty.
inline double UpperMedianInPlace(std::vector<double>* values) {
  if (values->empty()) return 0.0;
  const auto mid = values->begin() + values->size() / 2;
  std::nth_element(values->begin(), mid, values->end());
  return *mid;
}

}  // namespace sacfuse
