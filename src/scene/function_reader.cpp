#include "scene/function_reader.h"

namespace periflex {

TimeFunction read_time_function(const ReadContext& context, const toml::node& node, const std::string& key) {
  // every number of a function is bounded like a length: a rate of 1e300 is no motion a solver can follow
  // a plain number is a constant
  if (node.is_number()) return TimeFunction::constant(read_number(context, node, key, Sign::kAny, true));
  const auto* table = node.as_table();
  if (table == nullptr)
    context.fail(&node, key, "expected a function (a number or an inline table with a type), found " +
                 describe_type(node));

  TableReader in(context, *table, key, "function '" + key + "'");
  const std::string type = in.required_choice("type", {"constant", "rate", "polynomial", "harmonic", "table"});
  TimeFunction f;
  if (type == "constant") {
    // f = value
    f = TimeFunction::constant(in.required_number("value", Sign::kAny, true));
  } else if (type == "rate") {
    // f = value + rate t
    const double value = in.number("value", 0.0, Sign::kAny, true);
    f = TimeFunction::linear(value, in.required_number("rate", Sign::kAny, true));
  } else if (type == "polynomial") {
    // f = sum c_k t^k
    f.kind = TimeFunction::Kind::kPolynomial;
    const toml::node* coefficients = in.node("coefficients");
    if (coefficients == nullptr) in.fail_missing("coefficients");
    f.coefficients = read_number_list(context, *coefficients, in.key_path("coefficients"), true);
    if (f.coefficients.empty()) in.fail("coefficients", "a polynomial needs at least one coefficient");
  } else if (type == "harmonic") {
    // f = offset + amplitude sin(omega t + phase)
    f.kind = TimeFunction::Kind::kHarmonic;
    f.offset = in.number("offset", 0.0, Sign::kAny, true);
    f.amplitude = in.required_number("amplitude", Sign::kAny, true);
    f.omega = in.required_number("omega", Sign::kAny, true);
    f.phase = in.number("phase", 0.0, Sign::kAny, true);
  } else {
    // piecewise linear through (times[k], values[k])
    f.kind = TimeFunction::Kind::kTable;
    const toml::node* times = in.node("times");
    const toml::node* values = in.node("values");
    if (times == nullptr) in.fail_missing("times");
    if (values == nullptr) in.fail_missing("values");
    f.times = read_number_list(context, *times, in.key_path("times"), true);
    f.values = read_number_list(context, *values, in.key_path("values"), true);
    if (f.times.empty()) in.fail("times", "a table function needs at least one point");
    if (f.times.size() != f.values.size())
      in.fail("values", "a table function needs as many values as times (" + std::to_string(f.times.size()) +
              " times, " + std::to_string(f.values.size()) + " values)");
    // interpolation needs strictly increasing times
    const auto& list = *times->as_array();
    for (size_t k = 1; k < f.times.size(); ++k)
      if (!(f.times[k] > f.times[k - 1]))
        context.fail(list.get(k), in.key_path("times"),
                     "times must strictly increase, but times[" + std::to_string(k) + "] = " +
                     format_number(f.times[k]) + " follows " + format_number(f.times[k - 1]));
  }
  in.finish({"value", "rate", "coefficients", "offset", "amplitude", "omega", "phase", "times", "values"},
            "a '" + type + "' function");
  return f;
}

}  // namespace periflex
