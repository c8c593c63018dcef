// JSON read by the tests (summary.json, run.json, the program's --json output). The parser is
// compiled once, in json_text.cpp: instantiated in each of the fifteen test files that read a
// summary it cost about 4 s of processor time per file in a Release build and 8 s under ASan.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

namespace periflex::testing {

// The document in `text`; throws nlohmann::json::parse_error when it is not JSON.
nlohmann::json parse_json(const std::string& text);

// The document in the file at `path`; a discarded value (is_discarded()) when the file is
// missing or not JSON.
nlohmann::json read_json_file(const std::filesystem::path& path);

}  // namespace periflex::testing
