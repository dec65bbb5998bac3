#pragma once
// Pairwise (cascade) summation of fixed-size vectors of partial sums.
//
// Adding n numbers one after the other lets the rounding error grow like n·ε; adding them in a
// balanced binary tree keeps it at log₂(n)·ε. The mesh integrals add a block sum per few hundred
// triangles; this class merges those block sums like a binary counter: level k holds the sum of 2^k
// blocks, and adding a block carries through the occupied levels, so memory stays at 64 levels and
// every block sum is added to a partner of equal size. (Boost.Accumulators and Eigen's redux offer
// no pairwise reduction of a stream of vectors; the carry loop is a dozen lines.)
#include <array>
#include <cstddef>
#include <cstdint>

namespace tumble::detail {

template <std::size_t N>
class PairwiseSum {
 public:
  using Terms = std::array<double, N>;

  void add(Terms x) {
    std::uint64_t c = count_++;
    int level = 0;
    while ((c & 1U) != 0U) {  // carry: merge with the equal-sized partial sum at this level
      for (std::size_t i = 0; i < N; ++i) x[i] = partial_[level][i] + x[i];
      c >>= 1U;
      ++level;
    }
    partial_[level] = x;
  }

  /// The sum of everything added, smallest partial sums first.
  Terms total() const {
    Terms sum{};
    std::uint64_t c = count_;
    for (int level = 0; c != 0U; ++level, c >>= 1U) {
      if ((c & 1U) != 0U) {
        for (std::size_t i = 0; i < N; ++i) sum[i] += partial_[level][i];
      }
    }
    return sum;
  }

 private:
  std::array<Terms, 64> partial_{};
  std::uint64_t count_ = 0;
};

}  // namespace tumble::detail
