#include "gplan_commands.h"

#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include "check_command.h"
#include "command_line.h"
#include "gplanner/common/gpu_device.h"
#include "gplanner/version.h"
#include "plan_command.h"
#include "view_command.h"

namespace gplan {

const char* const kUsage =
    "usage: gplan COMMAND ...\n"
    "  gplan check SCENE [--n N] [--seed S] [--backend gpu|cpu|fcl]\n"
    "                    [--traversal basic|packet|balanced] [--compare BACKEND]\n"
    "                    [--threads T] [--memory-cap-mb M] [--small-batch N] [--device D]\n"
    "                    [--repeat R] [--out FILE [--pairs]] [--html FILE.html] [--json]\n"
    "      sample N configurations (default 10000, seed 1) within the scene's bounds and\n"
    "      joint limits and check them (default backend fcl; gpu falls back to cpu where\n"
    "      there is no GPU); --compare runs a second backend on the same configurations\n"
    "      and judges every disagreement by FCL's distance against the tolerance band\n"
    "      (exit 3 when it is broken); --repeat checks the batch R times and reports the\n"
    "      median time; --small-batch: the balanced traversal runs batches of up to N\n"
    "      queries in one kernel, a warp per body pair (default: 4096 to 1024 for robots\n"
    "      with many links, fewer the more checked bodies; 10 for rigid ones; 0: never);\n"
    "      with --backend gpu every call runs\n"
    "      on the GPU (the planners answer small calls on the host); --device D: the\n"
    "      CUDA device (0, 1, ... among those CUDA_VISIBLE_DEVICES leaves; all: every\n"
    "      one, batches of 32768 or more split across them; default 0); --out\n"
    "      writes each configuration's values and its\n"
    "      verdict (1 collision, 0 free), one per line; --json ends with a JSON summary\n"
    "  gplan plan SCENE [--planner auto|rrtconnect|lazyprm|prm] [--backend gpu|cpu|fcl]\n"
    "                   [--seed S] [--time-limit SECONDS] [--milestones N] [--traversal T]\n"
    "                   [--threads T] [--device D]"
    " [--load-roadmap FILE] [--save-roadmap FILE] [--out FILE]\n"
    "                   [--picture FILE.svg] [--html FILE.html [--html-roadmap]]\n"
    "                   [--edges sampled|certified] [--path-check certified|fine] [--json]\n"
    "      plan from the scene's start to its goal (default auto: batched RRT-Connect for\n"
    "      robots with joints, lazy PRM for rigid bodies and roadmaps; the gpu backend;\n"
    "      seed, time limit and first-round milestones default to the scene's planner\n"
    "      settings) and print the time per stage; --out writes the path (YAML),\n"
    "      --picture a drawing of it (SVG), --html a 3-D view of it to open in a browser\n"
    "      (one file, offline); exit 4\n"
    "      when no path is found within the time limit. The path returned is certified\n"
    "      free along every motion (docs/design.md, \"Certified motions\"); --path-check\n"
    "      fine re-checks it at samples instead; --edges certified certifies every edge\n"
    "      the planner uses, not only the path's; --device D: the gpu backend's CUDA\n"
    "      device, as gplan check's\n"
    "  gplan view PATHFILE [--scene SCENE] --html FILE.html\n"
    "      the 3-D view of a path file (plan --out, a gplan-bench failed_paths/ entry) in\n"
    "      its scene (the file's scene: key, or --scene)\n"
    "  gplan bench CONFIG ...\n"
    "      deprecated alias of gplan-bench CONFIG ... (the benchmark program installed\n"
    "      beside gplan; gplan-bench --help), to be removed in 0.6\n"
    "  gplan info\n"
    "      gplanner's version, how it was built and which GPUs it can use (numbered as\n"
    "      --device numbers them)\n"
    "Output files (--out, --picture, --html, --save-roadmap) are checked before any work: a\n"
    "regular file or a new one in a writable folder, never a folder or device, never a\n"
    "file the run reads or another output; a symbolic link is written through to its\n"
    "target. Each is written whole or not at all. Exit codes: 0 done, 1 internal error,\n"
    "2 bad input or usage, 3 checkers disagree (check --compare) or a path failed the\n"
    "FCL re-check (bench), 4 no path (plan), 5 a regression against the baseline (bench);\n"
    "SIGINT, SIGTERM or SIGHUP stops a run cleanly, writing nothing more and leaving no\n"
    "temporary file (bench keeps the runs done in DIR/results.partial.csv): exit 130\n"
    "(SIGINT), 143 (SIGTERM) or 129 (SIGHUP); a second signal ends it at once.\n";

namespace {

int run_info() {
  const gplanner::GpuDevice device = gplanner::query_gpu_device();
  std::cout << "gplanner    " << gplanner::version() << "\n";
  std::cout << "CUDA        " << (device.compiled_with_cuda ? "compiled in" : "not compiled in")
            << "\n";
  if (!device.available) {
    std::cout << "GPU         none: " << device.reason << "\n";
    return 0;
  }
  // Every device the process sees, numbered as --device numbers them.
  for (int d = 0; d < device.count; ++d) {
    const gplanner::GpuDevice gpu = d == 0 ? device : gplanner::query_gpu_device(d);
    std::cout << "GPU " << d << (d < 10 ? "       " : "      ") << gpu.name << " (sm_"
              << gpu.compute_major << gpu.compute_minor << ", " << gpu.multiprocessors << " SMs, "
              << gpu.memory_bytes / (1024 * 1024) << " MiB)\n";
  }
  return 0;
}

// This process's command line as the kernel holds it (/proc/self/cmdline): where a
// dynamic loader started the program (`ld.so [OPTIONS] PROGRAM ARGS`), the loader and its
// options come first.
std::vector<std::string> process_command_line() {
  std::ifstream file("/proc/self/cmdline", std::ios::binary);
  std::vector<std::string> words;
  for (std::string word; std::getline(file, word, '\0');) words.push_back(word);
  return words;
}

// `gplan bench ARGS`: runs gplan-bench ARGS from the folder gplan lies in, in gplan's
// place (its exit code is gplan's). Where a dynamic loader started gplan (a relocatable
// bundle's `ld.so --library-path DIR gplan ...`), the same loader with the same options
// starts gplan-bench.
int run_bench_alias(int argc, char** argv) {
  namespace fs = std::filesystem;
  std::error_code error;
  fs::path gplan = fs::read_symlink("/proc/self/exe", error);
  std::vector<std::string> command;
  if (error || gplan.filename().string().rfind("gplan", 0) != 0) {
    gplan = argv[0];
    const std::vector<std::string> words = process_command_line();
    const std::size_t n = static_cast<std::size_t>(argc);
    if (words.size() > n &&
        std::equal(words.end() - n, words.end(), argv,
                   [](const std::string& a, const char* b) { return a == b; })) {
      command.assign(words.begin(), words.end() - n);  // the loader and its options
    }
  }
  const std::string bench = (gplan.parent_path() / "gplan-bench").string();
  command.push_back(bench);
  for (int i = 2; i < argc; ++i) command.push_back(argv[i]);
  std::vector<char*> args;
  for (std::string& word : command) args.push_back(word.data());
  args.push_back(nullptr);
  std::cout.flush();
  std::cerr.flush();
  ::execv(args[0], args.data());
  throw std::runtime_error("gplan bench runs gplan-bench, which did not start from " + bench +
                           " (" + std::strerror(errno) +
                           "); run gplan-bench from where it is installed");
}

}  // namespace

int run_command(int argc, char** argv) {
  if (argc < 2 || std::string(argv[1]) == "--help" || std::string(argv[1]) == "-h") {
    std::cout << kUsage;
    return argc < 2 ? 2 : 0;
  }
  const std::string command = argv[1];
  if (command == "check") return run_check(argc, argv);
  if (command == "plan") return run_plan(argc, argv);
  if (command == "bench") return run_bench_alias(argc, argv);
  if (command == "view") return run_view(argc, argv);
  if (command == "info") return run_info();
  throw UsageError("unknown command '" + excerpt(command) +
                   "'; use check, plan, view, bench or info");
}

}  // namespace gplan
