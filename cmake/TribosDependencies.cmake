# Third-party dependencies, wrapped once in INTERFACE targets (Trilinos 13.2 as Debian
# ships it has no namespaced targets and its imported targets carry no include dirs).

find_package(MPI REQUIRED COMPONENTS C CXX)
find_package(OpenMP REQUIRED COMPONENTS CXX)

find_package(Trilinos 13.2 REQUIRED COMPONENTS Tpetra Amesos2 Belos Teuchos Kokkos KokkosKernels
  PATHS /usr/lib/x86_64-linux-gnu/cmake/Trilinos)
add_library(tribos_trilinos INTERFACE)
target_include_directories(tribos_trilinos SYSTEM INTERFACE ${Trilinos_INCLUDE_DIRS} ${Trilinos_TPL_INCLUDE_DIRS})
target_link_libraries(tribos_trilinos INTERFACE ${Trilinos_LIBRARIES} ${Trilinos_TPL_LIBRARIES} MPI::MPI_CXX)

find_path(METIS_INCLUDE_DIR metis.h REQUIRED)
find_library(METIS_LIBRARY metis REQUIRED)
add_library(tribos_metis INTERFACE)
target_include_directories(tribos_metis SYSTEM INTERFACE ${METIS_INCLUDE_DIR})
target_link_libraries(tribos_metis INTERFACE ${METIS_LIBRARY})

# exoIIv2c already links Debian's MPI netCDF/HDF5 stack: do not add -lnetcdf here.
find_path(EXODUS_INCLUDE_DIR exodusII.h REQUIRED)
find_library(EXODUS_LIBRARY exoIIv2c REQUIRED)
add_library(tribos_exodus INTERFACE)
target_include_directories(tribos_exodus SYSTEM INTERFACE ${EXODUS_INCLUDE_DIR})
target_link_libraries(tribos_exodus INTERFACE ${EXODUS_LIBRARY})

find_package(nlohmann_json 3 REQUIRED)
