// What the tests of the program on the GPU share: whether a compute context can be made here, and
// two runs' rows compared.
#pragma once

#include <filesystem>
#include <string>

#include "../cli/run_output_files.h"
#include "../cli/run_program.h"
#include "core/resources.h"
#include "gpu/gl_compute_context.h"

namespace periflex::testing {

// Why no compute context can be made here (empty: one can).
inline const std::string& compute_unavailable() {
  static const std::string why = [] {
    try {
      GlComputeContext probe(find_resource_root());
      return std::string();
    } catch (const std::exception& e) {
      return std::string(e.what());
    }
  }();
  return why;
}

#define REQUIRE_PROGRAM_COMPUTE_CONTEXT() \
  if (!compute_unavailable().empty()) GTEST_SKIP() << "no OpenGL compute context here: " << compute_unavailable()

// `periflex ARGUMENTS` with `environment` (VAR=value ...) before it in the shell.
inline ProgramResult run_periflex_with(const std::string& environment, const std::string& arguments) {
  return run_periflex_command(environment + " " + PERIFLEX_BINARY + " " + arguments);
}

// Whether two runs' series.csv hold the same rows bit for bit, the machine's speed left out.
inline bool same_rows(const Series& a, const Series& b) {
  if (a.columns != b.columns || a.rows.size() != b.rows.size()) return false;
  const int speed = a.find_column("steps_per_second");
  for (size_t r = 0; r < a.rows.size(); ++r)
    for (size_t c = 0; c < a.columns.size(); ++c)
      if (static_cast<int>(c) != speed && a.rows[r][c] != b.rows[r][c]) return false;
  return true;
}

}  // namespace periflex::testing
