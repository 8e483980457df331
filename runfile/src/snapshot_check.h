// What every reader of a snapshot may trust: its arrays agree with each other and hold finite
// numbers (an edited or damaged file is refused by name before any analysis sees it).
#pragma once

#include <cstddef>

#include "runfile/run_file.h"

namespace runfile {

/// Throws std::runtime_error naming the first record at fault: `sphere_values` (the length of the
/// flat spheres dataset) not 4 per sphere, a sphere_body entry per sphere missing, a body id
/// repeated or outside 0..N-1, a sphere or contact referring to a body the snapshot does not hold
/// or to a wall it does not have, a wall axis outside 0..2, a radius or diameter that is not
/// positive, or any number that is not finite; a periodic cell (`cell_values` the length of its
/// flat dataset, 0 where it has none) that is not 2 x 3, not finite, has a corner not above the
/// other or comes with walls.
void check_snapshot(const Snapshot& s, std::size_t sphere_values, std::size_t cell_values = 0);

}  // namespace runfile
