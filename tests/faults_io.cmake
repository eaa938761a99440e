# The fault matrix's rows for files, markers and the environment (docs/testing.md, "Fault matrix",
# "Files, markers, environment"): one ctest a row, `faults_io_<case>`, each a case of
# tests/klayout/check_faults_io.py. A case that needs root (a tmpfs mount, running as nobody)
# reports SKIPPED (exit 77) without it.
set(FAULTS_IO_CASES
  truncated_gds truncated_oasis wrong_magic gzip_gds layer_above_65535 unreadable_file directory_input missing_file
  markers_nan_inf_empty markers_wrong_columns markers_million_rows markers_outside_layout
  marker_layer_is_working_layer
  full_disk read_only_folder sigkill two_runs memory_limit)
foreach(case IN LISTS FAULTS_IO_CASES)
  add_test(NAME faults_io_${case}
           COMMAND klayout -b -r ${REPO}/tests/klayout/check_faults_io.py -rd case=${case}
                   -rd work=${ARTIFACTS}/faults_io_${case})
  set_tests_properties(faults_io_${case} PROPERTIES TIMEOUT 900 SKIP_RETURN_CODE 77
                       ENVIRONMENT "PYTHONDONTWRITEBYTECODE=1")
endforeach()
# Mounts and a second process into one folder: not beside other tests that time themselves.
set_tests_properties(faults_io_full_disk faults_io_read_only_folder faults_io_sigkill faults_io_two_runs
                     faults_io_memory_limit PROPERTIES RUN_SERIAL TRUE)
