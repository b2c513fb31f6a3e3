# All dependencies come from Debian 12 packages (the list in scripts/setup.sh).
find_package(Eigen3 3.4 REQUIRED NO_MODULE)
find_package(MPI REQUIRED COMPONENTS C CXX)
find_package(PkgConfig REQUIRED)
pkg_check_modules(PETSC REQUIRED IMPORTED_TARGET PETSc>=3.18)
pkg_check_modules(SLEPC REQUIRED IMPORTED_TARGET SLEPc>=3.18)
find_package(arpack-ng REQUIRED)
# libpetsc_real.so loads the Open MPI build of HDF5; link the same one to avoid two HDF5s in one
# process.
set(HDF5_PREFER_PARALLEL TRUE)
find_package(HDF5 REQUIRED COMPONENTS C)
find_package(tomlplusplus REQUIRED)
find_package(CLI11 REQUIRED)
if(MASTROM_BUILD_TESTS)
  find_package(GTest REQUIRED)
endif()
if(MASTROM_BUILD_BENCHMARKS)
  find_package(benchmark REQUIRED)
endif()
