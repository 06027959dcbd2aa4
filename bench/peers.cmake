# Peer broadphases for bench_contact_detection (bench/peers/): CGAL's box_intersection_d
# (header-only, Debian libcgal-dev) and Bullet's btDbvt (libbullet-dev). Optional and bench
# only: each peer is compiled in when found and FIBRA_BENCH_PEERS is on; nothing else in the
# build depends on them.
if(NOT FIBRA_BENCH_PEERS OR NOT TARGET bench_contact_detection)
  return()
endif()

find_path(FIBRA_CGAL_INCLUDE_DIR CGAL/box_intersection_d.h)
find_package(Boost QUIET)
if(FIBRA_CGAL_INCLUDE_DIR AND Boost_FOUND)
  target_sources(bench_contact_detection PRIVATE ${PROJECT_SOURCE_DIR}/bench/peers/cgal_broadphase.cpp)
  target_include_directories(bench_contact_detection SYSTEM PRIVATE ${FIBRA_CGAL_INCLUDE_DIR}
    ${Boost_INCLUDE_DIRS})
  # CGAL_LINKED_WITH_TBB enables CGAL::Parallel_tag (oneTBB is linked through fibra_lib).
  target_compile_definitions(bench_contact_detection PRIVATE FIBRA_HAVE_CGAL CGAL_LINKED_WITH_TBB)
  message(STATUS "bench peers: CGAL box_intersection_d in ${FIBRA_CGAL_INCLUDE_DIR}")
else()
  message(STATUS "bench peers: CGAL not found (libcgal-dev), skipped")
endif()

find_package(PkgConfig QUIET)
if(PkgConfig_FOUND)
  pkg_check_modules(FIBRA_BULLET QUIET bullet)
endif()
if(FIBRA_BULLET_FOUND)
  target_sources(bench_contact_detection PRIVATE ${PROJECT_SOURCE_DIR}/bench/peers/bullet_broadphase.cpp)
  target_include_directories(bench_contact_detection SYSTEM PRIVATE ${FIBRA_BULLET_INCLUDE_DIRS})
  target_link_libraries(bench_contact_detection PRIVATE BulletCollision LinearMath)
  target_compile_definitions(bench_contact_detection PRIVATE FIBRA_HAVE_BULLET
    ${FIBRA_BULLET_CFLAGS_OTHER})
  message(STATUS "bench peers: Bullet btDbvt ${FIBRA_BULLET_VERSION}")
else()
  message(STATUS "bench peers: Bullet not found (libbullet-dev), skipped")
endif()
