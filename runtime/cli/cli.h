// The `cohort` command line: parsing, dispatch, and the mapping of errors to exit codes
// (0 success, 2 bad usage or input, 1 any other failure).
#pragma once

namespace cohort {

int run_cli(int argc, char** argv);

}  // namespace cohort
