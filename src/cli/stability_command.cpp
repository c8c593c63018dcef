#include "cli/stability_command.h"

#include <unistd.h>

#include <cstdio>
#include <filesystem>

#include "cli/interrupt.h"
#include "core/error.h"
#include "io/child_process.h"
#include "scene/scene_budget.h"
#include "stability/stability_suite.h"

namespace periflex {

int stability_command(const StabilityOptions& options) {
  // the cases to run
  std::vector<StabilityCase> cases;
  for (const auto& c : stability_cases()) {
    if (options.quick && !c.quick) continue;
    bool wanted = options.cases.empty();
    for (const auto& text : options.cases) wanted |= c.name.find(text) != std::string::npos;
    if (wanted) cases.push_back(c);
  }
  if (options.list) {
    for (const auto& c : cases) {
      std::printf("%-40s %-15s %-18s %s%s\n", c.name.c_str(), c.group.c_str(), expectation_name(c.expect),
                  c.description.c_str(), c.quick ? " [quick]" : "");
    }
    return kExitOk;
  }
  if (cases.empty()) throw InputError({"command line", 0, 0, "--case"}, "no stability case matches");

  // what every case would refuse, refused once here: a program that cannot run, more threads
  // than a run takes on this machine
  SuiteOptions suite;
  suite.program = options.program.empty() ? current_executable() : options.program;
  if (::access(suite.program.c_str(), X_OK) != 0 || std::filesystem::is_directory(suite.program))
    throw InputError({"command line", 0, 0, "--program"}, "'" + suite.program + "' is not a program this user can run");
  if (options.threads > thread_cap(LimitsDef{}))
    throw InputError({"command line", 0, 0, "--threads"},
                     "asks for " + std::to_string(options.threads) + " threads, more than a run takes here (" +
                         std::to_string(thread_cap(LimitsDef{})) + ", 4 x the cores of this machine)");
  suite.out_dir = options.out_dir;
  suite.threads = options.threads;
  // Ctrl-C or SIGTERM: the case under way is told to stop, no further case starts, and the
  // table holds the cases that ended
  catch_interrupts();
  suite.interrupt = [] { return pending_interrupt(); };

  // one line per case as it finishes, then the table
  std::vector<CaseResult> results;
  int failures = 0;
  for (size_t k = 0; k < cases.size() && pending_interrupt() == 0; ++k) {
    std::printf("[%2zu/%zu] %-40s ", k + 1, cases.size(), cases[k].name.c_str());
    std::fflush(stdout);
    CaseResult r = run_stability_case(cases[k], suite);
    if (pending_interrupt() != 0) {
      std::printf("interrupted\n");
      break;
    }
    std::printf("%-9s %6.2f s  %s%s\n", r.outcome.c_str(), r.run_seconds, r.as_expected ? "ok" : "NOT AS EXPECTED",
                r.verdict.empty() ? "" : (": " + r.verdict).c_str());
    std::fflush(stdout);
    failures += r.as_expected ? 0 : 1;
    results.push_back(std::move(r));
  }
  const std::string title = options.quick ? "Stability suite (quick)" : "Stability suite (full)";
  write_stability_table(results, options.out_dir, title);
  std::printf("\n%s\n", stability_table_markdown(results).c_str());
  std::printf("%zu cases, %d not as expected; table in %s/stability.md and stability.csv\n", results.size(), failures,
              options.out_dir.c_str());
  if (const int signal_number = pending_interrupt()) {
    std::fprintf(stderr, "periflex: stability suite interrupted by %s after %zu of %zu cases\n",
                 interrupt_name(signal_number), results.size(), cases.size());
    return interrupt_exit_code(signal_number);
  }
  return failures == 0 ? kExitOk : kExitOther;
}

}  // namespace periflex
