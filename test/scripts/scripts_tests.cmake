# The scripts' own checks (standard-library Python, seconds each): included from test/CMakeLists.txt.
find_program(COHORT_PYTHON3 python3)
if(COHORT_PYTHON3)
  # The external models' manifest is well formed, and every model present has its checksum.
  add_test(NAME scripts_external_scenes COMMAND ${COHORT_PYTHON3} ${PROJECT_SOURCE_DIR}/scripts/external-scenes --check)
  # docs/results.md is what results/current.json and the raw records give, byte for byte.
  add_test(NAME scripts_results_page COMMAND ${COHORT_PYTHON3} ${PROJECT_SOURCE_DIR}/scripts/results-page --check)
  # scripts/bench-suite: every suite expands, the GPU suite names its outputs as the records do, a run
  # alternates binaries in rounds and its summary takes medians of the JSON (a stand-in cohort).
  add_test(NAME scripts_bench_suite COMMAND ${COHORT_PYTHON3} ${CMAKE_CURRENT_LIST_DIR}/bench_suite_test.py)
  # The bench's table makers (scripts/lib/bench-peers.py, bench-summary.py) on committed records.
  add_test(NAME scripts_bench_tables COMMAND ${COHORT_PYTHON3} ${CMAKE_CURRENT_LIST_DIR}/bench_tables_test.py)
  # The peer comparison of scripts/bench-suite and the suite cpu-peers: groups alternate Cohort and
  # Mitsuba per model within a round, ratios divide figures of one round (stand-in programs).
  add_test(NAME scripts_cpu_peers COMMAND ${COHORT_PYTHON3} ${CMAKE_CURRENT_LIST_DIR}/cpu_peers_test.py)
  # scripts/remote/gpu-check passes on one set of image bytes and passing tests, fails on any other
  # (stand-in binaries: no GPU here).
  add_test(NAME scripts_gpu_check COMMAND ${COHORT_PYTHON3} ${CMAKE_CURRENT_LIST_DIR}/gpu_check_test.py)
  # scripts/ holds what a user or CI runs: each entry answers --help, the README's table names each,
  # and every scripts/... path the README and docs name exists.
  add_test(NAME scripts_layout COMMAND ${COHORT_PYTHON3} ${CMAKE_CURRENT_LIST_DIR}/scripts_layout_test.py)
endif()
