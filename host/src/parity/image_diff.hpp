// Helpers of the image comparison shared by its statistics, report and picture.
#pragma once
#include <string>
#include <vector>

namespace brdfcl::detail {

// The p-th percentile (0..100) of ascending `sorted`, interpolated linearly between the two
// nearest ranks (rank p/100 * (n - 1)); 0 for an empty vector.
double percentileOfSorted(const std::vector<double>& sorted, double p);

// A statistic as the report writes it: 4 significant digits ("0.01234", "1.5e-05", "0").
std::string formatStat(double v);

}  // namespace brdfcl::detail
