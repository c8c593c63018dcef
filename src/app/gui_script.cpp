#include "app/gui_script.h"

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <set>
#include <sstream>

#include "core/error.h"

namespace periflex {

namespace {

[[noreturn]] void fail(const std::string& action, const std::string& why) {
  throw InputError({"--script", 0, 0, "--script"}, "in action '" + action + "': " + why);
}

std::string trim(const std::string& s) {
  const size_t a = s.find_first_not_of(" \t\r\n");
  if (a == std::string::npos) return {};
  const size_t b = s.find_last_not_of(" \t\r\n");
  return s.substr(a, b - a + 1);
}

bool is_number(const std::string& s) {
  if (s.empty()) return false;
  char* end = nullptr;
  std::strtod(s.c_str(), &end);
  return end == s.c_str() + s.size();
}

// how many arguments each verb takes: {least, most}
struct Arity { size_t least, most; };
Arity arity(const std::string& verb) {
  static const std::set<std::string> none = {"run", "resume", "pause", "reset", "reload", "fit",
                                             "stop_record", "release", "quit"};
  static const std::set<std::string> one = {"scene", "set", "speed", "colormap", "field", "follow",
                                            "screenshot", "screenshot_ui", "wait", "expect", "inspect", "scrub"};
  if (none.count(verb)) return {0, 0};
  if (one.count(verb)) return {1, 1};
  if (verb == "step" || verb == "back") return {0, 1};
  if (verb == "history") return {1, 2};
  if (verb == "range") return {1, 2};
  if (verb == "plot") return {1, 2};
  if (verb == "cut") return {4, 4};
  if (verb == "show" || verb == "record" || verb == "grab" || verb == "drag") return {2, 2};
  return {99, 0};  // unknown
}

// checks the arguments a verb needs beyond their number
void check_arguments(const ScriptAction& a) {
  const Arity n = arity(a.verb);
  if (n.least == 99) {
    fail(a.text, "unknown verb '" + a.verb + "' (see docs/gui.md for the list)");
  }
  if (a.args.size() < n.least || a.args.size() > n.most) {
    fail(a.text, "'" + a.verb + "' takes " + std::to_string(n.least) +
                     (n.most != n.least ? " to " + std::to_string(n.most) : "") + " argument(s)");
  }
  const auto number_at = [&](size_t i) {
    if (!is_number(a.args[i])) fail(a.text, "'" + a.args[i] + "' is not a number");
  };
  if (a.verb == "step" && !a.args.empty()) {
    number_at(0);
    if (std::atol(a.args[0].c_str()) < 1) fail(a.text, "step count must be at least 1");
  }
  if (a.verb == "speed" && a.args[0] != "max") number_at(0);
  if (a.verb == "wait" || a.verb == "scrub") number_at(0);
  if (a.verb == "history") {
    for (size_t i = 0; i < a.args.size(); ++i) number_at(i);
  }
  if (a.verb == "back" && !a.args.empty()) number_at(0);
  if (a.verb == "record") number_at(1);
  if (a.verb == "grab" || a.verb == "drag") {
    number_at(0);
    number_at(1);
  }
  if (a.verb == "cut") {
    for (size_t i = 0; i < 4; ++i) number_at(i);
  }
  if (a.verb == "range" && !(a.args.size() == 1 && a.args[0] == "auto")) {
    if (a.args.size() != 2) fail(a.text, "range takes 'auto' or MIN MAX");
    number_at(0);
    number_at(1);
  }
  if (a.verb == "set" && a.args[0].find('=') == std::string::npos) fail(a.text, "set takes KEY=VALUE");
  if (a.verb == "field") {
    static const std::set<std::string> fields = {"damage", "displacement", "speed", "strain"};
    if (!fields.count(a.args[0])) fail(a.text, "field is one of damage, displacement, speed, strain");
  }
  if (a.verb == "show") {
    static const std::set<std::string> layers = {"bodies", "markers", "springs", "bonds",
                                                 "probes", "trails", "contacts", "overlay"};
    if (!layers.count(a.args[0])) {
      fail(a.text, "show takes bodies, markers, springs, bonds, probes, trails, contacts or overlay");
    }
    if (a.args[1] != "on" && a.args[1] != "off") fail(a.text, "show ... takes on or off");
  }
}

}  // namespace

std::vector<ScriptAction> parse_script(const std::string& text_or_file) {
  std::string text = text_or_file;
  // a readable file holds the script
  if (text.find('@') == std::string::npos) {
    std::ifstream in(text);
    if (!in) fail(text, "neither a readable file nor a script (actions need '@frame')");
    std::stringstream buffer;
    buffer << in.rdbuf();
    text = buffer.str();
  }

  // comments out, then split on ';' and new lines
  std::string cleaned;
  bool comment = false;
  for (char ch : text) {
    if (ch == '#') comment = true;
    if (ch == '\n') comment = false;
    if (!comment) cleaned += (ch == '\n' ? ';' : ch);
  }
  std::vector<ScriptAction> actions;
  std::stringstream parts(cleaned);
  std::string part;
  while (std::getline(parts, part, ';')) {
    part = trim(part);
    if (part.empty()) continue;
    ScriptAction a;
    a.text = part;
    const size_t at = part.rfind('@');
    if (at == std::string::npos) fail(part, "missing '@frame'");
    const std::string frame = trim(part.substr(at + 1));
    if (!is_number(frame) || frame.find_first_not_of("0123456789") != std::string::npos) {
      fail(part, "'" + frame + "' after '@' is not a frame number");
    }
    a.frame = std::atol(frame.c_str());
    std::stringstream words(part.substr(0, at));
    words >> a.verb;
    for (std::string w; words >> w;) a.args.push_back(w);
    check_arguments(a);
    actions.push_back(std::move(a));
  }
  // by frame, keeping the written order within a frame
  std::stable_sort(actions.begin(), actions.end(),
                   [](const ScriptAction& x, const ScriptAction& y) { return x.frame < y.frame; });
  return actions;
}

}  // namespace periflex
