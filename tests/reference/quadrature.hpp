// Adaptive Gauss-Kronrod quadrature (QUADPACK QAG with the 10/21-point pair) of the reference:
// the sheen albedo E and the directional albedo integrate with it. Private to tests/reference.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <vector>

namespace ref {

// Kronrod 21-point abscissae (positive half, kXgk[10] = 0) and weights; Gauss 10-point weights
// for the odd-indexed abscissae. Values from QUADPACK qk21 (test: exact for degree <= 31).
inline constexpr double kXgk[11] = {0.995657163025808080735527280689003, 0.973906528517171720077964012084452,
                                    0.930157491355708226001207180059508, 0.865063366688984510732096688423493,
                                    0.780817726586416897063717578345042, 0.679409568299024406234327365114874,
                                    0.562757134668604683339000099272694, 0.433395394129247190799265943165784,
                                    0.294392862701460198131126603103866, 0.148874338981631210884826001129720,
                                    0.0};
inline constexpr double kWgk[11] = {0.011694638867371874278064396062192, 0.032558162307964727478818972459390,
                                    0.054755896574351996031381300244580, 0.075039674810919952767043140916190,
                                    0.093125454583697605535065465083366, 0.109387158802297641899210590325805,
                                    0.123491976262065851077208707152081, 0.134709217311473325928054001771707,
                                    0.142775938577060080797094273138717, 0.147739104901338491374841515972068,
                                    0.149445554002916905664936468389821};
inline constexpr double kWg[5] = {0.066671344308688137593568809893332, 0.149451349150580593145776339657697,
                                  0.219086362515982043995534934228163, 0.269266719309996355091226921569469,
                                  0.295524224714752870173892994651338};

template <std::size_t K>
using VecK = std::array<double, K>;

template <std::size_t K>
struct Interval {
  double a, b;
  VecK<K> value;
  double err;
};

// One 21-point Kronrod estimate on [a, b] with QUADPACK's error estimate (qk21): |K21 - G10|
// scaled by the integrand's variation, err = resasc * min(1, (200 |K21 - G10| / resasc)^1.5). The
// raw |K21 - G10| is the error of G10, far larger than K21's once converged, and it also floors at
// rounding noise, so bisection would never stop for tight tolerances. QUADPACK's extra
// 50 eps |result| floor is left out for the same reason (rounding is far below any tolerance used).
template <std::size_t K, class F>
Interval<K> gk21(F& f, double a, double b) {
  const double c = 0.5 * (a + b), h = 0.5 * (b - a);
  VecK<K> fv[21];
  fv[10] = f(c);
  for (int j = 0; j < 10; ++j) {
    fv[j] = f(c - h * kXgk[j]);
    fv[20 - j] = f(c + h * kXgk[j]);
  }
  Interval<K> r{a, b, {}, 0.0};
  for (std::size_t i = 0; i < K; ++i) {
    double k = fv[10][i] * kWgk[10], g = 0.0;  // the 10-point Gauss rule has no centre node
    for (int j = 0; j < 10; ++j) {
      k += kWgk[j] * (fv[j][i] + fv[20 - j][i]);
      if (j % 2 == 1) g += kWg[j / 2] * (fv[j][i] + fv[20 - j][i]);
    }
    const double mean = 0.5 * k;
    double resasc = kWgk[10] * std::abs(fv[10][i] - mean);
    for (int j = 0; j < 10; ++j)
      resasc += kWgk[j] * (std::abs(fv[j][i] - mean) + std::abs(fv[20 - j][i] - mean));
    resasc *= std::abs(h);
    double err = std::abs((k - g) * h);
    if (resasc != 0.0 && err != 0.0) err = resasc * std::min(1.0, std::pow(200.0 * err / resasc, 1.5));
    r.value[i] = k * h;
    r.err = std::max(r.err, err);
  }
  return r;
}

// Globally adaptive (QUADPACK qag): always bisect the interval with the largest error estimate
// until the sum of the estimates is below absTol.
template <std::size_t K, class F>
VecK<K> qag(F&& f, double a, double b, double absTol, int maxIntervals = 4000) {
  std::vector<Interval<K>> heap;
  heap.reserve(64);
  auto less = [](const Interval<K>& p, const Interval<K>& q) { return p.err < q.err; };
  heap.push_back(gk21<K>(f, a, b));
  double totalErr = heap.front().err;
  while (totalErr > absTol && static_cast<int>(heap.size()) < maxIntervals) {
    std::pop_heap(heap.begin(), heap.end(), less);
    const Interval<K> worst = heap.back();
    heap.pop_back();
    const double m = 0.5 * (worst.a + worst.b);
    if (!(m > worst.a && m < worst.b)) {  // cannot split further: keep it and stop
      heap.push_back(worst);
      std::push_heap(heap.begin(), heap.end(), less);
      break;
    }
    heap.push_back(gk21<K>(f, worst.a, m));
    std::push_heap(heap.begin(), heap.end(), less);
    heap.push_back(gk21<K>(f, m, worst.b));
    std::push_heap(heap.begin(), heap.end(), less);
    totalErr = 0.0;  // recomputed, not updated, so rounding never accumulates
    for (const auto& iv : heap) totalErr += iv.err;
  }
  VecK<K> sum{};
  for (const auto& iv : heap)
    for (std::size_t i = 0; i < K; ++i) sum[i] += iv.value[i];
  return sum;
}

template <class F>
double qag1(F&& f, double a, double b, double absTol, int maxIntervals = 4000) {
  auto g = [&](double x) { return VecK<1>{f(x)}; };
  return qag<1>(g, a, b, absTol, maxIntervals)[0];
}

}  // namespace ref
