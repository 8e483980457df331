// sffcal: the project's command-line front end. Each subcommand is one stage of the pipeline.
#include <CLI/CLI.hpp>

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>
#include <vector>

#include "dem_commands.h"
#include "finite_options.h"
#include "import_command.h"
#include "output_guard.h"
#include "sff_command.h"
#ifdef SFFCAL_HAVE_FE_CHECK
#include "fe_check_command.h"
#endif
#ifdef SFFCAL_HAVE_CALIBRATE
#include "calibrate_command.h"
#endif

int main(int argc, char** argv) {
  // OpenMP threads that wait by spinning take a shared machine's cores from other work, and lose
  // their own when another process holds one (two threads ran 14 times slower than one). GNU
  // OpenMP reads OMP_WAIT_POLICY when it loads, before main: where the user has not chosen, the
  // program runs itself again with passive waiting (bench/RESULTS.md, "Threads on a busy machine").
  if (std::getenv("OMP_WAIT_POLICY") == nullptr && setenv("OMP_WAIT_POLICY", "PASSIVE", 0) == 0)
    execv("/proc/self/exe", argv);  // returns only where it could not: then run as we are
  CLI::App app{"sffcal " SFFCAL_VERSION
               ": from grain-scale DEM to a calibrated fabric-based soil model"};
  app.require_subcommand(1);

  std::string config_path, out_path, specimen_path, run_path;
  bool force = false;  // overwrite an existing output file
  const char* force_help = "overwrite the output file if it exists (a run file is replaced only "
                           "once the new one is complete)";
  CLI::App* config = app.add_subcommand("config", "Print (or write) the default configuration");
  config->add_option("-o,--output", out_path, "file to write instead of printing");
  config->add_flag("--force", force, force_help);

  CLI::App* prepare = app.add_subcommand("prepare", "Prepare a specimen (insertion, optional "
                                                    "gravity deposition, isotropic compaction)");
  prepare->add_option("-c,--config", config_path, "TOML configuration")->required()->check(CLI::ExistingFile);
  prepare->add_option("-o,--output", out_path, "specimen file to write (HDF5)")->required();
  prepare->add_flag("--force", force, force_help);

  CLI::App* triaxial = app.add_subcommand("triaxial", "Drained triaxial compression of a specimen");
  triaxial->add_option("-c,--config", config_path, "TOML configuration")->check(CLI::ExistingFile);
  triaxial->add_option("-s,--specimen", specimen_path, "specimen file from 'prepare'")->check(CLI::ExistingFile);
  triaxial->add_option("-o,--output", out_path, "run file to write (HDF5)")->required();
  triaxial->add_flag("--force", force, force_help);
  bool resume = false;
  triaxial->add_flag("--resume", resume, "continue the run file from its last checkpoint "
                                         "(uses the config stored in it)");

  CLI::App* dem = app.add_subcommand("dem", "Prepare a specimen and run the triaxial test");
  dem->add_option("-c,--config", config_path, "TOML configuration")->required()->check(CLI::ExistingFile);
  dem->add_option("-o,--output", out_path, "run file to write (HDF5); the specimen goes to "
                                           "<output>.specimen.h5")->required();
  dem->add_flag("--force", force, "overwrite the run and specimen files if they exist (each "
                                  "replaced only once the new one is complete)");

  CLI::App* vtk = app.add_subcommand("vtk", "Export the snapshots of a run file for ParaView");
  vtk->add_option("run", run_path, "run file")->required()->check(CLI::ExistingFile);
  vtk->add_option("-o,--output", out_path, "folder for the VTU/PVD files")->required();

  std::string description_path;
  CLI::App* import = app.add_subcommand(
      "import", "Turn another code's run (YADE, LAMMPS, LIGGGHTS: dumps, a series table and "
                "import.toml; docs/import.md) into a run file");
  import->add_option("description", description_path, "import.toml")->required()->check(CLI::ExistingFile);
  import->add_option("-o,--output", out_path, "run file to write (HDF5)")->required();
  import->add_flag("--force", force, force_help);

  CLI::App* info = app.add_subcommand("info", "Summarise a run or specimen file");
  info->add_option("run", run_path, "run file")->required()->check(CLI::ExistingFile);

  std::vector<std::string> run_paths;
  CLI::App* sff = app.add_subcommand(
      "sff", "Stress-force-fabric analysis of every snapshot of run files (writes /analysis/sff, "
             "/analysis/sff_checks, /analysis/sff_rose and CSV copies; plot with "
             "scripts/plot_sff.py)");
  sffcal::SffCommandOptions sff_options;
  sff->add_option("runs", run_paths, "run files")->required()->check(CLI::ExistingFile);
  sff->add_option("-o,--output", sff_options.csv_folder,
                  "folder for the CSV tables (default: beside each run)");
  sff->add_option("--resamples", sff_options.resamples,
                  "bootstrap resamples per snapshot, 0 to skip")
      ->check(CLI::Range(0, 100000))
      ->capture_default_str();
  sff->add_option("--seed", sff_options.seed, "bootstrap seed")->capture_default_str();

#ifdef SFFCAL_HAVE_FE_CHECK
  sffcal::FeCheckOptions fe_check_options;
  CLI::App* fe_check = app.add_subcommand(
      "fe-check", "Element-level drained triaxial checks of any registered model (ACST, the "
                  "contact-network model, linear elasticity): "
                  "material-point driver, one Q1 hexahedron and a 2x2x4 mesh, against each other "
                  "and against DEM runs (docs/fe.md; plot with scripts/plot_fe_check.py)");
  fe_check->add_option("--parameters", fe_check_options.parameters_path,
                       "parameter file of any registered model (ACST; the contact-network model, "
                       "whose cases are the --dem runs' networks; any other, driven through the "
                       "model interface)")
      ->required()
      ->check(CLI::ExistingFile);
  fe_check->add_option("--dem", fe_check_options.dem_runs,
                       "DEM run files to compare with (sigma_3, e_0 from /series, initial fabric "
                       "from /analysis/sff)")
      ->check(CLI::ExistingFile);
  fe_check->add_option("--pressures", fe_check_options.pressures,
                       "confining pressures of the plain cases [Pa], comma separated")
      ->delimiter(',')
      ->capture_default_str();
  fe_check->add_option("--void-ratio", fe_check_options.void_ratio,
                       "initial void ratio of the plain cases")
      ->capture_default_str();
  fe_check->add_option("--max-strain", fe_check_options.max_strain, "final axial strain")
      ->capture_default_str();
  fe_check->add_option("--steps", fe_check_options.steps, "equal axial strain increments")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  fe_check->add_option("-o,--output", fe_check_options.output_folder, "output folder")
      ->capture_default_str();
  fe_check->add_option("--model-tol", fe_check_options.integration_tolerance,
                       "ACST: substep error tolerance of the model, driver and FE alike (0: one step per increment)")
      ->capture_default_str();
  fe_check->add_option("--a-cs", fe_check_options.a_cs,
                       "ACST: DEM fabric normalisation ||A|| at critical state (F = A_DEM/a_cs); "
                       "default: the parameter file's a_cs, else 0.827");
  fe_check->add_option("--dem-eta-tol", fe_check_options.dem_eta_tolerance,
                       "pass tolerance of the RMS q/p error against DEM")
      ->capture_default_str();
  fe_check->add_option("--dem-ev-tol", fe_check_options.dem_volumetric_tolerance,
                       "pass tolerance of the RMS volumetric strain error against DEM")
      ->capture_default_str();
  fe_check->add_option("--time-limit", fe_check_options.time_limit,
                       "wall-clock budget of each FE run (element, mesh) [s]; past it the run "
                       "stops with a message (0: none)")
      ->capture_default_str();
  bool fe_check_no_mesh = false;
  fe_check->add_flag("--no-mesh", fe_check_no_mesh, "skip the 2x2x4 mesh (the slow run)");
  fe_check->add_flag("-v,--verbose", fe_check_options.verbose, "print the Newton logs");

  // The start of umat-cards and point (fe_model/model_start.h): a DEM run's, or a plain specimen's.
  // A plain specimen's flags and --dem exclude each other, and --a-cs needs --dem: nothing given
  // is silently ignored.
  const auto add_start_options = [](CLI::App& command, fe_model::StartOptions& start) {
    CLI::Option* dem_run = command.add_option(
        "--dem", start.dem_run,
        "start from this DEM run (sigma_3, e_0 and the model's initial state, as fe-check takes "
        "them); without it, a plain specimen");
    dem_run->check(CLI::ExistingFile);
    command.add_option("--pressure", start.confining_pressure, "plain specimen: sigma_3 [Pa]")
        ->capture_default_str()
        ->excludes(dem_run);
    command.add_option("--void-ratio", start.void_ratio, "plain specimen: e_0")
        ->capture_default_str()
        ->excludes(dem_run);
    command.add_option("--a-cs", start.a_cs,
                       "ACST with --dem: DEM fabric normalisation (default: the parameter file's, "
                       "else 0.827)")
        ->needs(dem_run);
  };
  fe_model::UmatCardOptions cards_options;
  std::string cards_elements;
  CLI::App* cards = app.add_subcommand(
      "umat-cards", "Print the input-deck cards of a model's UMAT for CalculiX or Abaqus: "
                    "*MATERIAL, *USER MATERIAL (PROPS from the parameter file and the start, "
                    "eight a line, each named in a comment), *DEPVAR and *INITIAL CONDITIONS "
                    "(docs/fe.md, \"CalculiX\")");
  cards->add_option("--parameters", cards_options.parameters_path,
                    "parameter file of any registered model")
      ->required()
      ->check(CLI::ExistingFile);
  add_start_options(*cards, cards_options.start);
  cards->add_option("--elements", cards_elements,
                    "elements whose integration points get the initial stress, e.g. 1-27 "
                    "(none: no *INITIAL CONDITIONS card)");
  cards->add_option("--points", cards_options.integration_points,
                    "integration points per element (C3D8, C3D20R: 8; C3D8R: 1)")
      ->capture_default_str();
  cards->add_option("--client", cards_options.client,
                    "calculix (material ABAQUS<NAME>: CalculiX strips ABAQUS before its UMAT sees "
                    "the name) or abaqus")
      ->check(CLI::IsMember({"calculix", "abaqus"}))
      ->capture_default_str();

  fe_model::PointPathOptions point_options;
  std::string point_drainage = "drained";
  CLI::App* point = app.add_subcommand(
      "point", "Drive one material point of any registered model along a triaxial path, drained or "
               "undrained, in compression or extension, from a DEM run's start or a plain "
               "specimen; write its curve as a CSV (docs/fe.md, \"One material point\")");
  point->add_option("--parameters", point_options.parameters_path,
                    "parameter file of any registered model")
      ->required()
      ->check(CLI::ExistingFile);
  add_start_options(*point, point_options.start);
  point->add_option("--drainage", point_drainage,
                    "drained (sigma_3 held) or undrained (constant volume)")
      ->check(CLI::IsMember({"drained", "undrained"}))
      ->capture_default_str();
  point->add_option("--max-strain", point_options.axial_strain_end,
                    "end axial strain (negative: extension)")
      ->capture_default_str();
  point->add_option("--steps", point_options.steps, "equal axial strain increments")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  point->add_option("-o,--output", out_path, "CSV file to write")->required();
  point->add_flag("--force", force, force_help);
#endif

#ifdef SFFCAL_HAVE_CALIBRATE
  std::vector<std::string> calibrate_runs;
  sffcal::CalibrateCommandOptions calibrate_options;
  CLI::App* calibrate = app.add_subcommand(
      "calibrate", "Fit the ACST model to DEM run files: critical state line, elasticity, fabric "
                   "evolution, hardening/dilatancy, then all tests jointly (Ceres); also the SFF "
                   "strength relation (docs/calibration.md; plot with scripts/plot_calibration.py). "
                   "--model network fits the contact-network model instead "
                   "(docs/network-model.md; plot with scripts/plot_network.py), --model NAME any "
                   "other registered model over its description (docs/model-interface.md)");
  calibrate->add_option("runs", calibrate_runs, "run files with an /analysis/sff table")
      ->required()
      ->check(CLI::ExistingFile);
  calibrate->add_option("-o,--output", calibrate_options.output_folder,
                        "folder for parameters.json, the curves and summary.md")
      ->required();
  sffcal::add_calibrate_options(*calibrate, calibrate_options);
#endif

  CLI11_PARSE(app, argc, argv);
  try {
    sffcal::refuse_non_finite_options(app);
    // Outputs are checked before any work starts (an existing file needs --force; an output is
    // never an input; its folder must be writable).
    if (config->parsed()) {
      if (!out_path.empty()) sffcal::check_new_output_file(out_path, {}, force);
      return sffcal::print_default_config(out_path);
    }
    if (prepare->parsed()) {
      sffcal::check_new_run_file(out_path, {config_path}, force, false);
      return sffcal::prepare_command(config_path, sffcal::RunFileTarget(out_path, false));
    }
    if (triaxial->parsed()) {
      if (resume) return sffcal::resume_command(out_path);
      if (config_path.empty() || specimen_path.empty())
        throw std::invalid_argument("triaxial needs --config and --specimen (or --resume)");
      sffcal::check_new_run_file(out_path, {config_path, specimen_path}, force, true);
      return sffcal::triaxial_command(config_path, specimen_path,
                                      sffcal::RunFileTarget(out_path, true));
    }
    if (dem->parsed()) {
      sffcal::check_new_run_file(out_path, {config_path}, force, true);
      sffcal::check_new_run_file(out_path + ".specimen.h5", {config_path}, force, false);
      return sffcal::dem_command(config_path, sffcal::RunFileTarget(out_path + ".specimen.h5", false),
                                 sffcal::RunFileTarget(out_path, true));
    }
    if (vtk->parsed()) {
      sffcal::check_output_folder(out_path);
      return sffcal::vtk_command(run_path, out_path);
    }
    if (import->parsed()) {
      sffcal::check_new_run_file(out_path, {description_path}, force, false);
      return sffcal::import_command(description_path, sffcal::RunFileTarget(out_path, false));
    }
    if (info->parsed()) return sffcal::info_command(run_path);
    if (sff->parsed()) {
      if (!sff_options.csv_folder.empty()) sffcal::check_output_folder(sff_options.csv_folder);
      return sffcal::sff_command(run_paths, sff_options);
    }
#ifdef SFFCAL_HAVE_CALIBRATE
    if (calibrate->parsed()) {
      std::string command_line;
      for (int k = 0; k < argc; ++k) command_line += (k ? " " : "") + std::string(argv[k]);
      calibrate_options.given = sffcal::given_settings(*calibrate);
      sffcal::check_output_folder(calibrate_options.output_folder);
      std::vector<std::string> inputs = calibrate_runs;
      inputs.insert(inputs.end(), calibrate_options.held_out.begin(), calibrate_options.held_out.end());
      if (!calibrate_options.settings.start_file.empty())
        inputs.push_back(calibrate_options.settings.start_file);
      sffcal::check_inputs_outside(calibrate_options.output_folder, inputs);
      return sffcal::calibrate_command(calibrate_runs, calibrate_options, command_line);
    }
#endif
#ifdef SFFCAL_HAVE_FE_CHECK
    if (fe_check->parsed()) {
      fe_check_options.mesh = !fe_check_no_mesh;
      sffcal::check_output_folder(fe_check_options.output_folder);
      std::vector<std::string> inputs = fe_check_options.dem_runs;
      inputs.push_back(fe_check_options.parameters_path);
      sffcal::check_inputs_outside(fe_check_options.output_folder, inputs);
      return sffcal::fe_check_command(fe_check_options);
    }
    if (point->parsed()) {
      std::vector<std::string> inputs = {point_options.parameters_path};
      if (!point_options.start.dem_run.empty()) inputs.push_back(point_options.start.dem_run);
      sffcal::check_new_output_file(out_path, inputs, force);
      point_options.drainage = model::parse_drainage(point_drainage);
      return sffcal::point_command(point_options, out_path);
    }
    if (cards->parsed()) {
      if (!cards_elements.empty())
        cards_options.elements = sffcal::parse_element_list(cards_elements);
      return sffcal::umat_cards_command(cards_options);
    }
#endif
  } catch (const std::exception& e) {
    std::fprintf(stderr, "sffcal: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
