# Run by the `docs` target after Doxygen (cmake -DLOG=<warnings.log> -P this-file):
# prints Doxygen's warning log when it is not empty. CI (.ci/run) fails on a
# non-empty log; this only makes the warnings visible in the build output.
if(NOT EXISTS "${LOG}")
  message(FATAL_ERROR "Doxygen wrote no warning log at ${LOG}")
endif()
file(READ "${LOG}" warnings)
if(NOT warnings STREQUAL "")
  message("Doxygen warnings (${LOG}):\n${warnings}")
endif()
