// Ctrl-C, kill and a closed terminal during a run: the first SIGINT, SIGTERM or SIGHUP only
// raises a flag, which the run loop reads between steps to finish cleanly (rows, frames, movie
// and summary.json closed and true); a second one ends the program at once. A SIGHUP that was
// ignored when the program started (nohup) stays ignored.
#pragma once

namespace periflex {

// Installs the handlers (once per process; later calls only clear the flag).
void catch_interrupts();
// The signal that asked the run to stop (SIGINT, SIGTERM or SIGHUP), or 0.
int pending_interrupt();
// The conventional exit status after a signal: 128 + its number (130 for SIGINT, 143 for SIGTERM,
// 129 for SIGHUP).
int interrupt_exit_code(int signal_number);
// The signal's name for messages: "SIGINT", "SIGTERM" or "SIGHUP".
const char* interrupt_name(int signal_number);

}  // namespace periflex
