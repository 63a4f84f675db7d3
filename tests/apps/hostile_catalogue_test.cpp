// The hostile-input catalogue (tests/apps/hostile/catalogue.yaml, issue 19): every case
// run through the real gplan in a scratch folder of its own, each a parameterised case
// named after its entry. A case checks that gplan
// - ends within its limit (killed and failed as a hang otherwise) and is not killed by
//   a signal (a crash); with max_s, that it kept the time limit;
// - exits with the code expected (2 for bad input or usage, 0 or 4 for a legitimate run);
// - says so in a message ("gplan: ..." lines) that names the file or option and the key
//   (the case's fragments) and, for a refusal, what to change (one of a few advice
//   words, not the exact wording);
// - writes a short error, not megabytes, and not a screenful before the usage text;
// - changed no file of the case (type, size, mode, time and content; symlinks still the
//   same symlinks), but those it may write through;
// - created nothing but the outputs it may write, and those only when it did not
//   refuse the run: no temporary file left.

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "apps/hostile/case_files.h"
#include "apps/hostile/catalogue_case.h"
#include "apps/hostile/guarded_run.h"
#include "test_support.h"

namespace gplanner {
namespace {

namespace fs = std::filesystem;
using hostile::CatalogueCase;

std::string catalogue_file() {
  return testing::project_root() + "/tests/apps/hostile/catalogue.yaml";
}

// The catalogue, or one case that fails with why it could not be read.
std::vector<CatalogueCase> cases() {
  try {
    return hostile::load_catalogue(catalogue_file());
  } catch (const std::exception& e) {
    CatalogueCase unreadable;
    unreadable.name = "catalogue_unreadable";
    unreadable.kind = e.what();
    return {unreadable};
  }
}

// Words that say what to change (advice), any one of which a refusal must hold.
const std::regex kAdvice(
    R"(\b(use|give|set|remove|add|change|expected|expects|must|raise|lower|at most|at least|one of|write|rename|choose|build|repair|fix|make|move|delete|pick|point|lower|reduce|shorten|split|keep|replace|name|drop|list|lists|quote|swap|widen|narrow|chain|check (its|the|that))\b)",
    std::regex::icase);

// gplan's own lines on standard error ("gplan: ..."), the usage text left out.
std::vector<std::string> message_lines(const std::string& err) {
  std::vector<std::string> lines;
  std::istringstream in(err);
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("usage: gplan", 0) == 0) break;
    if (line.rfind("gplan:", 0) == 0 || line.rfind("gplan-bench:", 0) == 0) lines.push_back(line);
  }
  return lines;
}

// Lines before the usage text (notices, progress and the message).
std::size_t lines_before_usage(const std::string& err) {
  std::size_t count = 0;
  std::istringstream in(err);
  for (std::string line; std::getline(in, line); ++count)
    if (line.rfind("usage: gplan", 0) == 0) break;
  return count;
}

bool contains(const std::vector<std::string>& list, const std::string& item) {
  return std::find(list.begin(), list.end(), item) != list.end();
}

std::string describe(const hostile::EntryState& s) {
  std::ostringstream out;
  out << s.type << " size " << s.size << " mode " << std::oct << s.mode << std::dec;
  if (s.type == 'l') out << " -> " << s.link_target;
  return out.str();
}

}  // namespace

}  // namespace gplanner

namespace gplanner::hostile {
// Cases print as their names (gtest would print their bytes).
void PrintTo(const CatalogueCase& c, std::ostream* out) { *out << c.name; }
}  // namespace gplanner::hostile

