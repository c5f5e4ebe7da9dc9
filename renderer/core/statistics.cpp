// Order statistics (see statistics.h).
#include "renderer/core/statistics.h"

#include <algorithm>
#include <cmath>

namespace gb {

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  const size_t n = v.size();
  std::nth_element(v.begin(), v.begin() + long(n / 2), v.end());
  double hi = v[n / 2];
  if (n % 2) return hi;
  double lo = *std::max_element(v.begin(), v.begin() + long(n / 2));
  return 0.5 * (lo + hi);
}

double percentile(std::vector<double> v, double p) {
  if (v.empty()) return 0.0;
  size_t k = std::min(v.size() - 1, size_t(std::max(std::ceil(p * double(v.size())), 1.0)) - 1);
  std::nth_element(v.begin(), v.begin() + long(k), v.end());
  return v[k];
}

}  // namespace gb
