# OMPL as one target, gplanner::ompl, after find_package(ompl) (the build) or
# find_dependency(ompl) (gplannerConfig.cmake): OMPL's own ompl::ompl where its package
# config exports one (newer releases), else an interface target over libompl and OMPL's
# include folders. Debian's OMPL 1.5 exports only variables, and its OMPL_LIBRARIES
# also lists the unversioned Boost libraries that only Boost's -dev packages install;
# libompl itself records those as its own dependencies, so libompl alone is linked.
if(NOT TARGET gplanner::ompl)
  add_library(gplanner::ompl INTERFACE IMPORTED)
  if(TARGET ompl::ompl)
    target_link_libraries(gplanner::ompl INTERFACE ompl::ompl)
  else()
    find_library(GPLANNER_LIBOMPL NAMES ompl PATHS ${OMPL_LIBRARY_DIRS} REQUIRED)
    target_include_directories(gplanner::ompl INTERFACE ${OMPL_INCLUDE_DIRS})
    target_link_libraries(gplanner::ompl INTERFACE ${GPLANNER_LIBOMPL})
  endif()
endif()
