// What a snapshot's spheres say about its bodies: their solid volume, defined once for every
// reader (the SFF analysis's void ratio, sff/src/run_snapshot.cc; the import's series,
// dem_import/src/import_run.cc).
#pragma once

#include "runfile/run_file.h"

namespace runfile {

/// The total volume of the snapshot's bodies [m^3]: each the union of its one or two equal spheres
/// (sffcal/clump_geometry.h), the centre distance taken from the two spheres' positions.
double solid_volume(const Snapshot& snapshot);

}  // namespace runfile
