// The ParaView export of a run file's snapshots (`sffcal vtk`): one VTU per snapshot and kind,
// and the collections (sffcal::write_pvd) that list them at the snapshots' times.
#include "dem/vtk_writer.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "runfile/run_file.h"
#include "sffcal/pvd.h"

namespace dem {
namespace {

std::string read_text(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

TEST(VtkExport, CollectionsListEverySnapshotAtItsTime) {
  const std::string reference =
      std::string(SFFCAL_SOURCE_DIR) + "/tests/data/reference/iso_dense_100kPa_reduced.h5";
  const runfile::RunFile run = runfile::RunFile::open(reference);
  const std::string folder = ::testing::TempDir() + "sffcal_vtk_export";
  std::filesystem::remove_all(folder);
  ASSERT_EQ(export_run_to_vtk(run, folder), run.num_snapshots());
  for (const char* kind : {"spheres", "contacts"}) {
    const std::string pvd = read_text(folder + "/" + kind + ".pvd");
    const std::regex dataset("<DataSet timestep=\"([^\"]+)\" file=\"([^\"]+)\"/>");
    std::vector<double> times;
    for (auto it = std::sregex_iterator(pvd.begin(), pvd.end(), dataset); it != std::sregex_iterator(); ++it) {
      times.push_back(std::stod((*it)[1]));
      EXPECT_TRUE(std::filesystem::exists(folder + "/" + (*it)[2].str())) << (*it)[2];
    }
    ASSERT_EQ(times.size(), static_cast<std::size_t>(run.num_snapshots())) << kind;
    for (int k = 0; k < run.num_snapshots(); ++k)
      EXPECT_NEAR(times[static_cast<std::size_t>(k)], run.read_snapshot(k).time, 1e-9 * run.read_snapshot(k).time);
  }
  // The spheres' VTU holds every sphere of its snapshot.
  const std::string vtu = read_text(folder + "/snapshot_0_spheres.vtu");
  EXPECT_NE(vtu.find("NumberOfPoints=\"" + std::to_string(run.read_snapshot(0).spheres.size()) + "\""),
            std::string::npos);
  EXPECT_THROW(sffcal::write_pvd(folder + "/bad.pvd", {"a.vtu"}, {}, "time"), std::invalid_argument);
  EXPECT_THROW(sffcal::write_pvd(folder + "/no/such/folder/x.pvd", {}, {}, "time"), std::runtime_error);
}

}  // namespace
}  // namespace dem
