# OMPL as one target, gplanner_ompl: OMPL's own ompl::ompl where its package config
# exports one (newer releases), else an interface target made from the variables that
# Debian's OMPL 1.5 exports (OMPL_INCLUDE_DIRS, OMPL_LIBRARIES).
find_package(ompl REQUIRED)
if(NOT TARGET gplanner_ompl)
  add_library(gplanner_ompl INTERFACE IMPORTED)
  if(TARGET ompl::ompl)
    target_link_libraries(gplanner_ompl INTERFACE ompl::ompl)
  else()
    target_include_directories(gplanner_ompl INTERFACE ${OMPL_INCLUDE_DIRS})
    target_link_libraries(gplanner_ompl INTERFACE ${OMPL_LIBRARIES})
  endif()
endif()
