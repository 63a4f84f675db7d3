// gplan: the command line on YAML scene files (the commands: gplan_commands.h).

#include "gplan_commands.h"
#include "program_main.h"

int main(int argc, char** argv) {
  gplan::program_main("gplan", gplan::kUsage, argc, argv, gplan::run_command);
}
