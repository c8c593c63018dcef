#include "app/sim_command.h"

#include <cmath>
#include <cstdlib>

namespace periflex {

namespace {

// strict number parse: the whole text must be a finite number
bool parse_number(const std::string& text, double& out) {
  if (text.empty()) return false;
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (end != text.c_str() + text.size() || !std::isfinite(v)) return false;
  out = v;
  return true;
}

bool parse_bool(const std::string& text, bool& out) {
  if (text == "on" || text == "true" || text == "1" || text == "yes") return out = true, true;
  if (text == "off" || text == "false" || text == "0" || text == "no") return out = false, true;
  return false;
}

}  // namespace

bool same_live_settings(const LiveSettings& a, const LiveSettings& b) {
  return a.integrator == b.integrator && a.dt == b.dt && a.correction.method == b.correction.method &&
         a.correction.alpha == b.correction.alpha && a.correction.beta == b.correction.beta &&
         a.correction.tolerance == b.correction.tolerance &&
         a.correction.max_iterations == b.correction.max_iterations && a.bond_damping == b.bond_damping &&
         a.global_damping == b.global_damping && a.fracture == b.fracture && a.allow_unstable == b.allow_unstable;
}

const char* live_parameter_keys() {
  return "dt, integrator, bond_damping, global_damping, fracture, correction, alpha, beta, tolerance, "
         "max_iterations";
}

std::string set_live_parameter(LiveSettings& settings, const std::string& key, const std::string& value) {
  LiveSettings s = settings;
  double number = 0.0;
  const bool numeric = parse_number(value, number);
  // keys with text values first
  if (key == "integrator") {
    if (value.empty()) return "integrator needs a name";
    s.integrator = value;
  } else if (key == "fracture") {
    if (!parse_bool(value, s.fracture)) return "fracture takes on or off, not '" + value + "'";
  } else if (key == "correction") {
    if (value == "none") s.correction.method = CorrectionDef::Method::kNone;
    else if (value == "baumgarte") s.correction.method = CorrectionDef::Method::kBaumgarte;
    else if (value == "projection") s.correction.method = CorrectionDef::Method::kProjection;
    else return "correction takes none, baumgarte or projection, not '" + value + "'";
  } else if (key == "dt" || key == "bond_damping" || key == "global_damping" || key == "alpha" ||
             key == "beta" || key == "tolerance" || key == "max_iterations") {
    // numeric keys: all must be finite and non-negative, dt and tolerance positive
    if (!numeric) return key + " needs a number, not '" + value + "'";
    if (number < 0.0) return key + " must not be negative";
    if ((key == "dt" || key == "tolerance") && number <= 0.0) return key + " must be positive";
    if (key == "dt") s.dt = number;
    else if (key == "bond_damping") s.bond_damping = number;
    else if (key == "global_damping") s.global_damping = number;
    else if (key == "alpha") s.correction.alpha = number;
    else if (key == "beta") s.correction.beta = number;
    else if (key == "tolerance") s.correction.tolerance = number;
    else s.correction.max_iterations = static_cast<int>(number);
  } else {
    return "unknown live setting '" + key + "' (known: " + live_parameter_keys() + ")";
  }
  settings = s;
  return {};
}

}  // namespace periflex
