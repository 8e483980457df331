// A deal.II program of its own, with the ACST model of an installed sffcal at every quadrature
// point: a drained triaxial compression of a cylinder-free box specimen (one eighth, by
// symmetry) with rough platens, stepped by fe_model::Solid. Prints the global q/p and the bulge
// of the outer face, and writes external_fe.vtu.
//
//   external_fe PARAMETERS.json [axial_strain_end=0.05] [steps=20]
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/tria.h>

#include <cstdio>
#include <cstdlib>
#include <exception>

#include "model/acst_model.h"  // sffcal::model
#include "fe_model/acst_material.h"   // sffcal::fe_model
#include "fe_model/solid.h"

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: external_fe PARAMETERS.json [axial_strain_end] [steps]\n");
    return 2;
  }
  const double strain_end = argc > 2 ? std::atof(argv[2]) : 0.05;
  const int steps = argc > 3 ? std::atoi(argv[3]) : 20;
  try {
    const model::acst::Parameters<double> parameters = model::acst::read_parameters_json(argv[1]);
    fe_model::AcstInitialState initial;
    initial.void_ratio = 0.8;
    const fe_model::AcstMaterial material(parameters, initial);

    const double L = 0.025, H = 0.05, p0 = 100e3;  // [m], [Pa]
    dealii::Triangulation<3> mesh;
    dealii::GridGenerator::subdivided_hyper_rectangle(mesh, {3, 3, 6}, dealii::Point<3>(0, 0, 0),
                                                      dealii::Point<3>(L, L, H), true);
    fe_model::Solid solid(mesh, material, -p0 * dealii::unit_symmetric_tensor<3>());
    auto zero = [](const dealii::Point<3>&, double) { return dealii::Tensor<1, 3>(); };
    solid.add_displacement_condition({0, {{true, false, false}}, zero});  // x = 0: symmetry
    solid.add_displacement_condition({2, {{false, true, false}}, zero});  // y = 0: symmetry
    solid.add_displacement_condition({4, {{false, false, true}}, zero});  // z = 0: symmetry
    solid.add_displacement_condition(                                     // z = H: rough platen
        {5, {{true, true, true}}, [&](const dealii::Point<3>&, double load) {
           dealii::Tensor<1, 3> u;
           u[2] = -load * strain_end * H;
           return u;
         }});
    auto confining = [p0](const dealii::Point<3>&, const dealii::Tensor<1, 3>& n, double) {
      return -p0 * n;
    };
    solid.add_traction_condition({1, confining});
    solid.add_traction_condition({3, confining});
    solid.setup();

    for (int step = 1; step <= steps; ++step) {
      const fe_model::StepReport report = solid.advance_to(static_cast<double>(step) / steps);
      if (!report.converged) {
        std::fprintf(stderr, "external_fe: step %d: %s\n", step, report.message.c_str());
        return 1;
      }
      const fe_model::VolumeAverages a = solid.volume_averages();
      const double p = -dealii::trace(a.stress) / 3.0;
      const double q = -a.stress[2][2] + 0.5 * (a.stress[0][0] + a.stress[1][1]);
      std::printf("step %2d  axial strain %.4f  q/p %.4f  volumetric strain %+.5f\n", step,
                  -a.strain[2][2], q / p, -dealii::trace(a.strain));
    }
    solid.write_vtu("external_fe.vtu");
  } catch (const std::exception& e) {
    std::fprintf(stderr, "external_fe: %s\n", e.what());
    return 1;
  }
  return 0;
}
