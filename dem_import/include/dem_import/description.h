// import.toml: what another code's run is and how its files are laid out (docs/import.md). Every
// key of [source], [physics] and [test] is required (but [test] boundary, a periodic cell unless
// it says "walls", which the dumps' box must agree with), so that nothing the source did not state
// is guessed; an unknown key is refused (a misspelt one would otherwise be ignored).
#pragma once

#include <map>
#include <string>

#include "runfile/run_file.h"

namespace dem_import {

/// The programs whose runs sffcal imports.
inline constexpr const char* kSourcePrograms[] = {"yade", "lammps", "liggghts"};

struct ImportDescription {
  std::string path;  ///< of import.toml
  std::string text;  ///< its text, kept in the run file
  std::string program, version;
  std::string atoms_path, contacts_path, series_path;  ///< resolved against import.toml's folder
  runfile::RunPhysics physics;
  std::string kind;               ///< the run file's kind, e.g. "triaxial"
  /// [test] boundary: false, a periodic cell ("periodic", the default); true, a box between six
  /// planar walls ("walls"), whose positions the series gives and whose forces the atoms dump.
  bool walls = false;
  runfile::LoadingRecord loading;
  bool stress_tension_positive = false;  ///< the series' stress sign
  std::string stress_definition;         ///< how the source computed it, in words
  bool force_on_atom1 = false;           ///< the contacts' force acts on atom 1 (else atom 2)
  /// The files' column names where they differ from the roles' names, per file: role -> name.
  std::map<std::string, std::string> atoms_columns, contacts_columns, series_columns;

  /// The name of `role`'s column in a file's `columns` map (the role's own name by default).
  static const std::string& column(const std::map<std::string, std::string>& columns,
                                   const std::string& role);
};

/// Throws std::invalid_argument naming the file and the key: a syntax error, a missing or unknown
/// key, a value of the wrong type, a physical constant that is not positive (friction and wall
/// friction may be zero) or a source program not in kSourcePrograms.
ImportDescription read_description(const std::string& path);

}  // namespace dem_import
