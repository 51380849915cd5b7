# System packages only (Debian); scripts/deps.sh installs them. No third-party source in the repo.
find_package(Threads REQUIRED)             # contact: the per-pair thread pool (WorldDef::thread_count)
find_package(nlohmann_json 3.10 CONFIG REQUIRED)
find_package(CLI11 CONFIG REQUIRED)
find_package(Eigen3 3.4 CONFIG REQUIRED)   # modal: sparse assembly, dense eigen solves
find_path(SPECTRA_INCLUDE_DIR Spectra/SymGEigsShiftSolver.h REQUIRED)  # modal: shift-invert eigen solves
# modal: supernodal sparse Cholesky with a fill-reducing ordering (libsuitesparse-dev; Debian's 5.x ships
# no pkg-config file or CMake package for it, so the header and library are found directly).
find_path(CHOLMOD_INCLUDE_DIR cholmod.h PATH_SUFFIXES suitesparse REQUIRED)
find_library(CHOLMOD_LIBRARY cholmod REQUIRED)
# SuiteSparse_config (its allocator hooks: the factor goes on huge pages), linked by name because
# CHOLMOD's own dependency on it is not on our link line.
find_library(SUITESPARSECONFIG_LIBRARY suitesparseconfig REQUIRED)
if(NOT TARGET SuiteSparse::CHOLMOD)
  add_library(SuiteSparse::CHOLMOD UNKNOWN IMPORTED)
  set_target_properties(SuiteSparse::CHOLMOD PROPERTIES IMPORTED_LOCATION ${CHOLMOD_LIBRARY}
    INTERFACE_INCLUDE_DIRECTORIES ${CHOLMOD_INCLUDE_DIR}
    INTERFACE_LINK_LIBRARIES ${SUITESPARSECONFIG_LIBRARY})
endif()
find_package(PkgConfig REQUIRED)
pkg_check_modules(CCD REQUIRED IMPORTED_TARGET ccd)  # contact: MPR penetration (libccd, double build)
find_package(assimp 5.2 CONFIG REQUIRED)  # io: mesh import (OBJ, PLY, STL, glTF/GLB, FBX)
if(SUPERMODAL_RENDER)
  # render: headless EGL (Mesa surfaceless platform) + OpenGL ES 3.0, PNG written by libspng, read by stb.
  pkg_check_modules(EGL REQUIRED IMPORTED_TARGET egl)        # libegl-dev (+ libegl-mesa0 at run time)
  pkg_check_modules(GLESV2 REQUIRED IMPORTED_TARGET glesv2)  # libgles-dev (+ libgl1-mesa-dri: llvmpipe)
  pkg_check_modules(STB REQUIRED IMPORTED_TARGET stb)        # libstb-dev
  pkg_check_modules(SPNG REQUIRED IMPORTED_TARGET spng)      # libspng-dev
endif()
if(SUPERMODAL_TESTS)
  find_package(GTest CONFIG REQUIRED)
endif()
if(SUPERMODAL_BENCH)
  find_package(benchmark CONFIG REQUIRED)
endif()
