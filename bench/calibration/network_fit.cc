// The contact-network model (docs/network-model.md) fitted to DEM tests' micro histories, then
// each test predicted on its own loading path (issue 19, point 2). A test is a paper-size run's
// committed reduced CSV pair by name (bench/reference/<name>_series.csv and <name>_sff.csv) or a
// run file (.h5) analysed by `sffcal sff`.
//
// usage: network_fit FITTED... [--hold-out HELD...] [--threads N] [--starts N] [--out DIR]
//   e.g. build/bench/network_fit dense_100kPa loose_200kPa --hold-out dense_300kPa
// Prints the fitted parameters and, per test, the RMS errors along the DEM's strain path (the
// fit's objective) and of the prediction; --out writes <DIR>/parameters.json (the parameter file
// of docs/network-model.md, with the fit's record) and <DIR>/<name>_network.csv per test (the
// prediction at the DEM's rows and snapshots) for plotting. DIR must not exist yet.
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "calibration/network_fit.h"
#include "reference_tests.h"

namespace {

void write_curve(const std::string& path, const calibration::network::Curve& c) {
  std::ofstream out(path);
  out << "axial_strain,volumetric_strain,void_ratio,p,q,eta,coordination,lambda,a_c,a_n,a_t,"
         "dem_row,dem_snapshot\n";
  out.precision(10);
  for (std::size_t k = 0; k < c.axial_strain.size(); ++k)
    out << c.axial_strain[k] << ',' << c.volumetric_strain[k] << ',' << c.void_ratio[k] << ','
        << c.p[k] << ',' << c.q[k] << ',' << c.eta[k] << ',' << c.coordination[k] << ','
        << c.lambda[k] << ',' << c.a_c[k] << ',' << c.a_n[k] << ',' << c.a_t[k] << ','
        << c.row[k] << ',' << c.snapshot[k] << '\n';
  if (!out) throw std::runtime_error("cannot write " + path);
}

}  // namespace

int main(int argc, char** argv) {
  namespace net = calibration::network;
  try {
    std::vector<std::string> fitted, held;
    std::string out_dir;
    net::FitOptions options;
    options.threads = 2;
    options.starts = 4;
    bool holding = false;
    for (int k = 1; k < argc; ++k) {
      const std::string a = argv[k];
      if (a == "--hold-out") {
        holding = true;
      } else if (a == "--threads" && k + 1 < argc) {
        options.threads = std::atoi(argv[++k]);
      } else if (a == "--starts" && k + 1 < argc) {
        options.starts = std::atoi(argv[++k]);
      } else if (a == "--out" && k + 1 < argc) {
        out_dir = argv[++k];
      } else {
        (holding ? held : fitted).push_back(a);
      }
    }
    if (fitted.empty()) {
      std::fprintf(stderr, "usage: network_fit FITTED... [--hold-out HELD...] "
                           "[--threads N] [--starts N] [--out DIR]\n");
      return 2;
    }
    if (!out_dir.empty()) {
      if (std::filesystem::exists(out_dir))
        throw std::runtime_error("output folder " + out_dir + " exists (not overwritten)");
      std::filesystem::create_directories(out_dir);
    }
    const std::vector<calibration::TestData> fit_tests = bench::read_reference_tests(fitted),
                                              held_tests = bench::read_reference_tests(held);
    const net::FitResult result = net::fit(fit_tests, net::default_start(), options);
    std::printf("# Contact-network model fitted to %zu test(s)\n\n%s\n", fit_tests.size(),
                result.report.c_str());
    std::printf("start %d of %zu won; final costs:", result.start, result.start_costs.size());
    for (double c : result.start_costs) std::printf(" %.1f", c);
    std::printf("\n\n");
    std::printf("| parameter | value |\n|---|---|\n");
    const auto x = net::to_array(result.parameters);
    for (int i = 0; i < net::kNumParameters; ++i)
      std::printf("| %s | %.6g |\n", net::parameter_names()[i], x[i]);
    std::printf("\n| test | role | path: RMS q/p | Z | Lambda (rel.) | a_c | a_n | a_t | "
                "predicted: RMS q/p | RMS eps_v | RMS p/p0 | Z | Lambda (rel.) | a_c | a_n | a_t |\n");
    std::printf("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
    auto row = [&](const calibration::TestData& t, const char* role) {
      const net::Curve along = net::follow_strain_path(result.parameters, t, options);
      const net::Curve predicted = net::predict(result.parameters, t, options);
      const net::Errors a = net::compare(along, t), b = net::compare(predicted, t);
      std::printf("| %s | %s | %.3f | %.3f | %.3f | %.3f | %.3f | %.4f |", t.name.c_str(), role,
                  a.eta, a.coordination, a.lambda, a.a_c, a.a_n, a.a_t);
      if (predicted.axial_strain.size() < 2)
        std::printf(" stopped: %s | | | | | | | |\n", predicted.message.c_str());
      else
        std::printf(" %.3f%s | %.4f | %.3f | %.3f | %.3f | %.3f | %.3f | %.4f |\n", b.eta,
                    predicted.complete ? "" : " (to the stop)", b.volumetric, b.p_ratio,
                    b.coordination, b.lambda, b.a_c, b.a_n, b.a_t);
      if (!predicted.complete && predicted.axial_strain.size() >= 2)
        std::printf("(%s: %s)\n", t.name.c_str(), predicted.message.c_str());
      if (!out_dir.empty()) write_curve(out_dir + "/" + t.name + "_network.csv", predicted);
    };
    for (const auto& t : fit_tests) row(t, "fitted");
    for (const auto& t : held_tests) row(t, "held back");
    if (!out_dir.empty()) {
      // The tests as given on the command line, as JSON strings.
      auto list = [](const std::vector<std::string>& names) {
        std::string out;
        for (const std::string& n : names) {
          out += out.empty() ? "\"" : ", \"";
          for (char ch : n) {
            if (ch == '"' || ch == '\\') out += '\\';
            out += ch;
          }
          out += '"';
        }
        return out;
      };
      std::string record = "{\"fit\": {\"tests\": [" + list(fitted) + "], \"held_back\": [" +
                           list(held);
      record += "], \"final_cost\": " + std::to_string(result.final_cost) +
                ", \"starts\": " + std::to_string(options.starts) +
                ", \"seed\": " + std::to_string(options.seed) + "}}";
      net::write_parameters_json(result.parameters, net::kDemYoungsModulus,
                                 out_dir + "/parameters.json", record);
    }
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "network_fit: %s\n", e.what());
    return 1;
  }
}
