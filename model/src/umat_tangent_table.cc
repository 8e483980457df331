#include "umat_tangent_table.h"

#include <array>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <mutex>
#include <optional>
#include <shared_mutex>
#include <vector>

namespace model::umat_detail {
namespace {

// The 15 entries above the diagonal of the antisymmetric 6 x 6 part; the rest follow from them.
using UnsymmetricPart = std::array<double, 15>;

struct Table {
  // Written by the UMAT calls (ccx's result threads), read by the assembly (its matrix threads).
  std::shared_mutex mutex;
  // [noel - 1][npt - 1]; empty where the UMAT has not been called at that point.
  std::vector<std::vector<std::optional<UnsymmetricPart>>> points;
  bool any = false;
  bool failed = false;  // a part could not be kept: the symmetric path from then on
};

Table& table() {
  static Table t;
  return t;
}

constexpr int kTensors = 6;

// The position of entry (i, j), i < j, in UnsymmetricPart.
int upper_index(int i, int j) { return i * kTensors - i * (i + 1) / 2 + (j - i - 1); }

}  // namespace

void keep_unsymmetric_part(int noel, int npt, const double* ddsdde, int ntens) noexcept {
  if (ntens != kTensors || noel < 1 || npt < 1) return;  // 3D elements only
  UnsymmetricPart part;
  for (int i = 0; i < kTensors; ++i)
    for (int j = i + 1; j < kTensors; ++j)
      part[upper_index(i, j)] = 0.5 * (ddsdde[i + kTensors * j] - ddsdde[j + kTensors * i]);
  Table& t = table();
  try {
    const std::unique_lock<std::shared_mutex> lock(t.mutex);
    if (t.failed) return;
    const auto e = static_cast<std::size_t>(noel - 1), p = static_cast<std::size_t>(npt - 1);
    if (t.points.size() <= e) t.points.resize(e + 1);
    if (t.points[e].size() <= p) t.points[e].resize(p + 1);
    t.points[e][p] = part;
    t.any = true;
  } catch (const std::exception& error) {
    t.failed = true;  // written under the lock unless the lock itself failed: then it is said twice
    std::fprintf(stderr,
                 "sffcal_umat: cannot keep the tangent's unsymmetric part (element %d, point %d: "
                 "%s): ccx goes on with the symmetric part\n",
                 noel, npt, error.what());
  }
}

}  // namespace model::umat_detail

extern "C" void sffcal_umat_has_unsymmetric_part_(const int* noel, int* found) {
  auto& t = model::umat_detail::table();
  const std::shared_lock<std::shared_mutex> lock(t.mutex);
  *found = (*noel >= 1 && static_cast<std::size_t>(*noel) <= t.points.size() &&
            !t.points[static_cast<std::size_t>(*noel - 1)].empty())
               ? 1
               : 0;
}

extern "C" void sffcal_umat_unsymmetric_part_(const int* noel, const int* npt, double* d,
                                              int* found) {
  using namespace model::umat_detail;
  auto& t = table();
  const std::shared_lock<std::shared_mutex> lock(t.mutex);
  *found = 0;
  if (*noel < 1 || *npt < 1) return;
  const auto e = static_cast<std::size_t>(*noel - 1), p = static_cast<std::size_t>(*npt - 1);
  if (e >= t.points.size() || p >= t.points[e].size() || !t.points[e][p]) return;
  const UnsymmetricPart& part = *t.points[e][p];
  for (int i = 0; i < kTensors; ++i) {
    d[i + kTensors * i] = 0.0;
    for (int j = i + 1; j < kTensors; ++j) {
      d[i + kTensors * j] = part[upper_index(i, j)];
      d[j + kTensors * i] = -part[upper_index(i, j)];
    }
  }
  *found = 1;
}

extern "C" int sffcal_umat_unsymmetric_wanted(void) {
  const char* symmetric = std::getenv("SFFCAL_CCX_SYMMETRIC_TANGENT");
  if (symmetric != nullptr && std::strcmp(symmetric, "1") == 0) return 0;
  if (symmetric != nullptr && *symmetric != '\0' && std::strcmp(symmetric, "0") != 0) {
    std::fprintf(stderr, "sffcal_umat: SFFCAL_CCX_SYMMETRIC_TANGENT must be 0 or 1, not \"%s\"\n",
                 symmetric);
    std::exit(2);
  }
  auto& t = model::umat_detail::table();
  const std::shared_lock<std::shared_mutex> lock(t.mutex);
  return t.any && !t.failed ? 1 : 0;
}
