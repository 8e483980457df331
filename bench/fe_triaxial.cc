// Times one whole element-level triaxial check of the ACST model (issue 6): drained compression
// at 100 kPa to 30 % axial strain by the material-point driver, one Q1 hexahedron and the 2x2x4
// mesh (what `sffcal fe-check` runs per case). Prints a table: wall time, steps, Newton
// iterations, cuts, and the check errors.
//
//   fe_triaxial [PARAMS.json] [STEPS] [--no-mesh]
//   (default: examples/acst_toyoura.json, 100 steps; e_0 = 0.8, isotropic fabric)
#include <cstdio>
#include <cstring>
#include <string>

#include "fe_model/acst_check.h"

namespace {

void print_row(const fe_model::Curve& curve, unsigned int steps, unsigned int points) {
  // Material updates: one per point per Newton assembly; a converged step of k iterations
  // assembles k + 1 times (failed attempts of cut steps not counted: approximate when cuts > 0).
  const double assemblies =
      static_cast<double>(curve.newton_iterations) + static_cast<double>(curve.points.size() - 1);
  const double per_update = points > 0 ? 1e3 * curve.wall_seconds / (assemblies * points) : 0.0;
  std::printf("| %-16s | %9s | %5zu/%u | %6d | %4d | %8.2f | %8.3f |\n", curve.label.c_str(),
              curve.completed ? "yes" : "NO", curve.points.size() - 1, steps,
              curve.newton_iterations, curve.cuts, curve.wall_seconds, per_update);
}

}  // namespace

int main(int argc, char** argv) {
  std::string parameters_path = std::string(SFFCAL_SOURCE_DIR) + "/examples/acst_toyoura.json";
  unsigned int steps = 100;
  bool mesh = true;
  int positional = 0;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--no-mesh") == 0) {
      mesh = false;
    } else if (positional++ == 0) {
      parameters_path = argv[i];
    } else {
      steps = static_cast<unsigned int>(std::stoul(argv[i]));
    }
  }
  try {
    const model::acst::Parameters<double> parameters =
        model::acst::read_parameters_json(parameters_path);
    fe_model::AcstSpecimen specimen;  // 100 kPa, e_0 = 0.8, isotropic
    fe_model::TriaxialLoading loading;
    loading.axial_strain_end = 0.3;
    loading.n_steps = steps;
    std::printf("fe_triaxial: %s, sigma_3 = 100 kPa, e_0 = %.2f, to axial strain %.2f in %u "
                "steps, integration tolerance %.0e\n\n",
                parameters_path.c_str(), specimen.void_ratio, loading.axial_strain_end, steps,
                loading.integration.tolerance);
    std::printf("| run              | completed | steps   | Newton | cuts | wall [s] | ms/update |\n");
    std::printf("|---|---|---|---|---|---|---|\n");

    const fe_model::Curve driver = fe_model::run_acst_driver_triaxial(parameters, specimen, loading);
    print_row(driver, steps, 0);
    const fe_model::Curve element =
        fe_model::run_acst_fe_triaxial(parameters, specimen, loading, {});
    fe_model::Curve renamed = element;
    renamed.label = "element (8 pts)";
    print_row(renamed, steps, 8);
    fe_model::Curve meshed;
    if (mesh) {
      fe_model::TriaxialMeshOptions options;
      options.cells_x = options.cells_y = 2;
      options.cells_z = 4;
      meshed = fe_model::run_acst_fe_triaxial(parameters, specimen, loading, options);
      fe_model::Curve shown = meshed;
      shown.label = "mesh 2x2x4 (128)";
      print_row(shown, steps, 128);
    }
    const double total =
        driver.wall_seconds + element.wall_seconds + (mesh ? meshed.wall_seconds : 0.0);
    std::printf("\nwhole check: %.2f s\n", total);
    const fe_model::PathError a = fe_model::compare_paths(element, driver);
    std::printf("element vs driver: max rel. error q %.2e, eps_v %.2e\n", a.q, a.volumetric_strain);
    if (mesh) {
      const fe_model::PathError b = fe_model::compare_paths(meshed, element);
      std::printf("mesh vs element:   max rel. error q %.2e, eps_v %.2e\n", b.q,
                  b.volumetric_strain);
    }
    if (!element.points.empty())
      std::printf("element at eps_a = %.3f: q/p = %.4f, eps_v = %.4f, e = %.4f, F:n_c = %.4f\n",
                  element.points.back().axial_strain, element.points.back().eta(),
                  element.points.back().volumetric_strain, element.points.back().void_ratio,
                  element.points.back().fabric_invariant);
    return driver.completed && element.completed && (!mesh || meshed.completed) ? 0 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "fe_triaxial: error: %s\n", e.what());
    return 1;
  }
}
