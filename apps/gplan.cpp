// gplan: the command line on YAML scene files (the commands: gplan_commands.h).

#include <iostream>

#include "command_line.h"
#include "gplan_commands.h"
#include "gplanner/planner/output/text_escaping.h"
#include "gplanner/planner/scene/input_error.h"

int main(int argc, char** argv) {
  try {
    return gplan::run_command(argc, argv);
  } catch (const gplan::UsageError& e) {
    std::cerr << "gplan: " << gplanner::terminal_text(e.what()) << "\n" << gplan::kUsage;
    return 2;
  } catch (const gplanner::InputError& e) {
    std::cerr << "gplan: " << gplanner::terminal_text(e.what()) << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "gplan: error: " << gplanner::terminal_text(e.what()) << "\n";
    return 1;
  }
}
