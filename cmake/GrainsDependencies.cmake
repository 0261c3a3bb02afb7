# Every dependency is a Debian package (see .ci/setup for the list).
find_package(Eigen3 3.4 REQUIRED NO_MODULE)
find_package(yaml-cpp REQUIRED)
find_package(OpenMP REQUIRED COMPONENTS CXX)
find_package(PkgConfig REQUIRED)
pkg_check_modules(FFTW3 REQUIRED IMPORTED_TARGET fftw3)
find_package(VTK 9 REQUIRED COMPONENTS CommonCore CommonDataModel IOXML)

if(GRAINS_WITH_MPI)
  find_package(MPI REQUIRED COMPONENTS CXX)
endif()

# HDF5: the Open MPI build (libhdf5-openmpi-dev).
set(HDF5_PREFER_PARALLEL TRUE)
find_package(HDF5 REQUIRED COMPONENTS C)

if(GRAINS_WITH_SUNDIALS)
  find_library(SUNDIALS_ARKODE_LIB sundials_arkode REQUIRED)
  find_library(SUNDIALS_NVECSERIAL_LIB sundials_nvecserial REQUIRED)
  find_library(SUNDIALS_NVECOPENMP_LIB sundials_nvecopenmp REQUIRED)
  find_path(SUNDIALS_INCLUDE_DIR arkode/arkode_erkstep.h REQUIRED)
  add_library(grains_sundials INTERFACE)
  target_include_directories(grains_sundials INTERFACE ${SUNDIALS_INCLUDE_DIR})
  target_link_libraries(grains_sundials INTERFACE ${SUNDIALS_ARKODE_LIB} ${SUNDIALS_NVECSERIAL_LIB} ${SUNDIALS_NVECOPENMP_LIB})
endif()

if(GRAINS_BUILD_TESTS)
  find_package(GTest REQUIRED)
  include(GoogleTest)
endif()
if(GRAINS_BUILD_BENCH)
  find_package(benchmark REQUIRED)
endif()

if(GRAINS_PYTHON)
  # Debian's interpreter (with python3-numpy), not one a pyenv or venv puts first on PATH.
  if(NOT Python3_EXECUTABLE AND EXISTS /usr/bin/python3)
    set(Python3_EXECUTABLE /usr/bin/python3)
  endif()
  find_package(Python3 REQUIRED COMPONENTS Interpreter Development.Module)
  set(PYBIND11_FINDPYTHON ON)
  find_package(pybind11 CONFIG REQUIRED)
endif()
