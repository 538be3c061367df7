// Interoperability with meshio (Debian's python3-meshio 5.0): meshio reads a Tribos result
// (element type TETRA, all fields), and Tribos solves a scene whose mesh meshio wrote (blocks
// numbered from 0 without names, node sets only: the load and the contact surfaces come from
// node sets). Skipped, saying why, where python3-meshio (with python3-netcdf4) is not installed.
// Also ParaView's reader (VTK's vtkExodusIIReader, python3-vtk9, skipped without it).
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "RunCommand.hpp"
#include "TestPaths.hpp"

using tribos::test::quote;
using tribos::test::runCommand;

namespace {
/// A python3 that imports meshio and netCDF4 (meshio's Exodus backend, only recommended by
/// the Debian package): Debian's packages install for /usr/bin/python3, which a python3
/// earlier on PATH (pyenv, venv) may not see. Empty if there is none.
std::string pythonWithMeshio() {
  for (const char* python : {"/usr/bin/python3", "python3"})
    if (runCommand(std::string(python) + " -c 'import meshio, netCDF4'").status == 0) return python;
  return "";
}

class MeshioTest : public ::testing::Test {
 protected:
  void SetUp() override {
    python_ = pythonWithMeshio();
    if (python_.empty())
      GTEST_SKIP() << "python3-meshio or python3-netcdf4 is not installed (apt-get install python3-meshio python3-netcdf4)";
    dir_ = std::filesystem::temp_directory_path() / ("tribos_meshio_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override {
    if (!dir_.empty()) std::filesystem::remove_all(dir_);
  }
  /// Runs a python snippet that reads `exo` with meshio as `m`; returns its output and status.
  tribos::test::CommandResult readWithMeshio(const std::string& exo, const std::string& checks) {
    const auto script = dir_ / "read.py";
    std::ofstream(script) << "import sys\nimport meshio\nm = meshio.read(sys.argv[1])\n" << checks << "\n";
    return runCommand(python_ + " " + quote(script.string()) + " " + quote(exo));
  }
  std::string python_;
  std::filesystem::path dir_;
};
}  // namespace

TEST_F(MeshioTest, readsATribosResult) {
  const auto exo = (dir_ / "bricks.exo").string();
  const auto run = runCommand(std::string(TRIBOS_DRIVER) + " --input " +
                              quote(tribos::test::sourceDir() + "/input/two_bricks.xml") +
                              " --set Solver/Verbose=false --output " + quote(exo));
  ASSERT_EQ(run.status, 0) << run.output;
  const auto read = readWithMeshio(exo,
                                   "assert len(m.points) == 90, len(m.points)\n"
                                   "assert sum(len(c.data) for c in m.cells) == 160\n"
                                   "assert all(c.type == 'tetra' for c in m.cells)\n"
                                   "for name in ['displ_x', 'nodal_von_mises', 'contact_pressure', 'contact_gap']:\n"
                                   "    assert name in m.point_data, name\n"
                                   "for name in ['stress_zz', 'von_mises', 'subdomain']:\n"
                                   "    assert name in m.cell_data, name\n"
                                   "print('meshio read', len(m.points), 'points')");
  EXPECT_EQ(read.status, 0) << read.output;
}

TEST_F(MeshioTest, tribosSolvesAMeshWrittenByMeshio) {
  const auto root = tribos::test::sourceDir();
  const auto mesh = (dir_ / "two_boxes.exo").string(), summary = (dir_ / "summary.json").string(),
             result = (dir_ / "result.exo").string();
  auto run = runCommand(python_ + " " + quote(root + "/test/integration/meshio_two_boxes.py") + " " + quote(mesh));
  ASSERT_EQ(run.status, 0) << run.output;
  run = runCommand(std::string(TRIBOS_DRIVER) + " --input " + quote(root + "/test/integration/meshio_two_boxes.xml") +
                   " --set " + quote("Mesh/File=" + mesh) + " --summary " + quote(summary) + " --output " +
                   quote(result));
  ASSERT_EQ(run.status, 0) << run.output;
  std::ifstream in(summary);
  const auto j = nlohmann::json::parse(in);
  EXPECT_TRUE(j["converged"].get<bool>());
  EXPECT_GT(j["contact_nodes_paired"].get<int>(), 0);
  // The upper box's load (5 on its unit top face) goes through the contact to the clamp.
  EXPECT_NEAR(j["applied_load"][2].get<double>(), -5.0, 1e-12);
  EXPECT_NEAR(j["contact_force_on_master"][2].get<double>(), 5.0, 1e-8 * 5.0);
  EXPECT_NEAR(j["reactions"]["lower_bottom"][2].get<double>(), 5.0, 1e-8 * 5.0);
  EXPECT_LE(j["force_balance"].get<double>(), 1e-8);
  // And meshio reads the result of its own mesh back.
  const auto read = readWithMeshio(result, "assert 'von_mises' in m.cell_data\nassert len(m.cells) == 2");
  EXPECT_EQ(read.status, 0) << read.output;
}

// ParaView reads Exodus through VTK's vtkExodusIIReader: with Debian's python3-vtk9 the
// same reader checks that our blocks are tetrahedra to it too, with the fields and globals.
TEST(vtkExodusReader, readsATribosResultAsTetrahedra) {
  if (runCommand("/usr/bin/python3 -c 'import vtk'").status != 0)
    GTEST_SKIP() << "python3-vtk9 is not installed (apt-get install python3-vtk9): ParaView's reader not checked";
  const auto dir = std::filesystem::temp_directory_path() / ("tribos_vtk_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const auto exo = (dir / "bricks.exo").string(), script = (dir / "read.py").string();
  const auto run = runCommand(std::string(TRIBOS_DRIVER) + " --input " +
                              quote(tribos::test::sourceDir() + "/input/two_bricks.xml") +
                              " --set Solver/Verbose=false --output " + quote(exo));
  ASSERT_EQ(run.status, 0) << run.output;
  std::ofstream(script) << "import sys\nimport vtk\n"
                           "r = vtk.vtkExodusIIReader()\nr.SetFileName(sys.argv[1])\nr.UpdateInformation()\n"
                           "r.SetElementResultArrayStatus('von_mises', 1)\nr.SetPointResultArrayStatus('displ_', 1)\n"
                           "r.Update()\nit = r.GetOutput().NewIterator()\nit.InitTraversal()\ncells = 0\n"
                           "while not it.IsDoneWithTraversal():\n"
                           "    ds = it.GetCurrentDataObject()\n"
                           "    assert all(ds.GetCellType(c) == vtk.VTK_TETRA for c in range(ds.GetNumberOfCells()))\n"
                           "    assert ds.GetCellData().GetArray('von_mises') is not None\n"
                           "    assert ds.GetPointData().GetArray('displ_').GetNumberOfComponents() == 3\n"
                           "    cells += ds.GetNumberOfCells()\n"
                           "    it.GoToNextItem()\n"
                           "assert cells == 160, cells\n"
                           "names = [r.GetGlobalResultArrayName(i) for i in range(r.GetNumberOfGlobalResultArrays())]\n"
                           "assert 'force_balance' in names, names\n";
  const auto read = runCommand("/usr/bin/python3 " + quote(script) + " " + quote(exo));
  EXPECT_EQ(read.status, 0) << read.output;
  std::filesystem::remove_all(dir);
}
