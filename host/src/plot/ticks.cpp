// Tick positions and labels for axes and colour bars: steps of 1, 2 or 5 times a power of ten,
// labels with just the decimals the step needs, so that neighbouring labels differ visibly.
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <fmt/format.h>

#include "plot/plot.hpp"

namespace brdfcl::plot {

Ticks niceTicks(double lo, double hi, int maxTicks) {
  if (!std::isfinite(lo) || !std::isfinite(hi) || lo > hi) throw std::invalid_argument("plot::niceTicks: bad range");
  if (maxTicks < 1) maxTicks = 1;
  Ticks t;
  if (hi == lo) {
    t.values = {lo};
    t.step = lo != 0 ? std::pow(10.0, std::floor(std::log10(std::fabs(lo)))) : 1.0;
    return t;
  }
  const double range = hi - lo;
  if (!std::isfinite(range)) {  // lo and hi near the ends of the double range: just the ends
    t.values = {lo, hi};
    t.step = hi / 2 - lo / 2;
    return t;
  }
  double magnitude = std::pow(10.0, std::floor(std::log10(range / maxTicks)));
  // A relative slack so that an end that is a multiple of the step, up to rounding, gets its tick.
  const double slack = 1e-9;
  for (;;) {
    for (const double m : {1.0, 2.0, 5.0}) {
      const double step = m * magnitude;
      const double first = std::ceil(lo / step - slack), last = std::floor(hi / step + slack);
      if (last - first + 1 <= maxTicks) {
        t.step = step;
        for (double k = first; k <= last; ++k) {
          const double v = k * step;
          t.values.push_back(std::fabs(v) < step * 1e-9 ? 0.0 : v);
        }
        return t;
      }
    }
    magnitude *= 10.0;
  }
}

std::string tickLabel(double value, double step) {
  if (value == 0.0 || std::fabs(value) < std::fabs(step) * 1e-9) return "0";
  const int decimals = std::max(0, static_cast<int>(std::ceil(-std::log10(std::fabs(step)) - 1e-9)));
  if (decimals <= 4 && std::fabs(value) < 1e6) return fmt::format("{:.{}f}", value, decimals);
  // Scientific, with as many mantissa digits as the step resolves and a short exponent ("2e-5").
  const int digits = std::max(0, static_cast<int>(std::floor(std::log10(std::fabs(value))) -
                                                  std::floor(std::log10(std::fabs(step)) + 1e-9)));
  std::string s = fmt::format("{:.{}e}", value, digits);
  const auto e = s.find('e');
  std::string exponent = s.substr(e + 1);
  const bool negative = exponent[0] == '-';
  exponent = exponent.substr(1);
  while (exponent.size() > 1 && exponent[0] == '0') exponent.erase(0, 1);
  return s.substr(0, e) + "e" + (negative ? "-" : "") + exponent;
}

}  // namespace brdfcl::plot
