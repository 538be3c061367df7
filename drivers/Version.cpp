// `tribos --version`: what a bug report needs to say which build ran. The versions are those
// of the headers this binary was compiled against (Debian's packages), the revision is the
// one CMake saw at configure time (CMake configures again when HEAD moves).
#include <mpi.h>

#include <Kokkos_Macros.hpp>
#include <Trilinos_version.h>
#include <exodusII.h>
#include <metis.h>
#include <netcdf_meta.h>
#include <SuiteSparse_config.h>
#include <cholmod_core.h>

#include <sstream>

#include "CommandLine.hpp"

#ifndef TRIBOS_GIT_REVISION
#define TRIBOS_GIT_REVISION "unknown"
#endif

namespace tribos::driver {

namespace {
std::string dotted(int major, int minor, int patch) {
  return std::to_string(major) + "." + std::to_string(minor) + "." + std::to_string(patch);
}

std::string mpiVersion() {
#ifdef OMPI_MAJOR_VERSION
  return "Open MPI " + dotted(OMPI_MAJOR_VERSION, OMPI_MINOR_VERSION, OMPI_RELEASE_VERSION);
#else
  return "MPI " + dotted(MPI_VERSION, MPI_SUBVERSION, 0);
#endif
}

std::string compilerVersion() {
#if defined(__clang__)
  return "Clang " + std::string(__clang_version__);
#elif defined(__GNUC__)
  return "GCC " + dotted(__GNUC__, __GNUC_MINOR__, __GNUC_PATCHLEVEL__);
#else
  return "unknown compiler";
#endif
}
}  // namespace

std::string versionText() {
  std::ostringstream text;
  text << "tribos " << TRIBOS_GIT_REVISION << "\n"
       << "  Trilinos " << TRILINOS_VERSION_STRING << " (Tpetra, Amesos2, Belos, Teuchos)\n"
       << "  Kokkos " << dotted(KOKKOS_VERSION / 10000, KOKKOS_VERSION / 100 % 100, KOKKOS_VERSION % 100) << "\n"
       << "  METIS " << dotted(METIS_VER_MAJOR, METIS_VER_MINOR, METIS_VER_SUBMINOR) << "\n"
       << "  Exodus II API " << EX_API_VERS_NODOT / 100 << "." << EX_API_VERS_NODOT % 100 / 10 << EX_API_VERS_NODOT % 10
       << " (netCDF "
       << NC_VERSION << ")\n"
       << "  CHOLMOD " << dotted(CHOLMOD_MAIN_VERSION, CHOLMOD_SUB_VERSION, CHOLMOD_SUBSUB_VERSION) << " (SuiteSparse "
       << dotted(SUITESPARSE_MAIN_VERSION, SUITESPARSE_SUB_VERSION, SUITESPARSE_SUBSUB_VERSION) << ")\n"
       << "  " << mpiVersion() << "\n"
       << "  compiler " << compilerVersion() << ", C++ " << __cplusplus << "\n";
  return text.str();
}

}  // namespace tribos::driver
