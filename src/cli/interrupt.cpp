#include "cli/interrupt.h"

#include <csignal>

namespace periflex {

namespace {

volatile std::sig_atomic_t g_signal = 0;

extern "C" void on_interrupt(int signal_number) { g_signal = signal_number; }

}  // namespace

void catch_interrupts() {
  g_signal = 0;
  // SA_RESETHAND: the handler runs once, then the default action is back, so a second Ctrl-C
  // stops a run whose clean end takes too long
  struct sigaction action {};
  action.sa_handler = on_interrupt;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESETHAND | SA_RESTART;
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
  // a closed terminal (SIGHUP) stops the run the same way, unless the run was started to outlive
  // its terminal (nohup, or a shell's `trap '' HUP`), which leaves the signal ignored
  struct sigaction hangup {};
  if (sigaction(SIGHUP, nullptr, &hangup) == 0 && hangup.sa_handler != SIG_IGN) sigaction(SIGHUP, &action, nullptr);
}

int pending_interrupt() { return g_signal; }

int interrupt_exit_code(int signal_number) { return 128 + signal_number; }

const char* interrupt_name(int signal_number) {
  return signal_number == SIGINT ? "SIGINT" : signal_number == SIGHUP ? "SIGHUP" : "SIGTERM";
}

}  // namespace periflex
