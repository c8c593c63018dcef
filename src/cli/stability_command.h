// `periflex stability [--quick] [--out DIR]`: runs the stability suite (stiff, extreme and long
// cases, each in its own child process) and prints and writes the table of outcomes.
#pragma once

#include <string>
#include <vector>

namespace periflex {

struct StabilityOptions {
  bool quick = false;                 // only the fast cases (those ctest runs)
  std::string out_dir = "out/stability";  // stability.md, stability.csv, one directory per case
  std::vector<std::string> cases;     // run only cases whose name contains one of these
  bool list = false;                  // print the cases and exit
  int threads = 1;                    // OpenMP threads of each case
  std::string program;                // the periflex run for each case; empty: this program
};

// Runs the suite. Returns 0 when every case behaved as expected, 1 otherwise.
int stability_command(const StabilityOptions& options);

}  // namespace periflex
