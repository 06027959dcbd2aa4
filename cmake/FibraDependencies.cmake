# The libraries fibra links, found the same way by fibra's own build and by fibraConfig.cmake
# (installed next to it). Defines fibra::suitesparse, an imported target with CHOLMOD, UMFPACK,
# AMD, SuiteSparse_config and OpenBLAS (Debian's libsuitesparse-dev ships no CMake package), and
# fibra::mumps, sequential MUMPS (Debian's libmumps-seq-dev: dmumps_seq, its common library and
# its MPI stub mpiseq_seq; not the MPI libmumps-dev, whose libraries lack the _seq suffix).
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
  foreach(lib dmumps_seq mumps_common_seq mpiseq_seq)
    find_library(FIBRA_${lib}_LIBRARY ${lib} REQUIRED)
    list(APPEND _fibra_libs ${FIBRA_${lib}_LIBRARY})
  endforeach()
  add_library(fibra::mumps INTERFACE IMPORTED)
  set_target_properties(fibra::mumps PROPERTIES
    INTERFACE_INCLUDE_DIRECTORIES "${FIBRA_MUMPS_INCLUDE_DIR}"
    INTERFACE_LINK_LIBRARIES "${_fibra_libs}")
  unset(_fibra_libs)
endif()
