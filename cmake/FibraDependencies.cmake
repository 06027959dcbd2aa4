# The libraries fibra links, found the same way by fibra's own build and by fibraConfig.cmake
# (installed next to it). Defines fibra::suitesparse, an imported target with CHOLMOD, UMFPACK,
# AMD, SuiteSparse_config and OpenBLAS (Debian's libsuitesparse-dev ships no CMake package), and
# fibra::mumps, sequential MUMPS (Debian's libmumps-seq-dev: dmumps_seq, its common library and
# its MPI stub mpiseq_seq; not the MPI libmumps-dev, whose libraries lack the _seq suffix), with
# Scotch (libscotch-dev), whose graph constructor fibra wraps for MUMPS (systems/mumps_solver.cpp).
include(CMakeFindDependencyMacro)
find_dependency(Eigen3 3.4 NO_MODULE)
find_dependency(TBB)
find_dependency(nlohmann_json 3)
find_dependency(ZLIB)
if(NOT TARGET fibra::suitesparse)
  find_path(FIBRA_SUITESPARSE_INCLUDE_DIR cholmod.h PATH_SUFFIXES suitesparse REQUIRED)
  set(_fibra_libs)
  foreach(lib cholmod umfpack amd suitesparseconfig openblas)
    find_library(FIBRA_${lib}_LIBRARY ${lib} REQUIRED)
    list(APPEND _fibra_libs ${FIBRA_${lib}_LIBRARY})
  endforeach()
  add_library(fibra::suitesparse INTERFACE IMPORTED)
  set_target_properties(fibra::suitesparse PROPERTIES
    INTERFACE_INCLUDE_DIRECTORIES "${FIBRA_SUITESPARSE_INCLUDE_DIR}"
    INTERFACE_LINK_LIBRARIES "${_fibra_libs}")
  unset(_fibra_libs)
endif()
if(NOT TARGET fibra::mumps)
  find_path(FIBRA_MUMPS_INCLUDE_DIR dmumps_c.h REQUIRED)
  set(_fibra_libs)
  find_path(FIBRA_SCOTCH_INCLUDE_DIR scotch.h PATH_SUFFIXES scotch REQUIRED)
  foreach(lib dmumps_seq mumps_common_seq mpiseq_seq scotch)
    find_library(FIBRA_${lib}_LIBRARY ${lib} REQUIRED)
    list(APPEND _fibra_libs ${FIBRA_${lib}_LIBRARY})
  endforeach()
  add_library(fibra::mumps INTERFACE IMPORTED)
  set_target_properties(fibra::mumps PROPERTIES
    INTERFACE_INCLUDE_DIRECTORIES "${FIBRA_MUMPS_INCLUDE_DIR};${FIBRA_SCOTCH_INCLUDE_DIR}"
    INTERFACE_LINK_LIBRARIES "${_fibra_libs}"
    # fibra's SCOTCHFGRAPHBUILD/PART (systems/mumps_solver.cpp) must be the ones MUMPS binds to
    INTERFACE_LINK_OPTIONS
      "LINKER:--export-dynamic-symbol=scotchfgraphbuild_;LINKER:--export-dynamic-symbol=scotchfgraphpart_")
  unset(_fibra_libs)
endif()
