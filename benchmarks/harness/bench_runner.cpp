#include "bench_runner.h"

#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <iomanip>
#include <ostream>
#include <set>
#include <sstream>

#include "gplanner/common/gpu_device.h"
#include "gplanner/common/parallel_for.h"
#include "gplanner/planner/output/text_escaping.h"
#include "gplanner/planner/scene/scene.h"
#include "harness/pipe_write.h"
#include "harness/plan_runs.h"
#include "harness/query_runs.h"

namespace gplan {
namespace {

using Clock = std::chrono::steady_clock;

// Messages from a worker to gplan, each "T LENGTH\n" and LENGTH bytes: R a record (a CSV
// line), N a notice, D the group is done.
void send(int fd, char type, const std::string& payload) {
  const std::string message = std::string(1, type) + " " + std::to_string(payload.size()) + "\n" + payload;
  std::size_t written = 0;
  while (written < message.size()) {
    const ssize_t n = ::write(fd, message.data() + written, message.size() - written);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) _exit(3);  // gplan has gone: nothing to report to
    written += static_cast<std::size_t>(n);
  }
}

// Runs one group in a worker: its records, notices, and D when it is done.
void run_group(int fd, const BenchConfig& config, const gplanner::Scene& scene,
               const BenchGroup& group, int host_threads, int device,
               const std::string& failed_paths_dir, const std::function<bool()>& should_stop) {
  const auto emit = [fd](const BenchRecord& record) {
    std::ostringstream line;
    write_bench_csv_line(line, record);
    send(fd, 'R', line.str());
  };
  const auto notice = [fd](const std::string& text) { send(fd, 'N', text); };
  try {
    if (config.kind == "planning") {
      run_planning_group(scene, group.scene_name, group.first_run, config, group.choice,
                         host_threads, device, emit, should_stop, notice, failed_paths_dir);
    } else {
      QueryTableOptions options;
      options.queries = config.queries;
      options.milestones = config.milestones;
      options.neighbors = config.neighbors;
      options.repeat = config.repeat;
      options.seed = config.seed;
      run_query_group(scene, config.name, group.scene_name, group.table, group.checker, options,
                      emit, should_stop);
    }
  } catch (const std::exception& e) {
    // The group could not be set up (a checker, a roadmap): one record says why.
    BenchRecord record;
    record.experiment = config.name;
    record.scene = group.scene_name;
    record.planner = config.kind == "planning" ? group.choice.planner : group.table;
    record.checker = config.kind == "planning" ? group.choice.checker : group.checker;
    record.status = "error";
    record.note = e.what();
    emit(record);
  }
  send(fd, 'D', "");
}

// A worker that runs groups one after another as gplan hands them over (a group's index
// and a newline on `commands`), keeping its CUDA context between them; it ends when gplan
// closes `commands`.
[[noreturn]] void serve_groups(int fd, int commands, const BenchConfig& config,
                               const std::vector<gplanner::Scene>& scenes,
                               const std::vector<BenchGroup>& groups, int host_threads, int device,
                               const std::string& failed_paths_dir,
                               const std::function<bool()>& should_stop) {
  std::string line;
  for (char c;;) {
    const ssize_t n = ::read(commands, &c, 1);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;  // gplan closed it: no more groups
    if (c != '\n') {
      line += c;
      continue;
    }
    const std::size_t g = std::stoul(line);
    line.clear();
    run_group(fd, config, scenes[groups[g].scene], groups[g], host_threads, device,
              failed_paths_dir, should_stop);
  }
  ::close(fd);
  _exit(0);
}

struct Worker {
  pid_t pid = -1;
  int fd = -1;
  std::size_t group = 0;  // the group it runs (a serving worker: its last)
  int device = -1;        // the GPU it was given (-1: none)
  int commands = -1;      // a serving worker's command pipe (-1: a worker of one group)
  bool idle = false;      // a serving worker between groups
  // A serving worker whose group ended in an error (a GPU left in a bad state, say) is
  // given no other group: a new worker takes the next.
  bool failed = false;
  std::string buffer;
  int records = 0;
  bool done = false;
  std::string killed;  // why gplan killed it
  Clock::time_point last = Clock::now();
};

std::string describe(const BenchRecord& r) {
  std::ostringstream text;
  text << std::setprecision(3);
  if (r.status == "measured") {
    text << std::fixed << r.time_s * 1000 << " ms";
    if (r.work >= 0) text << " (" << r.work << " " << (r.planner == "local-planning" ? "edges" : "queries") << ")";
    return text.str();
  }
  text << r.status;
  if (std::isfinite(r.time_s)) text << " in " << r.time_s << " s";
  if (!r.path_check.empty()) text << ", FCL re-check " << r.path_check;
  if (!r.note.empty()) text << " (" << gplanner::terminal_text(r.note.substr(0, 160)) << ")";
  return text.str();
}

}  // namespace

