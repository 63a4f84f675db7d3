#pragma once

namespace gplan {

// gplan plan SCENE [--planner lazyprm|prm] [--backend gpu|cpu|fcl] [--seed S]
//                  [--time-limit SECONDS] [--out PATH] [--json] ...
// Exit 0 with a path, 4 when none was found within the limit.
int run_plan(int argc, char** argv);

}  // namespace gplan
