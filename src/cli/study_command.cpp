#include "cli/study_command.h"

#include <cstdio>

#include "cli/interrupt.h"
#include "core/error.h"
#include "study/refine_study.h"
#include "study/study_def.h"
#include "study/study_report.h"
#include "study/study_runner.h"

namespace periflex {

int study_command(const StudyOptions& options) {
  try {
    StudyDef study = load_study(options.study_path);
    if (options.repeats > 0) study.repeats = options.repeats;
    const std::string out_dir = options.out_dir.empty() ? "out/study-" + study.name : options.out_dir;
    const StudyLog log = [&](const std::string& line) {
      if (!options.quiet) std::printf("  %s\n", line.c_str());
      std::fflush(stdout);
    };
    if (!options.quiet) std::printf("study %s\n", study.name.c_str());
    // Ctrl-C, SIGTERM or a closed terminal: the run under way is dropped, and what finished is
    // written and marked as stopped
    catch_interrupts();
    const StudyStop stop = [] { return pending_interrupt() != 0; };
    StudyResult result;
    try {
      result = study.mode == StudyDef::Mode::kRefine ? run_refine_study(study, log, stop) : run_study(study, log, stop);
    } catch (const StudyStopped& stopped) {
      const int signal_number = pending_interrupt();
      std::fprintf(stderr, "periflex: study %s interrupted by %s during its reference run (%s): nothing written\n",
                   study.name.c_str(), interrupt_name(signal_number), stopped.what());
      return interrupt_exit_code(signal_number);
    }
    const StudyOutputs outputs = write_study_outputs(result, out_dir);
    std::printf("wrote %s\nwrote %s\n", outputs.csv_path.c_str(), outputs.markdown_path.c_str());
    if (!outputs.plot_path.empty()) std::printf("wrote %s\n", outputs.plot_path.c_str());
    else std::printf("%s\n", outputs.plot_message.c_str());
    if (!outputs.energy_plot_path.empty()) std::printf("wrote %s\n", outputs.energy_plot_path.c_str());
    if (result.stopped) {
      const int signal_number = pending_interrupt();
      std::fprintf(stderr, "periflex: study %s interrupted by %s: %zu runs finished, written above\n",
                   study.name.c_str(), interrupt_name(signal_number), result.rows.size());
      return interrupt_exit_code(signal_number);
    }
    return kExitOk;
  } catch (const InputError& error) {
    std::fprintf(stderr, "periflex: error: %s\n", error.what());
    return kExitBadInput;
  } catch (const NumericalError& error) {
    std::fprintf(stderr, "periflex: numerical failure: %s\n", error.what());
    return kExitNumerical;
  } catch (const std::exception& error) {
    std::fprintf(stderr, "periflex: error: %s\n", error.what());
    return kExitOther;
  }
}

}  // namespace periflex
