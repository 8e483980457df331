// The fe-check subcommand: fe_model::run_fe_check (fe_model/fe_check.h, docs/fe.md) with its
// progress and its pass/fail table on stdout; umat-cards, the UMAT's input-deck cards
// (fe_model/umat_cards.h); and point, one material point along a triaxial path
// (fe_model/point_path.h). main.cc parses the flags into the options.
#ifndef SFFCAL_FE_CHECK_COMMAND_H_
#define SFFCAL_FE_CHECK_COMMAND_H_

#include <string>
#include <vector>

#include "fe_model/fe_check.h"
#include "fe_model/point_path.h"
#include "fe_model/umat_cards.h"

namespace sffcal {

using FeCheckOptions = fe_model::FeCheckOptions;

/// Runs the checks; returns 0 if every check passed, 2 if only FE-vs-DEM checks failed, 1 if a
/// verification check failed or a run did not complete. Throws for unreadable input files.
int fe_check_command(const FeCheckOptions& options);

/// Element numbers from "1-8,12,20-27"; throws std::invalid_argument naming a bad part.
std::vector<int> parse_element_list(const std::string& text);

/// Prints fe_model::umat_cards on stdout; returns 0.
int umat_cards_command(const fe_model::UmatCardOptions& options);

/// Runs fe_model::run_point_path, writes its CSV to `output` and prints the start and the end;
/// returns 0 where the path was completed, 1 where an update stopped it (the CSV holds the points
/// reached and says why).
int point_command(const fe_model::PointPathOptions& options, const std::string& output);

}  // namespace sffcal

#endif  // SFFCAL_FE_CHECK_COMMAND_H_