int count_gpus_in_child() {
  int fds[2];
  if (::pipe(fds) != 0) throw std::runtime_error(std::string("pipe: ") + std::strerror(errno));
  const pid_t pid = ::fork();
  if (pid < 0) throw std::runtime_error(std::string("fork: ") + std::strerror(errno));
  if (pid == 0) {
    ::close(fds[0]);
    const int count = gplanner::gpu_device_count();
    const ssize_t written = ::write(fds[1], &count, sizeof count);
    _exit(written == sizeof count ? 0 : 1);
  }
  ::close(fds[1]);
  int count = 0;
  ssize_t n = 0;
  while ((n = ::read(fds[0], &count, sizeof count)) < 0 && errno == EINTR) {
  }
  ::close(fds[0]);
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  return n == sizeof count ? count : 0;
}

std::string BenchGroup::label() const {
  return scene_name + " " + (table.empty() ? choice.label() : table + " " + checker);
}

std::string side_by_side_notice(const std::vector<BenchGroup>& groups, int jobs) {
  const auto together =
      std::count_if(groups.begin(), groups.end(), [](const BenchGroup& g) { return !g.alone; });
  if (jobs <= 1 || together < 2) return {};
  return "--jobs " + std::to_string(jobs) + ": OMPL's single-threaded planners ran up to " +
         std::to_string(std::min<long>(jobs, together)) +
         " at a time, each slower than alone (shared cores, caches and clock): their times, "
         "and ratios against them, are not those of a planner run alone; to compare "
         "planners, run with --jobs 1";
}

std::vector<BenchGroup> bench_groups(const BenchConfig& config) {
  std::vector<BenchGroup> alone, together;
  for (std::size_t s = 0; s < config.scenes.size(); ++s) {
    BenchGroup base;
    base.scene = s;
    base.scene_name = s < config.scene_labels.size()
                          ? config.scene_labels[s]
                          : std::filesystem::path(config.scenes[s]).stem().string();
    base.first_run = s < config.first_runs.size() ? config.first_runs[s] : 0;
    if (config.kind == "planning") {
      for (const PlannerChoice& choice : config.planners) {
        BenchGroup group = base;
        group.choice = choice;
        group.runs = config.runs;
        group.alone = !choice.single_threaded();
        group.gpu = choice.backend() == "gpu";
        (group.alone ? alone : together).push_back(group);
      }
    } else {
      for (const std::string& table : config.tables) {
        for (const std::string& checker : config.checkers) {
          BenchGroup group = base;
          group.table = table;
          group.checker = checker;
          group.runs = config.repeat;
          alone.push_back(group);
        }
      }
    }
  }
  alone.insert(alone.end(), together.begin(), together.end());
  return alone;
}

