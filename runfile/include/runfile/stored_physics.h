// The physics of a schema-1 run file, which stored only its config text (RunFile::metadata reads
// it so; public for the tests).
#pragma once

#include <string>

#include "runfile/run_file.h"

namespace runfile {

/// Reads [contact], [grains] and [engine] of a schema-1 config text. A key the text does not set
/// takes the value schema-1 programs (sffcal 0.1) gave it: these defaults are frozen with that
/// schema, whatever today's DEM defaults are. Throws std::runtime_error naming `source` when the
/// text is not TOML or a value is not a number.
RunPhysics physics_from_config_text(const std::string& text, const std::string& source);

}  // namespace runfile
