#include <iostream>
#include <string>
#include <vector>

#include "tools/cli.h"
#include "tools/commands.h"

int main(int argc, char** argv) {
  const int code =
      relief::run_cli(std::vector<std::string>(argv, argv + argc), std::cout, std::cerr);
  // A report lost on the way out (stdout on a full disk, a closed pipe) is an output that could
  // not be written: said, and not exit 0.
  std::cout.flush();
  if (!std::cout) {
    std::cerr << "relief: error: cannot write to standard output; the report was lost\n";
    // compare's codes are idiff's (1 is a warning there, 4 anything that is not a comparison);
    // crosscheck's unwritten output is 5.
    const std::string command = argc > 1 ? argv[1] : "";
    const int lost = command == "compare"      ? 4
                     : command == "crosscheck" ? relief::kCrosscheckOutputError
                                               : relief::kExitOutputError;
    // Whatever the verdict was, the report was not delivered: that is the code.
    (void)code;
    return lost;
  }
  return code;
}
