// Ctrl-C and kill during a run: the first SIGINT or SIGTERM only raises a flag, which the run
// loop reads between steps to finish cleanly (rows, frames, movie and summary.json closed and
// true); a second one ends the program at once.
#pragma once

namespace periflex {

// Installs the handlers (once per process; later calls only clear the flag).
void catch_interrupts();
// The signal that asked the run to stop (SIGINT or SIGTERM), or 0.
int pending_interrupt();
// The conventional exit status after a signal: 128 + its number (130 for SIGINT, 143 for SIGTERM).
int interrupt_exit_code(int signal_number);
// The signal's name for messages: "SIGINT" or "SIGTERM".
const char* interrupt_name(int signal_number);

}  // namespace periflex
