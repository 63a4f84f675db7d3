#include "interruption.h"

#include <signal.h>
#include <string.h>

#include <csignal>
#include <iostream>

#include "gplanner/planner/output/text_escaping.h"

namespace gplan {
namespace {

volatile std::sig_atomic_t received_signal = 0;

extern "C" void record_signal(int signal_number) { received_signal = signal_number; }

std::string joined(const std::vector<std::string>& items) {
  std::string text;
  for (std::size_t i = 0; i < items.size(); ++i) {
    text += (i == 0 ? "" : i + 1 == items.size() ? " and " : ", ") + items[i];
  }
  return text;
}

}  // namespace

void catch_interruptions() {
  struct sigaction action {};
  action.sa_handler = record_signal;
  sigemptyset(&action.sa_mask);
  // The first signal asks the run to stop; the handler is then reset, so that a second
  // one ends a run that does not stop in time. SA_RESTART: a write to the terminal the
  // signal comes in the middle of goes on (else the stream would fail and later lines,
  // the "interrupted" one among them, be lost).
  action.sa_flags = SA_RESETHAND | SA_RESTART;
  // SIGHUP (the terminal closed, an ssh session dropped) as SIGTERM: no output half written.
  for (const int signal_number : {SIGINT, SIGTERM, SIGHUP}) {
    // A signal ignored on entry (a background job of a script, for SIGINT; nohup, for
    // SIGHUP) stays ignored.
    struct sigaction previous {};
    if (sigaction(signal_number, nullptr, &previous) == 0 && previous.sa_handler == SIG_IGN)
      continue;
    sigaction(signal_number, &action, nullptr);
  }
}

bool interrupted() { return received_signal != 0; }

int report_interruption(const std::vector<std::string>& written,
                        const std::vector<std::string>& left) {
  const int signal_number = received_signal;
  const char* name = signal_number == SIGINT   ? "SIGINT"
                     : signal_number == SIGHUP ? "SIGHUP"
                                               : "SIGTERM";
  std::string line = std::string("gplan: interrupted by ") + name + "; ";
  if (written.empty()) {
    line += "nothing written";
  } else {
    line += "wrote " + joined(written) + " before it";
  }
  if (!left.empty()) {
    line += "; " + joined(left) + (left.size() == 1 ? " left as it was" : " left as they were");
  }
  std::cerr << gplanner::terminal_text(line) << "\n";
  return 128 + signal_number;
}

}  // namespace gplan
