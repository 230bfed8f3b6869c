#include <iostream>
#include <string>
#include <vector>

#include "tools/cli.h"
#include "tools/commands.h"

int main(int argc, char** argv) {
  const int code =
      relief::run_cli(std::vector<std::string>(argv, argv + argc), std::cout, std::cerr);
  std::cout.flush();
  if (std::cout) {
    return code;
  }
  // A report lost on the way out (stdout on a full disk, a closed pipe) is an output that could
  // not be written, whatever the verdict was: compare's code for it is idiff's 4 (1 is a warning
  // there), crosscheck's 5.
  std::cerr << "relief: error: cannot write to standard output; the report was lost\n";
  const std::string command = argc > 1 ? argv[1] : "";
  return command == "compare"      ? relief::exit_code(relief::CompareVerdict::kFileError)
         : command == "crosscheck" ? relief::kCrosscheckOutputError
                                   : relief::kExitOutputError;
}
