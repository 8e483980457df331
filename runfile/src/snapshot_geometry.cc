#include "runfile/snapshot_geometry.h"

#include <cmath>
#include <map>
#include <vector>

#include "sffcal/clump_geometry.h"

namespace runfile {

double solid_volume(const Snapshot& s) {
  std::map<std::int64_t, std::vector<std::size_t>> spheres_of;
  for (std::size_t k = 0; k < s.spheres.size(); ++k) spheres_of[s.sphere_body[k]].push_back(k);
  double total = 0.0;
  for (const auto& [body, list] : spheres_of) {
    const auto& a = s.spheres[list.front()];
    double distance = 0.0;
    if (list.size() == 2) {
      const auto& b = s.spheres[list.back()];
      distance = std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
                           (a[2] - b[2]) * (a[2] - b[2]));
    }
    total += sffcal::two_sphere_union_volume(a[3], distance);
  }
  return total;
}

}  // namespace runfile
