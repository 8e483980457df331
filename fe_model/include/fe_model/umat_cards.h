// The input-deck cards of a model's UMAT (docs/fe.md, "CalculiX"): *MATERIAL with *USER MATERIAL
// (PROPS, eight a line), *DEPVAR and *INITIAL CONDITIONS, TYPE=STRESS, from a parameter file and a
// start (a DEM run's, or a plain specimen's: model_start.h), so that nobody assembles PROPS by hand.
// deal.II-free (fe_model_acst); `sffcal umat-cards` prints what umat_cards returns.
#ifndef FE_MODEL_UMAT_CARDS_H_
#define FE_MODEL_UMAT_CARDS_H_

#include <string>
#include <vector>

#include "fe_model/model_start.h"

namespace fe_model {

struct UmatCardOptions {
  std::string parameters_path;  ///< a parameter file of any registered model
  StartOptions start;           ///< a DEM run's start, or a plain specimen's
  /// Elements whose integration points get the initial stress (-sigma_3 on the diagonal, tension
  /// positive); empty: no *INITIAL CONDITIONS card.
  std::vector<int> elements;
  int integration_points = 8;  ///< per element (C3D8: 8, C3D20R: 8, C3D8R: 1); CalculiX only
                               ///< (Abaqus' card has one line per element)
  /// "calculix": the material named ABAQUS<UMAT name> (CalculiX calls its UMAT for names that
  /// begin with ABAQUS and passes the rest); "abaqus": named <UMAT name>.
  std::string client = "calculix";
};

/// The cards, with comments naming every PROPS entry. Throws std::invalid_argument naming a bad
/// option or a start the model cannot carry (its initial_state refuses it), std::runtime_error for
/// an unreadable file.
std::string umat_cards(const UmatCardOptions& options);

}  // namespace fe_model

#endif  // FE_MODEL_UMAT_CARDS_H_
