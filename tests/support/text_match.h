// Regular expressions over the program's output (ECMAScript grammar, as std::regex's default).
// The matcher is compiled once, in text_match.cpp: std::regex instantiated in a test file cost
// about 4.5 s of processor time in a Release build and 12 s under ASan, per file.
#pragma once

#include <string>
#include <vector>

namespace periflex::testing {

// Whether `pattern` matches somewhere in `text`.
bool contains_match(const std::string& text, const std::string& pattern);

// The first match of `pattern` in `text`: the whole match, then each group; empty when none.
std::vector<std::string> first_match(const std::string& text, const std::string& pattern);

// Every match of `pattern` in `text` (whole matches, in order, not overlapping).
std::vector<std::string> all_matches(const std::string& text, const std::string& pattern);

}  // namespace periflex::testing
