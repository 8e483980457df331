// The fe-check subcommand: fe_model::run_fe_check (fe_model/fe_check.h, docs/fe.md) with its
// progress and its pass/fail table on stdout. main.cc parses the flags into the options.
#ifndef SFFCAL_FE_CHECK_COMMAND_H_
#define SFFCAL_FE_CHECK_COMMAND_H_

#include "fe_model/fe_check.h"

namespace sffcal {

using FeCheckOptions = fe_model::FeCheckOptions;

/// Runs the checks; returns 0 if every check passed, 2 if only FE-vs-DEM checks failed, 1 if a
/// verification check failed or a run did not complete. Throws for unreadable input files.
int fe_check_command(const FeCheckOptions& options);

}  // namespace sffcal

#endif  // SFFCAL_FE_CHECK_COMMAND_H_
