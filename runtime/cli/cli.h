// The `cohort` command line: parsing, dispatch, and the mapping of errors to exit codes
// (0 success, 2 bad usage or input, 1 any other failure).
#pragma once

#include <string>
#include <vector>

#include "runtime/cli/commands.h"

namespace cohort {

int run_cli(int argc, char** argv);

// `cohort render`'s options (the scene first, as on the command line) parsed as the CLI parses them:
// the same defaults and checks. Throws InputError with the parser's message.
RenderCommand parse_render_arguments(const std::vector<std::string>& arguments);

}  // namespace cohort
