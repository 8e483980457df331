// Deterministic parallel reductions: the sum is split into blocks of a fixed size, each block is
// summed in order, and the block sums are added in order, so the result does not depend on the
// number of threads (bit-identical runs for 1 and 2 threads).
#pragma once

#include <algorithm>
#include <vector>

namespace dem {

template <typename T, typename BlockSum>
T deterministic_sum(int n, const T& zero, BlockSum&& block_sum) {
  constexpr int kBlock = 1024;
  const int num_blocks = (n + kBlock - 1) / kBlock;
  std::vector<T> partial(num_blocks, zero);
#pragma omp parallel for schedule(static) if (num_blocks > 1)
  for (int b = 0; b < num_blocks; ++b)
    partial[b] = block_sum(b * kBlock, std::min(n, (b + 1) * kBlock));
  T total = zero;
  for (const T& p : partial) total += p;
  return total;
}

}  // namespace dem
