// Numeric options that are not finite numbers ("nan", "inf", 1e999), refused by name before any
// work: CLI11's range checks compare, and NaN passes every comparison.
#pragma once

namespace CLI {
class App;
}

namespace sffcal {

/// Throws std::invalid_argument naming the first option of `app` or of a parsed subcommand whose
/// value (or one of its comma-separated values) reads whole as a number that is not finite.
void refuse_non_finite_options(const CLI::App& app);

}  // namespace sffcal
