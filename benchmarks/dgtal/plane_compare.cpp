// Benchmark peer (benchmarks/planes.py): DGtal's ChordGenericStandardPlaneComputer on the point sets that
// MR Modeler's recognizer is given. Built by benchmarks/dgtal/build.sh, never by the product or the tests.
//
// Input (a file of little-endian int64): n_sets, then for each set n_points followed by 3 * n_points
// coordinates (x, y, z). Each set is fed to one computer point after point, as a recognizer is used when a
// segment grows; the run stops at the first point refused. Output, one line per set:
//   accepted a b c nanoseconds
// with accepted the number of points taken before the first refusal (all of them when none is refused),
// (a, b, c) the normal DGtal reports for the accepted points (divided by its gcd) and the time of the
// extend() calls of the set (the reading and the printing are not timed).
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <numeric>
#include <vector>

#include "DGtal/base/Common.h"
#include "DGtal/geometry/surfaces/ChordGenericStandardPlaneComputer.h"
#include "DGtal/kernel/SpaceND.h"

using Z3 = DGtal::SpaceND<3, int64_t>;
using Computer = DGtal::ChordGenericStandardPlaneComputer<Z3, Z3::Point, int64_t>;

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: plane_compare POINTS.bin\n";
    return 2;
  }
  std::ifstream in(argv[1], std::ios::binary);
  auto next = [&in]() {
    int64_t v = 0;
    in.read(reinterpret_cast<char*>(&v), sizeof v);
    return v;
  };
  const int64_t n_sets = next();
  for (int64_t s = 0; s < n_sets; ++s) {
    const int64_t n = next();
    std::vector<Z3::Point> pts;
    pts.reserve(n);
    for (int64_t i = 0; i < n; ++i) {
      const int64_t x = next(), y = next(), z = next();
      pts.emplace_back(x, y, z);
    }
    Computer plane;
    plane.init(1, 1);  // diagonal width < 1 x sqrt(3): the standard planes
    int64_t accepted = 0;
    const auto t0 = std::chrono::steady_clock::now();
    for (const auto& p : pts) {
      if (!plane.extend(p)) break;
      ++accepted;
    }
    const auto t1 = std::chrono::steady_clock::now();
    Computer::InternalVector normal;
    int64_t lo = 0, hi = 0;
    Z3::Point pmin, pmax;
    int64_t a = 0, b = 0, c = 0;
    if (accepted > 0) {
      plane.getCharacteristics(normal, lo, hi, pmin, pmax);
      a = normal[0], b = normal[1], c = normal[2];
      const int64_t g = std::gcd(std::gcd(a, b), c);
      if (g > 1) a /= g, b /= g, c /= g;
    }
    std::printf("%lld %lld %lld %lld %lld\n", static_cast<long long>(accepted), static_cast<long long>(a),
                static_cast<long long>(b), static_cast<long long>(c),
                static_cast<long long>(std::chrono::duration_cast<std::chrono::nanoseconds>(t1 - t0).count()));
  }
  return 0;
}
