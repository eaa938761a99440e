# The fault matrix's geometry rows (docs/testing.md, "Fault matrix", "Geometry"): one ctest a
# group of rows, each row a separate expectation of tests/klayout/check_faults_geometry.py.
# Included from the end of tests/CMakeLists.txt (REPO and ARTIFACTS set there).
# The huge polygon: 10^5 vertices here (under a minute); -rd vertices=1000000 for the row's 10^6.
foreach(group range shapes hierarchy huge_polygon)
  add_test(NAME faults_geometry_${group}
           COMMAND klayout -b -r ${REPO}/tests/klayout/check_faults_geometry.py -rd group=${group}
                   -rd work=${ARTIFACTS}/faults_geometry -rd vertices=100000)
  set_tests_properties(faults_geometry_${group} PROPERTIES TIMEOUT 600)
endforeach()
