// Order statistics used by reports, the bench and error analysis: one definition of each.
#pragma once
#include <vector>

namespace gb {

// The median (mean of the two middle values for an even count); 0 for an empty list.
double median(std::vector<double> values);
// The nearest-rank percentile: the smallest value with at least p (in [0, 1]) of the values at
// or below it (p99 of the error figures); 0 for an empty list.
double percentile(std::vector<double> values, double p);

}  // namespace gb
