// The `relief` command line: relief COMMAND [SCENE] [--set KEY=VALUE]... [options].
// Exit codes: 0 success, 2 bad input (scene, override or command-line value; nothing is
// written), 1 an output could not be written.
#pragma once

#include <iosfwd>
#include <string>
#include <vector>

namespace relief {

inline constexpr int kExitOk = 0;
inline constexpr int kExitOutputError = 1;
inline constexpr int kExitBadInput = 2;

// args[0] is the program name. Messages go to `out` and `err`.
int run_cli(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);

}  // namespace relief
