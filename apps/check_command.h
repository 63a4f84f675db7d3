#pragma once

namespace gplan {

// gplan check SCENE [--n N] [--seed S] [--backend B] [--threads T] [--out FILE] [--json]
int run_check(int argc, char** argv);

}  // namespace gplan