namespace gplanner {
namespace {

constexpr int kNobody = 65534;

class HostileCatalogue : public ::testing::TestWithParam<CatalogueCase> {};

TEST_P(HostileCatalogue, RefusedCleanlyOrRunInTime) {
  const CatalogueCase& c = GetParam();
  ASSERT_NE(c.name, "catalogue_unreadable") << c.kind;
  testing::ScratchFolder scratch;
  const std::string& folder = scratch.path();
  hostile::write_fixtures(folder);
  for (const auto& file : c.files)
    hostile::create_file(folder, file.first.as<std::string>(), file.second);
  std::vector<std::string> arguments;
  for (const YAML::Node& argument : c.arguments)
    arguments.push_back(hostile::build_text(argument, folder));

  // Permission cases run as nobody where the tests run as root (who may write
  // anywhere): the folder and its files are given to nobody first, the read-only
  // modes kept.
  int as_user = 0;
  if (c.needs_non_root && geteuid() == 0) {
    as_user = kNobody;
    hostile::give_to(folder, kNobody);
  }
  const hostile::EntryState dev_null_before = hostile::entry_state("/dev/null");
  const auto before = hostile::snapshot(folder);
  const hostile::GuardedRun run = hostile::run_gplan_guarded(arguments, folder, c.limit_s, as_user);
  const auto after = hostile::snapshot(folder);
  hostile::make_removable(folder);
  ASSERT_EQ(hostile::entry_state("/dev/null").type, dev_null_before.type)
      << "/dev/null was replaced: the machine's device node is gone";

  const std::string err_head = run.err.substr(0, 2000);
  const std::string seen = "\n  class: " + c.kind + "\n  exit " + std::to_string(run.exit_code) +
                           " after " + std::to_string(run.seconds) + " s; stderr (" +
                           std::to_string(run.err_bytes) + " bytes): " + err_head;
  ASSERT_FALSE(run.hung) << "hang: did not end within " << c.limit_s << " s" << seen;
  ASSERT_EQ(run.signal, 0) << "crash: ended by signal " << run.signal << seen;
  if (c.max_s > 0) {
    EXPECT_LE(run.seconds, c.max_s) << "time limit not kept: " << run.seconds << " s" << seen;
  }
  EXPECT_NE(std::find(c.exit_codes.begin(), c.exit_codes.end(), run.exit_code), c.exit_codes.end())
      << "exit code " << run.exit_code << " not among those expected" << seen;

  // The message: short, naming the file or option and the key, saying what to change.
  EXPECT_LE(run.err_bytes, 8192u) << "standard error is not a few lines" << seen;
  EXPECT_LE(lines_before_usage(run.err), 6u) << "more than a few lines before the usage" << seen;
  const std::vector<std::string> lines = message_lines(run.err);
  std::string message;
  for (const std::string& line : lines) message += line + "\n";
  for (const std::string& line : lines)
    EXPECT_LE(line.size(), 1500u) << "a message line of " << line.size() << " characters" << seen;
  // A run that ends normally (0) need not say anything; one that refuses (2) or finds
  // no path (4) says why (where a case accepts either, the fragments name the refusal).
  const bool either = std::count(c.exit_codes.begin(), c.exit_codes.end(), 2) > 0;
  if (!c.message.empty() && (run.exit_code == 2 || (run.exit_code != 0 && !either))) {
    EXPECT_FALSE(lines.empty()) << "no gplan: message" << seen;
    for (const std::string& fragment : c.message) {
      EXPECT_NE(message.find(hostile::build_text(YAML::Node(fragment), folder)), std::string::npos)
          << "the message does not say '" << fragment << "'" << seen;
    }
  }
  for (const std::string& fragment : c.absent) {
    EXPECT_EQ(run.err.find(fragment), std::string::npos)
        << "the message says '" << fragment << "', which misleads" << seen;
  }
  if (run.exit_code == 2 || (c.advice && run.exit_code != 0)) {
    EXPECT_TRUE(std::regex_search(message, kAdvice))
        << "the message does not say what to change" << seen;
  }

  // Nothing changed, nothing left behind.
  const bool refused = run.exit_code != 0 && run.exit_code != 4;
  for (const auto& [name, state] : before) {
    if (contains(c.changes, name)) continue;
    const auto it = after.find(name);
    if (it == after.end()) {
      ADD_FAILURE() << "input " << name << " was removed" << seen;
    } else if (!(it->second == state)) {
      ADD_FAILURE() << "input " << name << " changed: " << describe(state) << " became "
                    << describe(it->second) << seen;
    }
  }
  for (const auto& [name, state] : after) {
    if (before.count(name)) continue;
    if (refused || !contains(c.outputs, name)) {
      ADD_FAILURE() << (refused ? "a refused run left " : "the run left ") << name << " ("
                    << describe(state) << ")" << seen;
    }
  }
  if (refused) {
    EXPECT_EQ(run.out.find("wrote "), std::string::npos) << "a refused run said it wrote" << seen;
  }
  // What outputs must not hold (unescaped text), and outputs that must read back.
  for (const auto& item : c.output_lacks) {
    const std::string name = item.first.as<std::string>();
    std::string text = name == "stdout" ? run.out : name == "stderr" ? run.err : "";
    if (name != "stdout" && name != "stderr") {
      text = testing::read_file((fs::path(folder) / name).string());
    }
    for (const YAML::Node& fragment : item.second) {
      EXPECT_EQ(text.find(fragment.as<std::string>()), std::string::npos)
          << name << " holds '" << fragment.as<std::string>() << "' unescaped" << seen;
    }
  }
  for (const std::string& name : c.output_yaml) {
    if (!fs::exists(fs::path(folder) / name)) continue;
    EXPECT_NO_THROW(YAML::LoadFile((fs::path(folder) / name).string()))
        << name << " does not read back as YAML" << seen;
  }
}

std::string case_name(const ::testing::TestParamInfo<CatalogueCase>& info) {
  return info.param.name;
}

INSTANTIATE_TEST_SUITE_P(Cases, HostileCatalogue, ::testing::ValuesIn(cases()), case_name);

TEST(HostileCatalogueFile, HoldsAtLeast150CasesCoveringEveryClass) {
  const std::vector<CatalogueCase> all = hostile::load_catalogue(catalogue_file());
  EXPECT_GE(all.size(), 150u);
  std::map<std::string, int> per_class;
  for (const CatalogueCase& c : all) ++per_class[c.kind];
  for (const char* kind : {"files destroyed", "crashes", "hangs/memory", "time limit",
                           "late or misleading errors", "silently accepted"}) {
    EXPECT_GE(per_class[kind], 5) << kind;
  }
}

}  // namespace
}  // namespace gplanner