std::vector<BenchRecord> run_bench_groups(const BenchConfig& config,
                                          const std::vector<gplanner::Scene>& scenes,
                                          const std::vector<BenchGroup>& groups,
                                          const BenchResources& resources, std::ostream& progress,
                                          const std::function<bool()>& should_stop,
                                          const std::function<void(const BenchRecord&)>& on_record,
                                          const std::string& failed_paths_dir) {
  std::vector<std::vector<BenchRecord>> records(groups.size());
  std::vector<Worker> running;
  std::set<std::string> notices;
  std::vector<bool> started(groups.size(), false);
  std::size_t next = 0;  // the first group not started
  // A planning run with no result this long after the last is killed.
  const double silence_limit_s = 2 * config.time_limit_s + 120;
  const int jobs = std::max(1, resources.jobs);
  const int gpus = std::max(1, resources.gpus);
  const int cores = gplanner::resolve_thread_count(0);
  // The host threads of a group beside others: an OMPL planner on the gpu backend answers
  // small calls on the host's thread pool, which gets the cores the other `jobs` - 1
  // single-threaded groups leave, so that neither it nor FCL's runs beside it are
  // handicapped by the other. Groups that run alone get every core (0); ours on the gpu
  // backend, one per GPU side by side, a GPU's share of them. --threads sets them all.
  const auto host_threads_of = [&](const BenchGroup& group) {
    if (resources.threads > 0) return resources.threads;
    if (!group.alone) return std::max(1, cores - (jobs - 1));
    if (group.gpu && gpus > 1) return std::max(1, cores / gpus);
    return 0;
  };
  // The GPUs in use by running workers.
  std::vector<bool> gpu_busy(static_cast<std::size_t>(gpus), false);
  const auto free_gpu = [&] {
    for (int d = 0; d < gpus; ++d)
      if (!gpu_busy[d]) return d;
    return -1;
  };

  // Our groups on the gpu backend go to serving workers, one per GPU, which keep their
  // CUDA context from group to group (its start costs a few tenths of a second, more than
  // an easy problem's plan); every other group to a worker of its own.
  const auto serves = [&](const BenchGroup& group) { return group.alone && group.gpu; };
  const auto say_started = [&](std::size_t g, int device) {
    progress << "[" << g + 1 << "/" << groups.size() << "] " << groups[g].label() << ": "
             << groups[g].runs << (config.kind == "planning" ? " runs" : " timed calls");
    if (device >= 0 && gpus > 1) progress << " on GPU " << device;
    progress << "\n";
  };
  // Hands group g to an idle serving worker; false where the worker has just ended (it
  // is then given nothing more and goes with its end of file).
  const auto hand_over = [&](Worker& worker, std::size_t g) {
    const std::string line = std::to_string(g) + "\n";
    if (!write_to_pipe(worker.commands, line.data(), line.size())) {
      ::close(worker.commands);
      worker.commands = -1;
      worker.failed = true;
      return false;
    }
    worker.group = g;
    worker.idle = false;
    worker.done = false;
    worker.records = 0;
    worker.last = Clock::now();
    say_started(g, worker.device);
    return true;
  };
  const auto start_worker = [&](std::size_t g, int device) {
    const bool serving = serves(groups[g]);
    int fds[2], commands[2] = {-1, -1};
    if (::pipe(fds) != 0 || (serving && ::pipe(commands) != 0))
      throw std::runtime_error(std::string("pipe: ") + std::strerror(errno));
    progress.flush();
    const pid_t pid = ::fork();
    if (pid < 0) throw std::runtime_error(std::string("fork: ") + std::strerror(errno));
    if (pid == 0) {
      ::close(fds[0]);
      for (const Worker& other : running) {
        ::close(other.fd);
        if (other.commands >= 0) ::close(other.commands);
      }
      if (serving) {
        ::close(commands[1]);
        serve_groups(fds[1], commands[0], config, scenes, groups, host_threads_of(groups[g]),
                     std::max(device, 0), failed_paths_dir, should_stop);
      }
      run_group(fds[1], config, scenes[groups[g].scene], groups[g], host_threads_of(groups[g]),
                std::max(device, 0), failed_paths_dir, should_stop);
      ::close(fds[1]);
      _exit(0);
    }
    ::close(fds[1]);
    Worker worker;
    worker.pid = pid;
    worker.fd = fds[0];
    worker.group = g;
    worker.device = device;
    if (serving) {
      ::close(commands[0]);
      worker.commands = commands[1];
    }
    if (device >= 0) gpu_busy[device] = true;
    running.push_back(worker);
    if (serving) {
      hand_over(running.back(), g);
    } else {
      say_started(g, device);
    }
  };

  const auto take_messages = [&](Worker& worker) {
    for (;;) {
      const std::size_t header_end = worker.buffer.find('\n');
      if (header_end == std::string::npos) return;
      const char type = worker.buffer[0];
      const std::size_t length = std::stoul(worker.buffer.substr(2, header_end - 2));
      if (worker.buffer.size() < header_end + 1 + length) return;
      const std::string payload = worker.buffer.substr(header_end + 1, length);
      worker.buffer.erase(0, header_end + 1 + length);
      worker.last = Clock::now();
      const BenchGroup& group = groups[worker.group];
      if (type == 'R') {
        const BenchRecord record = parse_bench_csv_record(payload);
        records[worker.group].push_back(record);
        on_record(record);
        ++worker.records;
        if (record.status == "error") worker.failed = true;
        progress << "  " << group.label() << " " << worker.records << "/" << group.runs << ": "
                 << describe(record) << "\n";
      } else if (type == 'N') {
        if (notices.insert(payload).second)
          progress << "notice: " << gplanner::terminal_text(payload) << "\n";
      } else if (type == 'D') {
        worker.done = true;
        if (worker.commands >= 0) worker.idle = true;  // ready for the next group
      }
    }
  };

  const auto end_worker = [&](Worker& worker) {
    ::close(worker.fd);
    if (worker.commands >= 0) ::close(worker.commands);
    int status = 0;
    while (::waitpid(worker.pid, &status, 0) < 0 && errno == EINTR) {
    }
    if (worker.done || worker.idle || should_stop()) return;
    // The run in progress ended without a result.
    const BenchGroup& group = groups[worker.group];
    BenchRecord record;
    record.experiment = config.name;
    record.scene = group.scene_name;
    record.planner = config.kind == "planning" ? group.choice.planner : group.table;
    record.checker = config.kind == "planning" ? group.choice.checker : group.checker;
    record.run = group.first_run + worker.records;
    record.seed = config.seed + static_cast<std::uint64_t>(worker.records);
    record.status = "crash";
    record.device = worker.device;
    if (!worker.killed.empty()) {
      record.note = worker.killed;
    } else if (WIFSIGNALED(status)) {
      record.note = std::string("the worker process ended by signal ") + std::to_string(WTERMSIG(status)) +
                    " (" + strsignal(WTERMSIG(status)) + ")";
    } else {
      record.note = "the worker process exited with status " + std::to_string(WEXITSTATUS(status));
    }
    records[worker.group].push_back(record);
    on_record(record);
    progress << "  " << group.label() << " " << worker.records + 1 << "/" << group.runs << ": "
             << describe(record) << "\n";
  };

  while (next < groups.size() || !running.empty()) {
    if (should_stop()) {
      for (Worker& worker : running) ::kill(worker.pid, SIGTERM);
      for (Worker& worker : running) end_worker(worker);
      running.clear();
      break;
    }
    // Serving workers left idle end where the next group is not theirs (a group that
    // runs alone, or the single-threaded ones after them), or where their last group
    // failed.
    for (Worker& worker : running) {
      const bool theirs = next < groups.size() && serves(groups[next]);
      if (worker.idle && worker.commands >= 0 && (!theirs || worker.failed)) {
        ::close(worker.commands);
        worker.commands = -1;
      }
    }
    // Start what may start: a group that runs alone when nothing runs (ours on the gpu
    // backend: beside others of its kind, one per GPU, on a serving worker); single-
    // threaded ones up to `jobs`, never beside one that runs alone, one per GPU on the
    // gpu backend.
    for (std::size_t g = next; g < groups.size(); ++g) {
      if (started[g]) continue;
      const BenchGroup& group = groups[g];
      const bool served = serves(group);
      const bool any_alone = std::any_of(running.begin(), running.end(),
                                         [&](const Worker& w) { return groups[w.group].alone; });
      const bool all_served = std::all_of(running.begin(), running.end(),
                                          [&](const Worker& w) { return serves(groups[w.group]); });
      const auto idle = std::find_if(running.begin(), running.end(), [](const Worker& w) {
        return w.idle && w.commands >= 0 && !w.failed;
      });
      const int device = group.gpu ? free_gpu() : -1;
      bool may_start = false;
      if (served) {
        may_start = all_served && (idle != running.end() || device >= 0);
      } else if (group.alone) {
        may_start = running.empty();
      } else {
        may_start = !any_alone && int(running.size()) < jobs && (!group.gpu || device >= 0);
      }
      if (may_start) {
        started[g] = true;
        if (served && idle != running.end()) {
          started[g] = hand_over(*idle, g);  // else again once the worker's end is seen
        } else {
          start_worker(g, device);
        }
      }
      // The order of those that run alone is kept (those on the GPUs among themselves).
      if (group.alone && !(served && may_start)) break;
    }
    while (next < groups.size() && started[next]) ++next;
    std::vector<pollfd> fds;
    for (const Worker& worker : running) fds.push_back({worker.fd, POLLIN, 0});
    const int ready = ::poll(fds.data(), fds.size(), 200);
    if (ready < 0 && errno != EINTR) throw std::runtime_error(std::string("poll: ") + std::strerror(errno));
    std::vector<bool> ended(running.size(), false);
    for (std::size_t i = 0; i < running.size(); ++i) {
      Worker& worker = running[i];
      if (ready > 0 && (fds[i].revents & (POLLIN | POLLHUP | POLLERR))) {
        char chunk[65536];
        const ssize_t n = ::read(worker.fd, chunk, sizeof chunk);
        if (n > 0) {
          worker.buffer.append(chunk, static_cast<std::size_t>(n));
          take_messages(worker);
        } else if (n == 0 || errno != EINTR) {
          ended[i] = true;
        }
      }
      if (!ended[i] && !worker.idle && config.kind == "planning" && worker.killed.empty() &&
          std::chrono::duration<double>(Clock::now() - worker.last).count() > silence_limit_s) {
        std::ostringstream why;
        why << "no result " << silence_limit_s << " s after the run began (time limit "
            << config.time_limit_s << " s); killed";
        worker.killed = why.str();
        ::kill(worker.pid, SIGKILL);
      }
    }
    for (std::size_t i = running.size(); i-- > 0;) {
      if (!ended[i]) continue;
      if (running[i].device >= 0) gpu_busy[running[i].device] = false;
      end_worker(running[i]);
      running.erase(running.begin() + static_cast<std::ptrdiff_t>(i));
    }
  }
  std::vector<BenchRecord> all;
  for (const auto& group_records : records) all.insert(all.end(), group_records.begin(), group_records.end());
  return all;
}

}  // namespace gplan
